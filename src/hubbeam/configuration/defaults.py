"""The values a configuration may leave out: ``numerics`` and ``eigen``, wholly or in part.

:func:`fill_numerics` puts in every ``numerics`` key the schema gives a ``default`` (the paper's
integrator settings); it runs before validation, so that the checks which read ``numerics``
(every case spans an output step, the memory budget) see the values the runs will use.
:func:`fill_eigen` derives the grids of the eigen-analysis from the study itself, once the
configuration is valid:

* ``tip_masses``: no tip mass and the tip mass of every case, ascending;
* ``positions``: :data:`POSITION_POINTS` tip-mass positions from the root to the tip, ``[0, L]``;
* ``speeds``: :data:`SPEED_POINTS` hub speeds from 0 to :data:`SPEED_MARGIN` times the larger of
  the highest hub speed a case reaches (``highest_speed`` of its maneuver, a free hub taken as
  rigid, :mod:`hubbeam.model.maneuvers`) and the highest critical
  speed of the study's beam with any tip mass (:func:`highest_critical_speed`), rounded up to
  two significant digits (:func:`round_up`), so that the Campbell diagram shows every case's
  speed and where TLAM loses its bending stiffness;
* ``critical_speed_search_max``: the top of that speed grid.

Both only add keys that are missing; a value the configuration gives is kept. The completed
configuration is what the rules read and what the archive records (``config/config.used.yaml``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from hubbeam.configuration.schema import SCHEMA
from hubbeam.model import linearised
from hubbeam.model.beam import beam_from_config
from hubbeam.model.drive import DcMotor
from hubbeam.model.maneuvers import maneuver_from_dict
from hubbeam.model.matrices import assemble

#: the top of the derived speed grid over the highest speed it must show
SPEED_MARGIN = 1.25
#: points of the derived speed grid (rad s-1)
SPEED_POINTS = 121
#: points of the derived grid of tip-mass positions (m)
POSITION_POINTS = 41


def numerics_defaults() -> dict:
    """``{key: default}`` of the ``numerics`` keys the schema gives a default."""
    properties = SCHEMA["properties"]["numerics"]["properties"]
    return {key: node["default"] for key, node in properties.items() if "default" in node}


def fill_numerics(cfg: dict) -> None:
    """Add, in place, every missing ``numerics`` key that has a default (a ``numerics`` that is
    not a mapping is left for the schema to report)."""
    numerics = cfg.setdefault("numerics", {})
    if isinstance(numerics, dict):
        for key, value in numerics_defaults().items():
            numerics.setdefault(key, value)


def fill_eigen(cfg: dict) -> None:
    """Add, in place, every missing key of ``eigen`` derived from the study (module docstring);
    ``cfg`` must be a valid configuration with its ``numerics`` filled in."""
    eigen = cfg.setdefault("eigen", {})
    missing = {"tip_masses", "positions", "speeds", "critical_speed_search_max"} - set(eigen)
    if not missing:
        return
    beam, cases, numerics = cfg["beam"], cfg["cases"], cfg["numerics"]
    if "tip_masses" in missing:
        eigen["tip_masses"] = sorted({0.0, *(float(case.get("tip_mass", {}).get("mass", 0.0))
                                             for case in cases.values())})
    if "positions" in missing:
        eigen["positions"] = {"start": 0.0, "stop": float(beam["length"]), "num": POSITION_POINTS}
    if missing & {"speeds", "critical_speed_search_max"}:
        params = beam_from_config(beam)
        bare = assemble(params, None, int(numerics["modes"]), int(numerics["quadrature_points"]))
        inertia = bare.Jh + bare.Jb

        def reached(case: Mapping) -> float:
            drive = DcMotor(**case["drive"]) if "drive" in case else None
            return maneuver_from_dict(case["maneuver"]).highest_speed(float(case["t_end"]), inertia, drive)

        highest = max(highest_critical_speed(bare.K2, bare.M2), *map(reached, cases.values()))
        top = round_up(SPEED_MARGIN * highest)
        eigen.setdefault("speeds", {"start": 0.0, "stop": top, "num": SPEED_POINTS})
        eigen.setdefault("critical_speed_search_max", top)


def highest_critical_speed(K2: np.ndarray, M2: np.ndarray) -> float:
    """The highest critical speed (rad s-1) over every tip mass and position, from the bare beam's
    ``K2, M2``: TLAM's, the bare beam's first natural frequency.

    ``K22 = K2 - Omega^2 B`` (Eq. 31) becomes singular at ``Omega^2 = 1 / mu`` for the largest
    eigenvalue ``mu`` of ``B v = mu K2 v`` (``hubbeam.model.eigen``), ``B = M2`` for TLAM. A point mass
    ``m`` at ``l`` adds the positive semi-definite ``m f2(l)^T f2(l)`` to ``M2``, which raises
    ``mu`` and so lowers the critical speed: the bare beam's bounds them all. FOAM has none
    (``B = M2 - D`` is negative definite for a beam clamped to the hub, ``hubbeam.model.eigen``), so it
    is not asked here: a rounding error could only make up a spurious one.
    """
    mu = linearised.symmetric_eigenvalues(M2, K2)[-1]  # B = M2 of TLAM
    return float(1.0 / math.sqrt(mu))


def round_up(value: float) -> float:
    """``value`` (> 0) rounded up to two significant digits (12.46 -> 13, 0.0123 -> 0.013)."""
    scale = 10.0 ** (math.floor(math.log10(value)) - 1)
    return float(round(math.ceil(round(value / scale, 9)) * scale, 12))


#: frequency responses: frequencies (rad s-1) when ``linear.frequencies`` is left out
LINEAR_FREQUENCIES = {"start": 0.1, "stop": 1000.0, "num": 500}
#: fractions of the top speed of the frequency responses when ``linear.bode_speeds`` is left out
BODE_SPEED_FRACTIONS = (0.0, 0.5, 0.875)
#: vibration modes whose shapes are drawn when ``linear.shapes`` is left out
LINEAR_SHAPES = 4


def fill_linear(cfg: dict) -> None:
    """Add, in place, every missing key of ``linear`` (the schema's descriptions): the speeds of
    ``eigen.speeds``, no tip mass and the largest of ``eigen.tip_masses``, frequency responses at
    rest, half and seven eighths of the top speed; ``cfg`` must be valid with ``eigen`` filled."""
    linear = cfg.setdefault("linear", {})
    eigen = cfg["eigen"]
    linear.setdefault("speeds", dict(eigen["speeds"]))
    largest = max(float(mass) for mass in eigen["tip_masses"])
    linear.setdefault("tip_masses", [0.0, largest] if largest > 0.0 else [0.0])
    top = float(linear["speeds"]["stop"])
    linear.setdefault("bode_speeds", [fraction * top for fraction in BODE_SPEED_FRACTIONS])
    linear.setdefault("frequencies", dict(LINEAR_FREQUENCIES))
    linear.setdefault("shapes", LINEAR_SHAPES)
