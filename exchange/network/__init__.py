"""A scene's gas network: cavities joined by exchanges (:mod:`exchange.network.vent`), their activation rules, the
unknowns' layout and the discrete state, and how it lowers onto the engine."""
from .network import LEDGER_PER_CAVITY, LEDGER_PER_EXCHANGE, DiscreteState, Network

__all__ = ["Network", "DiscreteState", "LEDGER_PER_EXCHANGE", "LEDGER_PER_CAVITY"]
