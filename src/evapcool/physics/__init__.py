"""The model: exact event-driven hard disks in a parabolic cup (NumPy, the compiled core)."""
