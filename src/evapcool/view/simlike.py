"""What the view reads from a `Simulation` (panels, condensate): one protocol, so a test's
stand-in and the real model answer the same questions."""

from __future__ import annotations

from typing import Protocol

import numpy as np


class SimLike(Protocol):
    """The parts of `evapcool.Simulation` the view reads."""

    n_atoms: int
    n_trapped: int
    temperature: float
    initial_temperature: float
    critical_temperature: float
    tc_exponent: float
    trap_height: float
    gravity: float
    curvature: float
    won: bool

    @property
    def radii(self) -> np.ndarray: ...

    @property
    def velocities(self) -> np.ndarray: ...

    @property
    def masses(self) -> np.ndarray: ...

    def energies(self) -> np.ndarray: ...
