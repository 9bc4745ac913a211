"""Flow laws: each a module with its pure law (a numba function Python calls too), its law object, its engine kernel
and its scene keys; :mod:`exchange.laws.registry` lists them."""
from .bulk_viscosity import BulkViscosityLaw
from .fabric import FabricLeakageLaw
from .flux import FluxLaw
from .graefe import GraefeLaw
from .leakage_table import LeakageTableLaw
from .linear_resistance import LinearResistanceLaw
from .orifice import OrificeLaw

__all__ = ["OrificeLaw", "FabricLeakageLaw", "GraefeLaw", "LeakageTableLaw", "FluxLaw", "BulkViscosityLaw",
           "LinearResistanceLaw"]
