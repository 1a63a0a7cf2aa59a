"""The original applet's constants and where its cup sits on the screen (SPEC section 1).

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
WINDOW = (640, 672)
BORDER_LEFT, BORDER_RIGHT, BORDER_TOP, BORDER_BOTTOM = 48, 96, 48, 96
CUP_DROP = 32  # px between the drawn cup bottom and the play-area bottom
TC_EXPONENT_SEED = 2.0 / 3.0  # seed Eq. (46), the 3D-box law
TC_EXPONENT_CUP = 2.0 / 5.0  # ideal Bose gas with g(E) ~ E^(3/2) (SPEC 4)
#: The Tc laws by name (game settings, the lab's --tc-law): name -> exponent p in Tc ~ N^p.
TC_LAWS: dict[str, float] = {"seed": TC_EXPONENT_SEED, "cup": TC_EXPONENT_CUP}


def cup_vertex(window: tuple[int, int]) -> tuple[float, float]:
    """Screen position of the drawn cup's lowest point: (296, 544) in 640 x 672."""
    w, h = window
    play_w = w - BORDER_LEFT - BORDER_RIGHT
    return BORDER_LEFT + play_w / 2.0, float(h - BORDER_BOTTOM - CUP_DROP)
