"""The package sources a script depends on, found from its imports (``hubbeam.reporting.sourcedeps``).

Checked on a throw-away package whose import graph is known by construction (absolute, relative,
``from package import submodule``, imports inside functions, a module nobody imports), on the real
package (a script importing ``hubbeam.simulation.simulate`` needs the Radau kernel, not the plotting code),
and on the rule files: every rule's code inputs are those of the script it runs.
"""

import textwrap
from pathlib import Path

import pytest

from hubbeam.reporting.sourcedeps import imported_names, script_dependencies


def write(root: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))


@pytest.fixture
def toy(tmp_path):
    """Package ``hubbeam`` in ``tmp_path/src`` and a script importing part of it."""
    root = tmp_path / "src" / "hubbeam"
    write(root, {
        "__init__.py": "",
        "a.py": "from . import b\nimport numpy\n",
        "b.py": "def f():\n    from hubbeam.sub.c import g\n    return g\n",
        "sub/__init__.py": "from .d import X\n",
        "sub/c.py": "g = 1\n",
        "sub/d.py": "X = 2\n",
        "unused.py": "import hubbeam.a\n",
        "late.py": "",
    })
    script = tmp_path / "script.py"
    script.write_text("import os\nfrom hubbeam import a\n")
    return root, script


def relative(files, root):
    return sorted(path.relative_to(root).as_posix() for path in files)


def test_closure_follows_every_kind_of_import(toy):
    root, script = toy
    assert relative(script_dependencies(script, root), root) == [
        "__init__.py", "a.py", "b.py", "sub/__init__.py", "sub/c.py", "sub/d.py"]


def test_declared_package_data_counts_for_every_importer(toy):
    root, script = toy
    write(root, {"b.py": 'PACKAGE_DATA = ("templates/*.j2",)\n', "templates/r.md.j2": "x",
                 "templates/notes.txt": "not matched", "other/t.md.j2": "not declared"})
    files = relative(script_dependencies(script, root), root)
    assert "templates/r.md.j2" in files
    assert "templates/notes.txt" not in files and "other/t.md.j2" not in files


def test_the_report_rules_depend_on_the_templates():
    from hubbeam.reporting.sourcedeps import package_dir

    root = package_dir()
    script = Path(__file__).parents[1] / "workflow" / "scripts" / "run_job.py"
    files = relative(script_dependencies(script, root, ["hubbeam.pipeline.jobs.reports"]), root)
    assert "reporting/templates/reproduction.md.j2" in files and "reporting/document.py" in files


def test_extra_modules_are_added_with_their_imports(toy):
    root, script = toy
    files = relative(script_dependencies(script, root, ["hubbeam.late", "hubbeam.unused"]), root)
    assert "late.py" in files and "unused.py" in files
    with pytest.raises(ModuleNotFoundError, match="'hubbeam.nowhere'"):
        script_dependencies(script, root, ["hubbeam.nowhere"])


def test_relative_import_resolution(toy):
    root, _ = toy
    assert "hubbeam.b" in imported_names(root / "a.py", "hubbeam.a")
    assert "hubbeam.sub.d" in imported_names(root / "sub" / "__init__.py", "hubbeam.sub")
    with pytest.raises(ValueError, match="relative import"):
        imported_names(root / "a.py")


def test_real_script_gets_the_integrator_and_not_the_plots(repo_root):
    script = repo_root / "workflow" / "scripts" / "run_job.py"
    root = repo_root / "src" / "hubbeam"
    files = relative(script_dependencies(script, root, ["hubbeam.pipeline.jobs.simulation"]), root)
    for needed in ("__init__.py", "pipeline/runner.py", "pipeline/jobs/simulation.py", "control/__init__.py",
                   "control/feedback.py", "simulation/simulate.py",
                   "core/__init__.py", "core/radau.py", "core/integrate.py", "core/eom.py", "model/matrices.py"):
        assert needed in files
    assert not any(name.startswith(("plotting/", "validation/")) for name in files)
    assert "paper/report.py" not in files and "core/first_order.py" not in files
