"""The compiled kernels (numba) and their loader; nothing else in img2logo imports numba."""
