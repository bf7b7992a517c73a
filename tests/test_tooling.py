"""The static checks of ``make test``: the import contracts of pyproject.toml (``lint-imports``:
the numba core stands alone, plotting does not reach into the report, the report side reads
results without the plotting package, the package's layers) and
``ruff check`` over every Python source of the repository."""

import subprocess
import sys
from pathlib import Path

import pytest

BIN = Path(sys.executable).parent
CHECKS = {
    "import contracts": [str(BIN / "lint-imports"), "--no-cache"],
    "ruff": [str(BIN / "ruff"), "check", "--no-cache", "src", "tests", "workflow", "benchmarks"],
}


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_static_check_passes(name, repo_root):
    run = subprocess.run(CHECKS[name], cwd=repo_root, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, f"{name} failed:\n{run.stdout}\n{run.stderr}"
