"""The one table of models (``hubbeam.model.models``), and a guard that nothing else dispatches on a name.

**Dispatch**, as the guard defines it, is code that decides what to compute from a model's (or a
kernel family's) identity instead of from the traits of the table:

* in Python (``src/`` and ``workflow/`` ``.py`` files): a comparison (``==``, ``!=``, ``in``,
  ``not in``, ``is``, ``is not``) one of whose operands is a string literal naming a model or a
  kernel family (``"CFOAM"``, ``"foam"``), a tuple, list or set literal holding one, or a name or
  attribute spelled like a model (the integer model ids the kernels once took, ``eom.SFOAM``); and
  a string literal that is a regular-expression alternation of such names (``"foam|cfoam"``);
* in the rule files (``workflow/**/*.smk`` and the ``Snakefile``, read as text): the same
  comparisons with a literal, an alternation of names, and a hand-written list of two or more
  names (``family=("foam", "cfoam")``).

Not dispatch: naming a model to *select or show* it -- a keyword argument (``run(model="FOAM")``),
a dictionary key (a colour per model, the paper's printed values per model), a list of models to
plot. Modules whose job is to show the paper's results may also compare names, since what they
show is named by the paper: :data:`PRODUCT_MODULES`. ``models.py`` states the table and
``core/inputs.py`` names the kernel families, so both are exempt as well.
"""

import ast
import re
from pathlib import Path

import numpy as np
import pytest
import yaml

import hubbeam
from hubbeam.configuration.schema import SCHEMA
from hubbeam.core import inputs
from hubbeam.core.integrate import FAMILY_KERNELS
from hubbeam.model import linearised, models
from hubbeam.results import variables

PACKAGE = Path(hubbeam.__file__).parent
ROOT = PACKAGE.parents[1]
NAMES = frozenset(models.MODELS) | frozenset(models.FAMILIES)
#: the modules that show the paper's results (figures, tables, claims, readings, its printed
#: values): they may name the models they show, also in a comparison
PRODUCT_MODULES = frozenset({
    "reporting/products.py", "paper/tables.py", "paper/claims.py", "paper/readings.py", "model/printed.py",
    "plotting/critical_map.py",  # the paper's TLAM critical speeds (Sections 4.2, 4.4)
    *(path.relative_to(PACKAGE).as_posix() for path in (PACKAGE / "plotting").glob("fig*.py")),
})
EXEMPT = frozenset({"model/models.py", "core/inputs.py"}) | PRODUCT_MODULES
_WORD = "|".join(sorted(NAMES, key=len, reverse=True))
#: an alternation of two or more model or family names, as in a regular expression
ALTERNATION = re.compile(rf"\b(?:{_WORD})\s*\|\s*(?:{_WORD})\b")
_LITERAL = rf"""["'](?:{_WORD})["']"""
#: in rule files: a comparison with a name, or a literal list of two or more names
RULE_DISPATCH = re.compile(
    rf"(?:==|!=|\bin\b|\bis\b)\s*[(\[{{]?\s*{_LITERAL}"
    rf"|{_LITERAL}\s*(?:==|!=|\bin\b|\bnot\s+in\b|\bis\b)"
    rf"|{_LITERAL}\s*,\s*{_LITERAL}")


def _names_a_model(node) -> bool:
    if isinstance(node, ast.Constant):
        return isinstance(node.value, str) and node.value in NAMES
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return any(_names_a_model(element) for element in node.elts)
    if isinstance(node, ast.Name):
        return node.id in models.MODELS
    if isinstance(node, ast.Attribute):
        return node.attr in models.MODELS
    return False


def python_dispatch(source: str) -> list[str]:
    """The dispatching comparisons and alternations of a Python source (module docstring)."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Compare):
            operands = [node.left, *node.comparators]
            if any(_names_a_model(operand) for operand in operands):
                found.append(f"line {node.lineno}: {ast.unparse(node)}")
        elif (isinstance(node, ast.Constant) and isinstance(node.value, str)
              and "\n" not in node.value and ALTERNATION.search(node.value)):
            found.append(f"line {node.lineno}: {node.value!r}")
    return found


def rule_dispatch(text: str) -> list[str]:
    """The dispatching comparisons, alternations and name lists of a rule file's text."""
    return [f"line {number}: {line.strip()}" for number, line in enumerate(text.splitlines(), 1)
            if not line.lstrip().startswith("#")
            and (ALTERNATION.search(line) or RULE_DISPATCH.search(line))]


def test_no_code_outside_the_table_dispatches_on_a_model_name():
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE).as_posix()
        if relative not in EXEMPT:
            found += [f"src/hubbeam/{relative} {hit}" for hit in python_dispatch(path.read_text())]
    for path in sorted((ROOT / "workflow").rglob("*.py")):
        found += [f"{path.relative_to(ROOT)} {hit}" for hit in python_dispatch(path.read_text())]
    rules = [*(ROOT / "workflow").rglob("*.smk"), *ROOT.glob("Snakefile"), *ROOT.glob("workflow/Snakefile")]
    for path in sorted(rules):
        found += [f"{path.relative_to(ROOT)} {hit}" for hit in rule_dispatch(path.read_text())]
    assert not found, "decide from hubbeam.model.models traits instead:\n" + "\n".join(found)


