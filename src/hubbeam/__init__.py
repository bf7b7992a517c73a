"""hubbeam: dynamic stiffening of a rotating hub-beam with a tip mass.

Importing the package points numba's on-disk cache (``NUMBA_CACHE_DIR``) at a directory keyed by
a hash of the package's own Python sources, unless the user has set ``NUMBA_CACHE_DIR``. Numba only
notices edits to the file that defines a kernel, not to the modules it calls or the globals it
freezes; a new directory per source state makes a stale compiled kernel impossible. This runs
before any submodule imports numba (``core/jit.py`` is where numba is first imported).
"""

import hashlib
import os
import sys
from pathlib import Path

__version__ = "0.1.0"


PACKAGE_DIR = Path(__file__).resolve().parent


def source_hash(package_dir: Path = PACKAGE_DIR) -> str:
    """Short SHA-256 digest of every ``*.py`` file of the package (relative path and bytes)."""
    digest = hashlib.sha256()
    for path in sorted(package_dir.rglob("*.py")):
        digest.update(path.relative_to(package_dir).as_posix().encode())
        digest.update(b"\0")
        digest.update(path.read_bytes())
        digest.update(b"\0")
    return digest.hexdigest()[:12]


def _default_numba_cache_dir() -> Path:
    cache_home = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(cache_home) / "hubbeam" / f"numba-{source_hash()}"


if "NUMBA_CACHE_DIR" not in os.environ:
    os.environ["NUMBA_CACHE_DIR"] = str(_default_numba_cache_dir())
    if "numba" in sys.modules:
        # numba was imported before hubbeam and has already read its environment; its cache
        # locator reads config.CACHE_DIR when a kernel is decorated, which has not happened yet.
        sys.modules["numba"].config.CACHE_DIR = os.environ["NUMBA_CACHE_DIR"]
