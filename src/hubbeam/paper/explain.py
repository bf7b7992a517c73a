"""Why a printed number differs: the readings tried, simple misprints, and a conclusion per claim.

For every claim that differs under the default reading (claims.csv), :func:`conclude` weighs
(1) each alternative reading that recomputed it (:mod:`hubbeam.paper.readings`): the reading explains the
claim when the claim agrees under it; (2) simple misprints of the printed number
(:func:`misprints`): an exponent off by one, two adjacent digits swapped; the default result
explains the misprinted number when it agrees with it within the claim's own tolerance (the rule
of reproduction note 18). Otherwise the claim is "not explained by any reading tried", and the
closest reading is named with its distance. A reading that brings one claim closer to the print
but moves another further away is flagged (:func:`side_effects`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from hubbeam.configuration.sections import Reading
from hubbeam.reporting.formatting import number, percent

EXPLAINED = "explained by a reading"
MISPRINT = "likely misprint"
UNEXPLAINED = "not explained by any reading tried"


@dataclass(frozen=True)
class Misprint:
    """A simple misprint hypothesis: the number meant, and what the misprint would be."""

    value: float
    description: str


def _swaps(printed: str) -> Iterable[Misprint]:
    mantissa, e, exponent = printed.lower().partition("e")
    digits = [i for i, char in enumerate(mantissa) if char.isdigit()]
    for a, b in zip(digits, digits[1:]):
        if b == a + 1 and mantissa[a] != mantissa[b]:
            swapped = mantissa[:a] + mantissa[b] + mantissa[a] + mantissa[b + 1:]
            yield Misprint(float(swapped + e + exponent), f"digits swapped: {swapped + e + exponent} "
                           f"printed as {printed}")


def misprints(printed: float) -> list[Misprint]:
    """Simple misprints of ``printed`` (three significant figures): exponent off by one either
    way, and every swap of two adjacent differing digits."""
    text = number(float(printed), 3)
    return [Misprint(printed * 10.0, f"exponent off by one: {number(printed * 10.0, 3)} printed as {text}"),
            Misprint(printed / 10.0, f"exponent off by one: {number(printed / 10.0, 3)} printed as {text}"),
            *_swaps(text)]


def _distance(row: Mapping) -> float:
    """How far a claim row is from the print: |relative difference|, or |computed - paper| for
    claims that two curves coincide (paper 0)."""
    rel = row.get("rel_diff")
    if rel is not None and math.isfinite(rel):
        return abs(rel)
    distance = abs(row["computed"] - row["paper"])
    return distance if math.isfinite(distance) else math.inf


@dataclass(frozen=True)
class Conclusion:
    """The conclusion for one differing claim."""

    claim: str
    verdict: str
    text: str
    closest: str | None
    closest_distance: float | None
    default_distance: float
    tried: tuple[str, ...]
    explaining: tuple[str, ...] = ()


def conclude(default: Mapping, trials: Mapping[str, Mapping]) -> Conclusion:
    """Conclusion for the differing claim row ``default`` given ``{reading: claim row}``."""
    base = _distance(default)
    closest = min(trials, key=lambda name: _distance(trials[name]), default=None)
    closest_distance = _distance(trials[closest]) if closest else None
    explaining = sorted(name for name, row in trials.items() if row["verdict"] == "agrees")
    if explaining:
        best = min(explaining, key=lambda name: _distance(trials[name]))
        text = (f"explained by reading {', '.join(explaining)}: computed {number(trials[best]['computed'])} "
                f"against the printed {number(default['paper'])} ({_percent(trials[best])})")
        return Conclusion(default["id"], EXPLAINED, text, best, closest_distance, base, tuple(trials),
                          tuple(explaining))
    if default.get("rel_diff") is not None and math.isfinite(default["rel_diff"]):
        for hypothesis in misprints(default["paper"]):
            rel = (default["computed"] - hypothesis.value) / abs(hypothesis.value)
            if abs(rel) <= default["tolerance"]:
                text = (f"likely misprint ({hypothesis.description}): computed {number(default['computed'])} "
                        f"is within {percent(abs(rel))} of {number(hypothesis.value)}")
                return Conclusion(default["id"], MISPRINT, text, closest, closest_distance, base,
                                  tuple(trials))
    if closest is None:
        text = "no reading recomputes this claim"
    elif closest_distance < base:
        text = (f"closest reading {closest}: {number(trials[closest]['computed'])} against the printed "
                f"{number(default['paper'])} ({_percent(trials[closest])}; default {_percent(default)})")
    else:
        text = f"no reading tried comes closer than the default ({_percent(default)})"
    return Conclusion(default["id"], UNEXPLAINED, text, closest, closest_distance, base, tuple(trials))


def _percent(row: Mapping) -> str:
    rel = row.get("rel_diff")
    if rel is not None and math.isfinite(rel):
        return percent(rel, 3, signed=True)
    return f"max difference {number(row['computed'], 3)} of the peak"


def side_effects(default_rows: Mapping[str, Mapping], reading_rows: Iterable[Mapping]) -> dict[str, dict]:
    """Per reading, the claims it brings closer to the print and those it moves further away
    (relative to the default reading), ``{reading: {"closer": [...], "further": [...]}}``."""
    out: dict[str, dict] = {}
    for row in reading_rows:
        entry = out.setdefault(row["reading"], {"closer": [], "further": []})
        before, after = _distance(default_rows[row["id"]]), _distance(row)
        if not math.isclose(before, after, rel_tol=1e-9, abs_tol=1e-15):
            entry["closer" if after < before else "further"].append(row["id"])
    return out


def conclusions(default_rows: Iterable[Mapping], reading_rows: Iterable[Mapping]) -> list[Conclusion]:
    """One conclusion per differing claim of ``default_rows`` (claims.csv), from the reading rows
    (``reading`` plus the claim columns), in claims.csv order."""
    by_claim: dict[str, dict] = {}
    for row in reading_rows:
        by_claim.setdefault(row["id"], {})[row["reading"]] = row
    return [conclude(row, by_claim.get(row["id"], {})) for row in default_rows
            if row["verdict"] == "differs"]


def shared_explanations(found: Iterable[Conclusion]) -> dict[str, list[str]]:
    """Readings that explain more than one claim: ``{reading: [claim ids]}``."""
    by_reading: dict[str, list[str]] = {}
    for conclusion in found:
        for name in conclusion.explaining:
            by_reading.setdefault(name, []).append(conclusion.claim)
    return {name: ids for name, ids in by_reading.items() if len(ids) > 1}


def section(default_rows: list[Mapping], reading_rows: list[Mapping], readings: Mapping[str, Reading]) -> dict:
    """What the report's readings section shows: the readings (with their notes), one conclusion
    per differing claim, the readings that explain several claims, and the readings that bring
    some claims closer while moving others further away."""
    found = conclusions(default_rows, reading_rows)
    effects = side_effects({row["id"]: row for row in default_rows}, reading_rows)
    return {
        "readings": [{"name": name, "why": entry.why, "notes": ", ".join(map(str, entry.notes)),
                      "claims": len(entry.claims)} for name, entry in readings.items()],
        "conclusions": found,
        "counts": {key: sum(c.verdict == verdict for c in found) for key, verdict in
                   (("explained", EXPLAINED), ("misprint", MISPRINT), ("unexplained", UNEXPLAINED))},
        "shared": shared_explanations(found),
        "mixed": {name: entry for name, entry in effects.items() if entry["closer"] and entry["further"]},
    }
