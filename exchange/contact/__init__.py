"""Normal contact of a rigid body with a seat: the pressure-overclosure and damping laws as numba kernels
(:mod:`exchange.contact.laws`, the ones the engine runs) and their definitions and Python API
(:mod:`exchange.contact.definitions`: CPRESS at a node, suggested damping)."""
from .advice import suggest_mu0, suggest_mu0_euler_column
from .definitions import (ContactDamping, Hard, LinearPenalty, Softened, contact_stiffness, cpress,
                          critical_damping_coefficient, damping_coefficient, damping_pressure,
                          default_critical_fraction, hard_contact_pressure, overclosure_pressure)

__all__ = ["ContactDamping", "Hard", "LinearPenalty", "Softened", "contact_stiffness", "cpress",
           "critical_damping_coefficient", "damping_coefficient", "damping_pressure", "default_critical_fraction",
           "hard_contact_pressure", "overclosure_pressure", "suggest_mu0", "suggest_mu0_euler_column"]
