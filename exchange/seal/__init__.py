"""Seals that leak by contact pressure: gas flow through the interface gap of a seal (docs/seals.md).

* :mod:`~exchange.seal.gap_laws`, :mod:`~exchange.seal.hysteresis`: the channel height h(p) of a rough contact;
* :mod:`~exchange.seal.channel`: the channel height of every seal node from its contact state;
* :mod:`~exchange.seal.film`, :mod:`~exchange.seal.reynolds`: the compressible Reynolds film on the seal mesh;
* :mod:`~exchange.seal.percolation`: whether a leak path joins the edges (exact);
* :mod:`~exchange.seal.conductance`, :mod:`~exchange.seal.load_paths`: the seal's conductance as a function of
  the flange's displacement (or a held flange's reaction), built once, with the exact closure load;
* :mod:`~exchange.seal.kernels`: what the engine evaluates per right-hand side (compiled);
* :mod:`~exchange.seal.flange`: leak onset and lift-off pressures of a preloaded flange;
* :mod:`~exchange.seal.spec`, :mod:`~exchange.seal.setup`: a scene's seal exchange, its law built once with its
  flange (the law and its engine kernel: :mod:`exchange.laws.seal`);
* :mod:`~exchange.seal.outputs`, :mod:`~exchange.seal.leak_fit`, :mod:`~exchange.seal.viscosity`,
  :mod:`~exchange.seal.meshes`: outputs and picture, calibration on a measured curve, gas properties, test meshes.
"""