@pytest.mark.parametrize("source", [
    'if case["model"] == "CFOAM": pass',
    "x = 0.0 if model == TLAM else 1.0",
    "y = model != eom.SFOAM",
    'z = name in ("TLAM", "FOAM")',
    'w = "foam" == family',
    'constraint = "foam|cfoam"',
])
def test_the_guard_finds_python_dispatch(source):
    assert python_dispatch(source)


@pytest.mark.parametrize("source", [
    'run("fig04", model="CFOAM")',
    'STYLE = {"TLAM": "red", "FOAM": "blue"}',
    'if model(name).keeps_axial: pass',
    'MODELS_TO_PLOT = ["TLAM", "FOAM"]',
    'text = "FOAM and CFOAM agree"',
])
def test_the_guard_leaves_selection_and_display_alone(source):
    assert not python_dispatch(source)


@pytest.mark.parametrize("line, dispatches", [
    ('        family="foam|cfoam",', True),
    ('    family=("foam", "cfoam")),', True),
    ('    if config["model"] == "SFOAM":', True),
    ('        family=wildcard_pattern(FAMILIES),', False),
    ("# TLAM, FOAM, SFOAM share the foam|cfoam kernels", False),
])
def test_the_guard_reads_rule_files(line, dispatches):
    assert bool(rule_dispatch(line)) == dispatches


# --------------------------------------------------------------------------- the table itself
def test_every_model_has_a_family_with_a_compiled_kernel():
    assert set(models.FAMILIES) == set(FAMILY_KERNELS) == set(inputs.FAMILIES)
    for m in models.MODELS.values():
        assert m.family in FAMILY_KERNELS
        assert models.family_model(m.family).family == m.family


def test_models_differ_in_what_the_kernels_compute():
    traits = [m.traits for m in models.MODELS.values()]
    assert len(set(traits)) == len(traits)
    assert all(isinstance(flag, bool) for t in traits for flag in t)


def test_wildcard_pattern_matches_exactly_the_families():
    pattern = models.wildcard_pattern(models.FAMILIES)
    for family in models.FAMILIES:
        assert re.fullmatch(pattern, family)
    for other in ("", "FOAM", "sfoam", "foamx", "cfoam|foam", "foamcfoam", *models.MODELS):
        assert not re.fullmatch(pattern, other), other


def test_unknown_model_names_the_allowed_ones():
    with pytest.raises(models.UnknownModelError, match="model = 'XFOAM'; allowed: one of TLAM, "
                                                         "FOAM, SFOAM, CFOAM"):
        models.model("XFOAM")
    with pytest.raises(models.UnknownModelError):
        models.model(["FOAM"])


def test_linearisations_follow_the_traits():
    """Every model's linearisation is a variant of Eq. (31) whose terms are its traits': the
    ``D`` terms where it keeps the softening terms; the axial block where it keeps ``q1``."""
    for m in models.MODELS.values():
        a, c = linearised.CENTRIFUGAL_TERMS[m.linearisation]
        assert (a, c) == (1.0, 1.0 if m.softening_terms else 0.0)
        if m.keeps_axial:
            assert m.linearisation in linearised.AXIAL_MODELS
    assert linearised.AXIAL_MODELS == ("TLAM", "FOAM")
    assert linearised.CENTRIFUGAL_TERMS["flapwise"] == (0.0, 1.0)


def test_dataset_variables_follow_the_high_order_trait():
    for name, m in models.MODELS.items():
        extra = set(variables.dataset_variables(name)) - set(variables.VARIABLES)
        assert extra == (set(variables.HIGH_ORDER_VARIABLES) if m.high_order_outputs else set())


def test_the_schema_allows_exactly_the_models_of_the_table():
    schema = yaml.safe_load((PACKAGE / "configuration" / "schemas" / "config.schema.yaml").read_text())
    enums = []

    def walk(node):
        if isinstance(node, dict):
            if isinstance(node.get("enum"), list) and "FOAM" in node["enum"]:
                enums.append(node["enum"])
            for value in node.values():
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)

    walk(schema)
    assert not enums  # the schema file names no model: the one list is filled in from the table
    assert SCHEMA["$defs"]["model"]["enum"] == list(models.MODELS)
    # every place that takes a model refers to that one definition
    text = (PACKAGE / "configuration" / "schemas" / "config.schema.yaml").read_text()
    assert text.count('$ref: "#/$defs/model"') == 7


def test_sweep_traits_rows_round_trip():
    from hubbeam.core.sweep import traits_at

    rows = np.array([m.traits for m in models.MODELS.values()], dtype=bool)
    for k, m in enumerate(models.MODELS.values()):
        assert traits_at(rows, k) == m.traits
