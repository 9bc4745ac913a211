"""A scene's gas network: cavities joined by exchanges (:mod:`exchange.network.vent`), their activation rules
(:mod:`exchange.network.activation`), the unknowns' layout and the discrete state (:mod:`exchange.network.network`,
:mod:`exchange.network.discrete_state`), and how it lowers onto the engine (:mod:`exchange.network.lowering`)."""
