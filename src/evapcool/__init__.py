"""evapcool: evaporative cooling of atoms in a cup, exact and event-driven."""

from evapcool.about import __version__
from evapcool.physics.simulation import Simulation

__all__ = ["Simulation", "__version__"]
