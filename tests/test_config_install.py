"""An installed hubbeam (not the source tree) checks a configuration: the schema is package data.

The project is copied to a temporary folder and installed with ``pip install --no-deps`` into a
fresh virtual environment; pip fetches only the build backend (from PyPI), the dependencies come
from the environment running the tests (one ``.pth`` line naming its site-packages, whose own
``.pth`` files, such as an editable install of hubbeam, are then not read). The check runs from a folder outside the
source tree, so that only the installed package can be imported.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
import textwrap
from pathlib import Path

CHECK = textwrap.dedent("""
    import sys
    from pathlib import Path
    import hubbeam
    from hubbeam.configuration.load import ConfigError, load_config
    assert Path(hubbeam.__file__).resolve().is_relative_to(Path(sys.prefix).resolve()), hubbeam.__file__
    load_config("good.yaml")
    try:
        load_config("bad.yaml")
    except ConfigError as error:
        print(error)
    else:
        raise SystemExit("the bad configuration was accepted")
""")


def _run(*command, cwd: Path) -> str:
    """Run ``command`` in ``cwd`` without PYTHONPATH (which could name the source tree)."""
    env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True, env=env)
    assert done.returncode == 0, f"{' '.join(map(str, command))} failed:\n{done.stdout}\n{done.stderr}"
    return done.stdout


def test_an_installed_package_checks_a_configuration_outside_the_source_tree(tmp_path, repo_root):
    source = tmp_path / "source"
    source.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(repo_root / name, source / name)
    shutil.copytree(repo_root / "src", source / "src",
                    ignore=shutil.ignore_patterns("__pycache__", "*.egg-info", "*.nbi", "*.nbc"))
    venv = tmp_path / "venv"
    _run(sys.executable, "-m", "venv", "--without-pip", venv, cwd=tmp_path)
    python = venv / "bin" / "python"
    purelib = Path(_run(python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])",
                        cwd=tmp_path).strip())
    (purelib / "test_dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n", encoding="utf-8")
    # the build backend (setuptools, pyproject.toml) comes from PyPI into pip's isolated build environment
    _run(sys.executable, "-m", "pip", "--python", python, "install", "--quiet", "--no-deps", source, cwd=tmp_path)
    assert (purelib / "hubbeam" / "configuration" / "schemas" / "config.schema.yaml").is_file()

    work = tmp_path / "work"
    work.mkdir()
    good = (repo_root / "studies" / "spinup10m.yaml").read_text(encoding="utf-8")
    (work / "good.yaml").write_text(good, encoding="utf-8")
    (work / "bad.yaml").write_text(good.replace("name: spinup10m", "name: ../evil"), encoding="utf-8")
    message = _run(python, "-c", CHECK, cwd=work)
    assert "study.name: got '../evil'" in message
