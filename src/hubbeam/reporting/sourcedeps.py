"""The package modules a script depends on, found from its import statements (nothing is run).

Snakemake reruns a job when its script changes, not when a module the script imports does; the
workflow therefore lists, as inputs of each rule, every source file of the package the rule's
script imports, directly or through other modules of the package. Those files are found here by
reading the import statements (``ast``) of the script and, transitively, of each package module
it reaches, including imports inside functions. Importing ``a.b.c`` runs ``a/__init__.py`` and
``a/b/__init__.py`` too, so those are included. A module imported by a name computed at run time
(``importlib.import_module``) is invisible to this analysis: callers name such modules
themselves (``extra_modules``). A module that reads files of the package at run time (templates,
say) declares them in a module-level tuple of glob patterns relative to its own directory,
``PACKAGE_DATA = ("templates/*.j2",)``; those files count as dependencies of every script that
imports the module.
"""

from __future__ import annotations

import ast
import importlib.util
from collections.abc import Iterable
from functools import cache
from pathlib import Path

PACKAGE = "hubbeam"


def package_dir(package: str = PACKAGE) -> Path:
    """The directory of ``package`` on the import path (located without importing it)."""
    spec = importlib.util.find_spec(package)
    if spec is None or not spec.submodule_search_locations:
        raise ModuleNotFoundError(f"package {package!r} is not importable; allowed: an installed "
                                  "package or one on PYTHONPATH")
    return Path(next(iter(spec.submodule_search_locations))).resolve()


def module_file(module: str, root: Path, package: str = PACKAGE) -> Path | None:
    """The source file of ``module`` (``package.x.y``) under the package directory ``root``:
    ``x/y.py`` or ``x/y/__init__.py``; None when there is none."""
    parts = module.split(".")
    if parts[0] != package:
        return None
    base = root.joinpath(*parts[1:])
    for candidate in (base.with_suffix(".py") if len(parts) > 1 else None, base / "__init__.py"):
        if candidate is not None and candidate.is_file():
            return candidate
    return None


@cache
def imported_names(path: Path, module: str | None = None) -> frozenset[str]:
    """Every module name the file ``path`` may import: ``import a.b`` gives ``a.b``;
    ``from a import b`` gives ``a`` and ``a.b`` (``b`` may be a submodule). ``module`` is the
    file's own dotted name, needed to resolve relative imports (``from . import x``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                if module is None:
                    raise ValueError(f"{path}: relative import 'from {'.' * node.level}{base} import ...' "
                                     "outside a package; allowed: absolute imports in scripts")
                is_package = path.name == "__init__.py"
                anchor = module.split(".")[: len(module.split(".")) - node.level + is_package]
                base = ".".join(anchor + ([base] if base else []))
            names.add(base)
            names.update(f"{base}.{alias.name}" for alias in node.names if alias.name != "*")
    return frozenset(names)


@cache
def package_data(path: Path) -> tuple[Path, ...]:
    """The files the module ``path`` declares in its literal ``PACKAGE_DATA`` tuple of glob
    patterns (relative to the module's directory), sorted; none without such a tuple."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    for node in tree.body:
        if (isinstance(node, ast.Assign) and len(node.targets) == 1
                and isinstance(node.targets[0], ast.Name) and node.targets[0].id == "PACKAGE_DATA"):
            patterns = ast.literal_eval(node.value)
            return tuple(sorted(file for pattern in patterns for file in path.parent.glob(pattern)
                                if file.is_file()))
    return ()


def with_parents(module: str) -> list[str]:
    """``a.b.c`` -> ``[a, a.b, a.b.c]``: importing a module runs its parent packages first."""
    parts = module.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts) + 1)]


def module_closure(script: Path, root: Path, extra_modules: Iterable[str] = (),
                   package: str = PACKAGE) -> dict[str, Path]:
    """{module name: source file} of every module of ``package`` (directory ``root``) that
    ``script`` imports, directly or transitively, plus ``extra_modules`` and what they import."""
    pending = [*imported_names(Path(script)), *extra_modules]
    found: dict[str, Path] = {}
    while pending:
        for name in with_parents(pending.pop()):
            if name in found:
                continue
            path = module_file(name, root, package)
            if path is not None:
                found[name] = path
                pending.extend(imported_names(path, name))
    return found


def script_dependencies(script: Path, root: Path | None = None, extra_modules: Iterable[str] = (),
                        package: str = PACKAGE) -> list[Path]:
    """The source files of ``package`` the script ``script`` runs (see :func:`module_closure`)
    and the package data those modules declare (:func:`package_data`), sorted; ``root`` defaults
    to the package's directory on the import path."""
    script = Path(script)
    if not script.is_file():
        raise FileNotFoundError(f"script {script} does not exist; allowed: an existing Python file")
    root = package_dir(package) if root is None else Path(root)
    for name in extra_modules:
        if module_file(name, root, package) is None:
            raise ModuleNotFoundError(f"extra module {name!r} has no source file under {root}; "
                                      f"allowed: a module of {package}")
    modules = module_closure(script, root, extra_modules, package).values()
    return sorted({*modules, *(data for path in modules for data in package_data(path))})
