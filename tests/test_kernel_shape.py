"""The shape of the jitted core, read from its source with ``ast``.

* every kernel (a function decorated by one of ``hubbeam.core.jit``'s decorators) takes at most
  ``MAX_ARGUMENTS`` arguments, as its source states them (``test_core_arguments`` checks the
  imported functions): more travel in the named tuples of ``hubbeam.core.inputs``, where numba
  would not notice two swapped floats among a dozen;
* the torque a free hub receives, the drive's law applied to the shaped command, is written once
  (``hubbeam.core.drive.free_hub_torque``), so that every kernel gives the hub the same torque.
"""

import ast
from pathlib import Path

from test_core_arguments import MAX_ARGUMENTS

import hubbeam.core
from hubbeam.core import jit

CORE = Path(hubbeam.core.__file__).parent
#: the decorators of ``hubbeam.core.jit`` that compile a kernel
DECORATORS = {"kernel", "borrowing_kernel", "internal_kernel", "inline_kernel"}


def _trees():
    return {path.name: ast.parse(path.read_text(encoding="utf-8")) for path in sorted(CORE.glob("*.py"))}


def _name(node):
    """The name a decorator or a called function is spelled with (``kernel``, ``jit.kernel``)."""
    if isinstance(node, ast.Call):
        node = node.func
    if isinstance(node, ast.Attribute):
        return node.attr
    return getattr(node, "id", None)


def _kernels():
    for module, tree in _trees().items():
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef) and DECORATORS & {_name(d) for d in node.decorator_list}:
                yield module, node


def _parameters(function):
    args = function.args
    return (len(args.posonlyargs) + len(args.args) + len(args.kwonlyargs) + (args.vararg is not None)
            + (args.kwarg is not None))


def test_the_decorators_are_those_of_the_jit_module():
    assert all(callable(getattr(jit, name)) for name in DECORATORS)


def test_every_kernel_takes_at_most_eight_arguments():
    kernels = list(_kernels())
    assert len(kernels) > 100  # the decorators were recognised
    wide = [f"{module}: {node.name} ({_parameters(node)})" for module, node in kernels
            if _parameters(node) > MAX_ARGUMENTS]
    assert not wide, f"kernels with more than {MAX_ARGUMENTS} arguments: {wide}"


def test_the_drive_s_torque_on_the_shaped_command_is_written_once():
    sites = [(module, node) for module, tree in _trees().items() for node in ast.walk(tree)
             if isinstance(node, ast.Call) and _name(node) == "drive_torque"]
    assert len(sites) == 1, [f"{module}:{node.lineno}" for module, node in sites]
    module, call = sites[0]
    assert module == "drive.py"
    assert _name(call.args[1]) == "shaped_torque"  # the command is the shaped one
