"""Seals that leak by contact pressure: gas flow through the interface gap of a seal (docs/seals.md).

* :mod:`~exchange.seal.gap_laws`, :mod:`~exchange.seal.hysteresis`: the channel height h(p) of a rough contact;
* :mod:`~exchange.seal.channel`: the channel height of every seal node from its contact state;
* :mod:`~exchange.seal.film`, :mod:`~exchange.seal.reynolds`: the compressible Reynolds film on the seal mesh;
* :mod:`~exchange.seal.percolation`: whether a leak path joins the edges (exact);
* :mod:`~exchange.seal.conductance`: the seal's conductance as a function of the flange's displacement, built
  once for the engine, with the exact closure displacement.
"""
