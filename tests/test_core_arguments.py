"""Every function of the jitted core takes at most :data:`MAX_ARGUMENTS` arguments.

Numba checks types, not meanings: among a dozen positional floats two swapped ones compile and run.
The core passes grouped values instead (``hubbeam.core.inputs``: the model traits and problem
inputs, the integrator settings, states and trajectories), so no entry point needs many.
"""

import importlib
import inspect
import pkgutil

from numba.core.dispatcher import Dispatcher

import hubbeam.core

MAX_ARGUMENTS = 8


def core_functions():
    """``(qualified name, function)`` of every function defined in a module of hubbeam.core,
    jitted (its Python source) or not."""
    for info in pkgutil.iter_modules(hubbeam.core.__path__):
        module = importlib.import_module(f"hubbeam.core.{info.name}")
        for name, value in vars(module).items():
            function = value.py_func if isinstance(value, Dispatcher) else value
            if inspect.isfunction(function) and function.__module__ == module.__name__:
                yield f"{module.__name__}.{name}", function


def test_core_functions_take_at_most_eight_arguments():
    functions = dict(core_functions())
    assert "hubbeam.core.radau.radau5" in functions and "hubbeam.core.integrate.simulate_kernel" in functions
    many = {name: len(inspect.signature(function).parameters) for name, function in functions.items()
            if len(inspect.signature(function).parameters) > MAX_ARGUMENTS}
    assert not many
