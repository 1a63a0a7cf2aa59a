"""evapcool: evaporative cooling of atoms in a cup, exact and event-driven."""

from evapcool.physics.simulation import Simulation

__version__ = "0.1.0"
__all__ = ["Simulation", "__version__"]
