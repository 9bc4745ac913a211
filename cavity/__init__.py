"""Gas cavities: species and mixtures, real gas and walls, volumes, inflators, the cavity's energy balance and the
integrator. Importing it installs ventsim's numba cache locator (:mod:`cavity.kernel_cache`)."""
from .kernel_cache import install as _install_kernel_cache

_install_kernel_cache()
