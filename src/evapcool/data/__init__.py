"""Package data: the demo autopilot strategy."""
