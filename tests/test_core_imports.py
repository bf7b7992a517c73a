"""The jitted core stands alone: it imports numpy, numba and itself, nothing else of hubbeam."""

import ast
from pathlib import Path

import hubbeam.core

CORE = Path(hubbeam.core.__file__).parent


def _imports(path):
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            yield node.module or ""


def test_core_imports_nothing_of_the_package_outside_the_core():
    outside = sorted(f"{path.name}: {name}" for path in CORE.glob("*.py") for name in _imports(path)
                     if name.split(".")[0] == "hubbeam" and not name.startswith("hubbeam.core"))
    assert not outside


def test_core_imports_no_plotting_or_workflow_libraries():
    heavy = {"xarray", "matplotlib", "snakemake", "pandas", "scipy"}
    found = sorted(f"{path.name}: {name}" for path in CORE.glob("*.py") for name in _imports(path)
                   if name.split(".")[0] in heavy)
    assert not found
