"""The original applet's physical constants (SPEC section 1); the screen is the view's
(view/screen.py).

Below both the simulation and the state file (physics/state.py), which read them.
"""

from __future__ import annotations

#: The original applet's constants (SPEC section 1).
FPS = 30
GRAVITY = 10.0 / 30.0  # px / frame^2
CURVATURE = 0.01  # per px
ATOM_RADIUS = 12.0
N_ATOMS = 49
TRAP_HEIGHT = 400.0
TC_EXPONENT_SEED = 2.0 / 3.0  # seed Eq. (46), the 3D-box law
TC_EXPONENT_CUP = 2.0 / 5.0  # ideal Bose gas with g(E) ~ E^(3/2) (SPEC 4)
#: The Tc laws by name (game settings, the lab's --tc-law): name -> exponent p in Tc ~ N^p.
TC_LAWS: dict[str, float] = {"seed": TC_EXPONENT_SEED, "cup": TC_EXPONENT_CUP}
