"""References that resolve: every dotted name ``hubbeam.…`` in the README, the docs, the rule files
and the package's own strings (docstrings, comments, messages) names a module or an attribute that
exists; and the import layers docs/architecture.md lists are those of pyproject.toml's contracts.

A reference is written in full (``hubbeam.control.cases.simulate_case``), with an optional
``:attribute`` after a module (``hubbeam.plotting.bode:plot``), so that it can be followed; a
reference that no longer resolves (a function renamed or moved) fails here with where it is.
"""

from __future__ import annotations

import importlib
import re
import tomllib
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
#: a dotted name under the package, with an optional ``:attribute``; a trailing dot is punctuation
REFERENCE = re.compile(r"(?<![\w/.-])hubbeam(?:\.[A-Za-z_]\w*)+(?::[A-Za-z_]\w*)?(?![\w{])")
#: files of the package that are data, not modules (named like references)
DATA_FILES = {"hubbeam.mplstyle"}


def searched_files() -> list[Path]:
    files = [REPO / "README.md", REPO / "Snakefile"]
    for folder, patterns in (("docs", ("*.md",)), ("workflow", ("*.smk", "*.py", "*.rst")),
                             ("src/hubbeam", ("*.py", "*.j2", "*.yaml")), ("benchmarks", ("*.py",))):
        files += [path for pattern in patterns for path in sorted((REPO / folder).rglob(pattern))]
    return files


def resolves(reference: str) -> bool:
    """Whether ``reference`` names a module, or an attribute (possibly nested) of one."""
    dotted, _, attribute = reference.partition(":")
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            target = importlib.import_module(".".join(parts[:cut]))
        except ModuleNotFoundError:
            continue
        for name in [*parts[cut:], *([attribute] if attribute else [])]:
            if not hasattr(target, name):
                return False
            target = getattr(target, name)
        return True
    return False


def test_every_reference_to_the_package_resolves():
    unresolved = []
    for path in searched_files():
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
            for reference in REFERENCE.findall(line):
                if reference not in DATA_FILES and not resolves(reference):
                    unresolved.append(f"{path.relative_to(REPO)}:{number}: {reference}")
    assert unresolved == []


def test_a_broken_reference_is_found():
    assert resolves("hubbeam.control.cases.simulate_case") and resolves("hubbeam.plotting.bode:plot")
    assert not resolves("hubbeam.control.feedback.simulate_case") and not resolves("hubbeam.benchmark")
    assert REFERENCE.findall("see hubbeam.model.eigen. Then `hubbeam.api.load`") == ["hubbeam.model.eigen",
                                                                                   "hubbeam.api.load"]


def contracts() -> dict[str, list[str]]:
    """The layers of every ``layers`` contract of pyproject.toml, by container (``hubbeam`` for the
    packages), each layer as the names it holds joined by ``|``."""
    config = tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["importlinter"]
    return {(contract.get("containers") or ["?"])[0]: [" | ".join(sorted(name.strip() for name in layer.split("|")))
                                                       for layer in contract["layers"]]
            for contract in config["contracts"] if contract["type"] == "layers"}


def documented_layers() -> dict[str, list[str]]:
    """The layers of the section "Import layers" of docs/architecture.md: the packages' line
    (``\\`a\\` > \\`b\\`, \\`c\\` > ...``) and a line per package (``- \\`name/\\`: ...``)."""
    text = (REPO / "docs" / "architecture.md").read_text()
    section = text[text.index("### Import layers"):]
    section = section[:section.index("\n#", 1)]
    found = {}
    packages = re.search(r"The packages, from the top: (.*?)\. A package", section, re.S).group(1)
    found["hubbeam"] = _layers(packages)
    for name, layers in re.findall(r"^- `([\w/]+)/`: (.*?);?$", section, re.M):
        found[f"hubbeam.{name.replace('/', '.')}"] = _layers(layers)
    return found


def _layers(text: str) -> list[str]:
    return [" | ".join(sorted(re.findall(r"`(\w+)`", layer))) for layer in " ".join(text.split()).split(" > ")]


@pytest.mark.parametrize("container", sorted(contracts()))
def test_the_documented_layers_are_the_contracts(container):
    assert documented_layers().get(container) == contracts()[container]
