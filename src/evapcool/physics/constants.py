"""The original applet's physical constants (SPEC section 1); the screen is the view's
(view/screen.py).

Below both the simulation and the state file (physics/state.py), which read them.
"""

from __future__ import annotations

# The original applet's constants (SPEC section 1) are the core's (core/evapcool_core.h).
from evapcool.physics.model import (
    ATOM_RADIUS,
    CURVATURE,
    FPS,
    GRAVITY,
    N_ATOMS,
    TC_EXPONENT_CUP,
    TC_EXPONENT_SEED,
    TRAP_HEIGHT,
)

__all__ = [
    "ATOM_RADIUS",
    "CURVATURE",
    "FPS",
    "GRAVITY",
    "N_ATOMS",
    "TC_EXPONENT_CUP",
    "TC_EXPONENT_SEED",
    "TC_LAWS",
    "TRAP_HEIGHT",
]

#: The Tc laws by name (game settings, the lab's --tc-law): name -> exponent p in Tc ~ N^p.
TC_LAWS: dict[str, float] = {"seed": TC_EXPONENT_SEED, "cup": TC_EXPONENT_CUP}
