"""Game rules on top of the physics: pause, speed, restart, score. No pygame here."""

from evapcool.game.rules import (
    HEIGHT_MAX,
    HEIGHT_MIN,
    HEIGHT_START,
    SPEED_MAX,
    SPEED_MIN,
    Game,
    GameConfig,
)

__all__ = [
    "HEIGHT_MAX",
    "HEIGHT_MIN",
    "HEIGHT_START",
    "SPEED_MAX",
    "SPEED_MIN",
    "Game",
    "GameConfig",
]
