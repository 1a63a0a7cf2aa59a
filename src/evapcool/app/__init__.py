"""The playable applet: window, main loop and command line (pygame lives here and in view)."""
