"""Exchanges between cavities and their surroundings: the flow laws (:mod:`exchange.laws`), activation, contact, the
network of a scene (:mod:`exchange.network`), the engine that integrates it (:mod:`exchange.engine`) and its results
read back (:mod:`exchange.readback`)."""
import cavity as _cavity  # noqa: F401  (numba's cache locator before any kernel here is made)
