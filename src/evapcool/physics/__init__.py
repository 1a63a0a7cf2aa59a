"""The model: exact event-driven hard disks in a parabolic cup (NumPy/Numba, no pygame)."""
