"""Game rules on top of the physics: pause, speed, restart, score. No pygame here."""
