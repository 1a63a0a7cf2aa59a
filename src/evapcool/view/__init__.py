"""Drawing with pygame: reusable widgets, icons, atom sprites and the applet's scene."""
