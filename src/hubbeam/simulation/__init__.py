"""Running the models: single simulations through the numba kernels, sweeps over speeds and
parameters, and the plain-Python reference integration they are checked against."""
