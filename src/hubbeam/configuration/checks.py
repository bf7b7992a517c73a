"""Checks of a configuration that a JSON schema cannot express (:func:`physical_problems`).

The tip mass lies on the beam (``0 <= l <= L``) and a tip body's centre beyond the root, every
case spans at least one output step, grids increase, numbers are finite and at most
:data:`LARGEST_NUMBER` in magnitude, case names stay
distinct on case-insensitive file systems, keys are text; a beam has the keys of one form only
(the forms and their keys are the schema's), stations run from x = 0 to x = L, tables of stations
and times increase, a case can start from its ``initial`` state (one value per mode, no axial
coordinates for SFOAM, a prescribed hub at its maneuver's speed at t = 0), a state feedback names
states and signals its models have, a study (``study`` section) neither takes a folder of the
paper's products nor compares unknown cases, and no case, validation run or sweep would need more
memory than ``numerics.memory_budget_mb`` (:mod:`hubbeam.results.variables`: a case's outputs, and the
arrays of its sampled controller per sample, of its shaper's impulses and of its tables). Each check runs only
on values the schema accepted, and each problem names the key, the value and what is allowed."""

from __future__ import annotations

import itertools
import math
import os
from collections.abc import Callable, Mapping
from typing import Any, NamedTuple

from hubbeam.configuration.schema import (
    MEASURED_SIGNALS,
    SCHEMA,
    Problem,
    Validator,
    allowed,
    key_path,
    kind_keys,
    show,
    type_name,
)
from hubbeam.model import limits
from hubbeam.model.maneuvers import MANEUVERS, REFERENCES, maneuver_from_dict
from hubbeam.model.models import DESIGN_ONLY_MODELS, MODELS
from hubbeam.model.modes import CLAMPED_FREE, TIP_BODY
from hubbeam.model.root import state_names as root_state_names
from hubbeam.reporting.products import PAPER
from hubbeam.results import variables
from hubbeam.results.paths import PAPER_FOLDERS

#: the lumped design model's states and outputs, as ``hubbeam.linear.lumped`` names them (which imports
#: the configuration, so it cannot be imported here; a test keeps the two the same)
LUMPED_STATES = ("theta", "alpha", "theta_dot", "alpha_dot")
LUMPED_OUTPUTS = ("hub_angle", "deflection_angle", "hub_speed", "deflection_rate", "tip_deflection", "tip_arc")
#: the largest magnitude of a number in a configuration: SI quantities of a beam on a hub stay far below
#: it (a steel's Young's modulus is 2e11 Pa), and the model multiplies them (E I, Omega^2 m L^2, ...) in
#: double precision, which overflows at 1.8e308
LARGEST_NUMBER = 1e15


def physical_problems(cfg: Any, whole: bool = True) -> list[Problem]:
    """Checks the schema cannot express; each runs only on values the schema accepted. ``whole``:
    ``cfg`` is a whole configuration (the paper or a study), not the Python API's bare case and
    numerics, which have no study to check."""
    if not isinstance(cfg, dict):
        return []
    problems = _non_finite_numbers_and_non_text_keys(cfg, [])
    beam, numerics, eigen, cases = (_section(cfg, key) for key in ("beam", "numerics", "eigen", "cases"))
    # bounds derived from a length or step the schema rejects would only repeat that problem
    length = _positive(beam.get("length"))
    output_step = _positive(numerics.get("output_step"))

    max_steps, step_warning = _integer(numerics.get("max_steps")), _integer(numerics.get("step_warning"))
    if max_steps is not None and step_warning is not None and step_warning > max_steps:
        problems.append(Problem("numerics.step_warning",
                                f"got {step_warning}; allowed: at most numerics.max_steps = {max_steps}"))

    linear = _section(cfg, "linear")
    grids = {"eigen.speeds": _section(eigen, "speeds"), "eigen.positions": _section(eigen, "positions"),
             "linear.speeds": _section(linear, "speeds"), "linear.frequencies": _section(linear, "frequencies")}
    for where, grid in grids.items():
        start, stop = _number(grid.get("start")), _number(grid.get("stop"))
        if start is not None and stop is not None and stop <= start:
            problems.append(Problem(f"{where}.stop", f"got {stop}; allowed: a value > {where}.start = {start}"))
    bode_speeds = linear.get("bode_speeds")
    if isinstance(bode_speeds, list) and all(_number(v) is not None for v in bode_speeds) and any(
            b <= a for a, b in zip(bode_speeds, bode_speeds[1:])):
        problems.append(Problem("linear.bode_speeds", f"got {show(bode_speeds)}; allowed: strictly increasing speeds"))
    stop = _number(grids["eigen.positions"].get("stop"))
    if stop is not None and length is not None and stop > length:
        problems.append(Problem("eigen.positions.stop",
                                f"got {stop}; allowed: a position on the beam, <= beam.length = {length}"))

    first_spelling: dict[str, str] = {}
    for name, case in cases.items():
        if isinstance(name, str):
            other = first_spelling.setdefault(name.lower(), name)
            if other != name:
                problems.append(Problem(f"cases.{name}", f"case name {name!r} differs from {other!r} only in "
                                        "letter case; allowed: names distinct ignoring case (they are file names)"))
        if not isinstance(case, dict):
            continue
        t_end = _number(case.get("t_end"))
        if t_end is not None and output_step is not None and t_end < output_step:
            problems.append(Problem(f"cases.{name}.t_end", f"got {t_end}; allowed: at least one output step, "
                                    f"t_end >= numerics.output_step = {output_step}"))
        position = _number(_section(case, "tip_mass").get("position"))
        if position is not None and length is not None and position > length:
            problems.append(Problem(f"cases.{name}.tip_mass.position",
                                    f"got {position}; allowed: 0 <= position <= beam.length = {length}"))
        offset = _number(_section(case, "tip_mass").get("offset"))
        attached = position if position is not None else length
        if offset is not None and attached is not None and attached + offset < 0.0:
            problems.append(Problem(f"cases.{name}.tip_mass.offset",
                                    f"got {offset}; allowed: offset >= -position = {-attached} (the body's centre "
                                    "on the beam's side of the clamped root, not inside the hub)"))
        entry_problems = _case_entry_problems(f"cases.{name}", case)
        modes = _modes(case.get("modes", numerics.get("modes")))
        problems += entry_problems + _initial_problems(f"cases.{name}", case, modes, check_speed=not entry_problems)
        problems += _feedback_problems(f"cases.{name}.maneuver", case, modes)
        problems += _drive_problems(f"cases.{name}", case) + _shaper_problems(f"cases.{name}.shaper", case, modes)
        problems += _functions_problems(f"cases.{name}", case, beam, length)
    problems += _beam_problems(beam, length)
    if whole:
        problems += _study_problems(cfg, eigen, cases)
    problems += _sweep_problems(_section(cfg, "sweeps"), length)
    problems += _validation_problems(_section(cfg, "validation"), length, output_step)
    problems += _memory_problems(cfg, output_step)
    return problems


def _memory_problems(cfg: Mapping, output_step: float | None) -> list[Problem]:
    """Every case, validation run and sweep whose outputs would exceed ``numerics.memory_budget_mb``
    (:mod:`hubbeam.results.variables`), each named with its estimated size and the budget."""
    numerics = _section(cfg, "numerics")
    budget_mb = _positive(numerics.get("memory_budget_mb", limits.MEMORY_BUDGET_MB))
    default_modes = _modes(numerics.get("modes"))
    if budget_mb is None or output_step is None:
        return []  # the schema reports it
    budget = budget_mb * variables.MIB
    problems = []

    def check_run(where: str, what: str, model: str, modes: int, t_end: float) -> None:
        size = variables.simulation_bytes(model, modes, t_end, output_step)
        if size <= budget:
            return
        values = variables.values_per_time(model, modes)
        count = variables.output_count(t_end, output_step)
        longest = (math.floor((budget / variables.BYTES_PER_VALUE - modes) / values) - 1) * output_step
        problems.append(Problem(where, f"got {t_end:g} s: {what} ({model}, {modes} modes) would store "
                                f"{count} output times x {values} values x {variables.BYTES_PER_VALUE} "
                                f"bytes = {variables.budget_text(size, budget_mb)}; allowed: " + (
                                    f"t_end <= {longest:.6g} s at numerics.output_step = {output_step:g} s "
                                    "(or a longer output step, or a larger numerics.memory_budget_mb)"
                                    if longest >= 0 else "a larger numerics.memory_budget_mb (it holds not "
                                    "even the first output time)")))

    for name, case in _section(cfg, "cases").items():
        case = case if isinstance(case, dict) else {}
        t_end, modes, model = _positive(case.get("t_end")), _modes(case.get("modes", default_modes)), \
            _name(case.get("model"))
        if t_end is None or modes is None or model not in MODELS:
            continue  # the schema reports it
        outputs = variables.simulation_bytes(model, modes, t_end, output_step)
        if outputs > budget:
            check_run(f"cases.{name}.t_end", f"case {name}", model, modes, t_end)
            continue
        parts = _run_parts(f"cases.{name}", case, modes, t_end)
        total = outputs + sum(part.size for part in parts)
        if total > budget:
            largest = max(parts, key=lambda part: part.size)
            rest = total - largest.size
            problems.append(Problem(largest.where, f"{largest.text}; with the rest of case {name} (its outputs "
                                    f"and arrays: {variables.size_text(rest)}) it would take "
                                    f"{variables.budget_text(total, budget_mb)}; allowed: "
                                    f"{largest.allowed(budget - rest)}, or a larger numerics.memory_budget_mb"))
    validation = _section(cfg, "validation")
    models = [m for m in validation.get("models", []) if _name(m) in MODELS] if isinstance(
        validation.get("models"), list) else []
    study = validation.get("mode_study") if isinstance(validation.get("mode_study"), list) else []
    modes = max((m for m in [default_modes, *study] if _modes(m) is not None), default=None)
    for name, case in _section(validation, "cases").items():
        t_end = _positive(case.get("t_end")) if isinstance(case, dict) else None
        if t_end is not None and models and modes is not None:
            model = max(models, key=lambda m: variables.values_per_time(m, modes))
            check_run(f"validation.cases.{name}.t_end", f"validation run {name}", model, modes, t_end)
    problems += _sweep_memory_problems(_section(cfg, "sweeps"), default_modes, budget_mb)
    return problems


class _Part(NamedTuple):
    """Memory a case takes besides its outputs, for one key: its ``size`` (bytes), the key
    (``where``), what it holds in words (``text``) and ``allowed(room)``, the values of the key that
    fit into ``room`` bytes."""

    size: int
    where: str
    text: str
    allowed: Callable[[float], str]


def _run_parts(where: str, case: Mapping, modes: int, t_end: float) -> list[_Part]:
    """The arrays a run of ``case`` holds besides its outputs, each for the key that sizes it
    (:mod:`hubbeam.results.variables`): a sampled controller's per-sample arrays, a command shaper's
    impulses (convolved and shifting the maneuver's stops), the kernel's tables of a tabulated
    maneuver or reference. Values the schema refuses count nothing."""
    maneuver = _section(case, "maneuver")
    tables = [(f"{where}.maneuver", maneuver), (f"{where}.maneuver.reference", _section(maneuver, "reference"))]
    rows = {path: len(entry["time"]) for path, entry in tables if isinstance(entry.get("time"), list)}
    parts = [_Part(variables.table_bytes(count), f"{path}.time",
                   f"got {count} rows: the kernel's table of them holds {variables.TABLE_VALUES} values per row x "
                   f"{variables.BYTES_PER_VALUE} bytes = {variables.size_text(variables.table_bytes(count))}",
                   lambda room: f"at most {math.floor(room / variables.table_bytes(1))} rows")
             for path, count in rows.items()]
    sampled = _sampled_part(f"{where}.maneuver", maneuver, _modes(_section(maneuver, "design").get("modes", modes)),
                            t_end, _joint(case))
    shaper = _shaper_part(f"{where}.shaper", _section(case, "shaper"), max(rows.values(), default=2))
    return parts + [part for part in (sampled, shaper) if part is not None]


def _joint(case: Mapping) -> bool:
    """Whether the case has a compliant root (``root_spring``): its hub angle ``phi`` a state."""
    return isinstance(case.get("root_spring"), dict)


def _states(model, modes: int, joint: bool) -> tuple[str, ...]:
    """The state names of ``model`` with ``modes`` modes, the hub angle ``phi`` among them with a
    compliant root (``hubbeam.model.root.state_names``)."""
    return root_state_names(model, modes) if joint else model.state_names(modes)


def _sampled_part(where: str, maneuver: Mapping, design_modes: int | None, t_end: float,
                  joint: bool) -> _Part | None:
    """The per-sample arrays of a sampled controller (``maneuver.sampling``), None without one: its
    readings are the design's states (the exact estimator) or its sensors; it estimates the design's
    states and the commands its delay holds back (filtered differences: two per sensor)."""
    sampling, design = _section(maneuver, "sampling"), _section(maneuver, "design")
    sample_time, delay = _positive(sampling.get("sample_time")), _number(sampling.get("delay", 0.0))
    design_model, kind = _name(design.get("model")), _name(_section(sampling, "estimator").get("kind", "exact"))
    sensors = sampling.get("sensors") if isinstance(sampling.get("sensors"), list) else []
    if maneuver.get("kind") != "state_feedback" or sample_time is None or delay is None or delay < 0:
        return None
    if design_model in DESIGN_ONLY_MODELS:
        states = len(LUMPED_STATES)
    elif design_model in MODELS and design_modes is not None:
        states = len(_states(MODELS[design_model], design_modes, joint))
    else:
        return None  # the schema reports the design
    lags = math.floor(delay) + (1 if delay > math.floor(delay) else 0)  # hubbeam.linear.discrete.discretise
    readings, estimated = {"exact": (states, states + lags), "kalman": (len(sensors), states + lags),
                           "filtered_differences": (len(sensors), 2 * len(sensors))}.get(kind, (None, None))
    if readings is None:
        return None  # the schema reports the estimator
    count, values = variables.sample_count(t_end, sample_time), variables.sample_values(readings, estimated)
    size = variables.sampled_loop_bytes(t_end, sample_time, readings, estimated)

    def allowed(room: float) -> str:
        samples = math.floor(room / (variables.BYTES_PER_VALUE * values))
        return (f"sample_time >= {_rounded_up(t_end / (samples - 1))} s (at most {samples} samples up to t_end = "
                f"{t_end:g} s), a shorter t_end" if samples >= 2 else "a shorter t_end")

    return _Part(size, f"{where}.sampling.sample_time",
                 f"got {sample_time:g} s: the sampled controller runs {count} samples up to t_end = {t_end:g} s, each "
                 f"holding {values} values ({readings} readings, {estimated} estimated states and "
                 f"{variables.SAMPLE_VALUES} of the loop itself) x {variables.BYTES_PER_VALUE} bytes = "
                 f"{variables.size_text(size)}", allowed)


def _shaper_part(where: str, shaper: Mapping, stops: int) -> _Part | None:
    """A command shaper's impulses (one shaper per mode, convolved) and the ``stops`` of the
    maneuver each of them shifts; None without a shaper."""
    kind = _name(shaper.get("kind"))
    key = "frequencies" if "frequencies" in shaper else "modes"
    given = shaper.get(key, [1])
    if kind not in variables.SHAPER_IMPULSES or not isinstance(given, list) or not given:
        return None  # the schema reports it
    count = len(given)
    impulses = variables.shaper_impulses(kind, count)
    size = variables.shaper_bytes(impulses, stops)

    def allowed(room: float) -> str:
        most = 0
        while variables.shaper_bytes(variables.shaper_impulses(kind, most + 1), stops) <= room:
            most += 1
        return f"at most {most} {key} for a {kind} shaper" if most else f"no {kind} shaper"

    return _Part(size, f"{where}.{key}", f"got {count} {key}: the {kind} shaper convolves one per mode, up to "
                 f"{variables.SHAPER_IMPULSES[kind]}^{count} = {impulses} impulses, each shifting the {stops} stops "
                 f"of the maneuver: {variables.size_text(size)}", allowed)


def _rounded_up(value: float) -> str:
    """``value`` > 0 rounded up to three significant digits, as text."""
    scale = 10.0 ** (math.floor(math.log10(value)) - 2)
    return f"{math.ceil(value / scale * (1 - 1e-12)) * scale:.3g}"


def _sweep_memory_problems(sweeps: Mapping, default_modes: int, budget_mb: float) -> list[Problem]:
    """The sweeps whose per-run values and dense outputs would exceed the memory budget."""
    output_step = _positive(_section(sweeps, "numerics").get("output_step"))
    problems = []
    for name, spec in _section(sweeps, "maps").items():
        if not isinstance(spec, dict) or output_step is None:
            continue
        grid, maneuver = _section(spec, "grid"), _section(spec, "maneuver")
        counts = [_integer(_section(grid, key).get("num")) for key in grid]
        tf = _positive(_section(grid, "tf").get("stop")) if "tf" in grid else _positive(maneuver.get("tf"))
        t_after, modes = _number(spec.get("t_after")), spec.get("modes", default_modes)
        models, outputs = spec.get("models"), spec.get("outputs")
        if (None in counts or tf is None or t_after is None or _integer(modes) is None
                or not isinstance(models, list) or not isinstance(outputs, list)):
            continue  # the schema reports it
        points = len(models) * math.prod(counts)
        threads = os.cpu_count() or 1
        size = variables.sweep_bytes(points, len(outputs) + variables.SWEEP_VALUES_PER_RUN, tf + t_after,
                                     output_step, modes, threads)
        if size > budget_mb * variables.MIB:
            problems.append(Problem(f"sweeps.maps.{name}", f"got {points} runs ({len(models)} models x "
                                    f"{' x '.join(map(str, counts))} grid points) up to t = {tf + t_after:g} s "
                                    f"on {threads} threads: sweep {name} would take "
                                    f"{variables.budget_text(size, budget_mb)}; allowed: fewer grid points, "
                                    "a shorter t_after or tf, a longer sweeps.numerics.output_step, or a "
                                    "larger numerics.memory_budget_mb"))
    return problems


#: maneuver parameters of each kind (a sweep gives each of the first two kinds either fixed or swept)
MANEUVER_PARAMETERS = kind_keys("maneuver")
#: parameters of each kind of a pd maneuver's reference motion
REFERENCE_PARAMETERS = kind_keys("reference")


def _table_problems(where: str, entry: Mapping, abscissa: str, columns: tuple[str, ...],
                    unit: str) -> list[Problem]:
    """A table's abscissa strictly increases and every column has its length."""
    first = entry.get(abscissa)
    if not isinstance(first, list) or any(_number(v) is None for v in first):
        return []  # the schema reports it
    problems = [Problem(f"{where}.{abscissa}", f"got {show(first)}; allowed: strictly increasing "
                        f"values ({unit})")] if any(b <= a for a, b in itertools.pairwise(first)) else []
    for column in columns:
        values = entry.get(column)
        if isinstance(values, list) and len(values) != len(first) and len(values) >= 2:  # shorter: minItems
            problems.append(Problem(f"{where}.{column}", f"got {len(values)} values; allowed: one "
                                    f"per entry of {where}.{abscissa} ({len(first)})"))
    return problems


def _case_entry_problems(where: str, case: Mapping) -> list[Problem]:
    """The time tables of a maneuver and of its pd reference start at t >= 0 and increase (the
    schema checks each kind's keys)."""
    maneuver = _section(case, "maneuver")
    reference = _section(maneuver, "reference")
    problems = []
    for path, entry, kinds in ((f"{where}.maneuver", maneuver, MANEUVER_PARAMETERS),
                               (f"{where}.maneuver.reference", reference, REFERENCE_PARAMETERS)):
        columns = kinds.get(_name(entry.get("kind")), ())
        if "time" not in columns:
            continue
        problems += _table_problems(path, entry, "time", columns[1:], "s")
        start = _number((entry.get("time") or [None])[0]) if isinstance(entry.get("time"), list) else None
        if start is not None and start < 0:
            problems.append(Problem(f"{path}.time", f"starts at {start}; allowed: times >= 0 s"))
    return problems


#: the modal coordinates and rates of a case's ``initial`` state (schema ``case.initial``), one value per mode
INITIAL_MODAL_KEYS = tuple(key for key in SCHEMA["$defs"]["case"]["properties"]["initial"]["properties"]
                           if key != "hub_speed")
#: a validator of one maneuver (schema ``maneuver``)
MANEUVER_VALIDATOR = Validator({"$ref": "#/$defs/maneuver", "$defs": SCHEMA["$defs"]})


def _initial_problems(where: str, case: Mapping, modes: int | None, check_speed: bool) -> list[Problem]:
    """The case can start from its ``initial`` state: one value per mode (the case's ``modes``),
    no axial coordinates for a model that keeps none (Eq. 40), and, if ``check_speed`` (its
    maneuver's tables are in order), for a prescribed hub the maneuver's own speed at ``t = 0``."""
    spec = _section(case, "initial")
    model = MODELS.get(_name(case.get("model")))
    problems = []
    for key in INITIAL_MODAL_KEYS:
        value = spec.get(key)
        if not isinstance(value, list) or any(_number(v) is None for v in value):
            continue  # the schema reports it
        if modes is not None and len(value) != modes:
            source = f"{where}.modes" if "modes" in case else "numerics.modes"
            problems.append(Problem(f"{where}.initial.{key}", f"got {show(value)}; allowed: a list of {modes} "
                                    f"numbers, one per mode ({source} = {modes}; kg1/2 m, or kg1/2 m s-1 for rates)"))
        elif key in ("q1", "q1_dot") and any(value) and model is not None and not model.keeps_axial:
            problems.append(Problem(f"{where}.initial.{key}", f"got {show(value)}; allowed: zeros or no {key}: "
                                    f"{model.name} keeps no axial coordinates (q1 = 0, Eq. 40)"))
    speed = _number(spec.get("hub_speed"))
    maneuver = _section(case, "maneuver")
    if speed is None or not check_speed or not MANEUVER_VALIDATOR.is_valid(maneuver) \
            or _non_finite_numbers_and_non_text_keys(maneuver, []):
        return problems  # the other checks report the maneuver
    start = maneuver_from_dict(maneuver).start_speed()
    if start is not None and not math.isclose(speed, start, rel_tol=1e-12, abs_tol=1e-12):
        problems.append(Problem(f"{where}.initial.hub_speed", f"got {speed!r}; allowed: {start!r} rad s-1, the "
                                "speed at t = 0 of the prescribed maneuver (or no hub_speed)"))
    return problems


def _feedback_problems(where: str, case: Mapping, modes: int | None) -> list[Problem]:
    """A state feedback's names: gains on states of the simulated model, design weights on states
    of the design model or on measured signals (:data:`hubbeam.configuration.schema.MEASURED_SIGNALS`),
    and a feedforward only with a reference whose acceleration is known (Eq. 43). What needs the
    case's matrices (a steady spin at the design speed, stabilisability) is checked before any job
    by ``hubbeam.control.cases.case_problems``."""
    maneuver = _section(case, "maneuver")
    if maneuver.get("kind") != "state_feedback" or modes is None:
        return []
    problems = []
    model, design = MODELS.get(_name(case.get("model"))), _section(maneuver, "design")
    design_modes = _modes(design.get("modes", modes))
    joint = _joint(case)
    names = {"gains": (_section(maneuver, "gains"),
                       None if model is None else (f"{model.name} with {modes} modes", _states(model, modes, joint)))}
    if _design_model(maneuver) in DESIGN_ONLY_MODELS:  # the lumped model: its states and outputs
        names["design.weights"] = (_section(design, "weights"), (f"the {design['model']} model",
                                                                 LUMPED_STATES + LUMPED_OUTPUTS))
    elif _design_model(maneuver) is not None and design_modes is not None:
        owner = MODELS[design["model"]]
        allowed = _states(owner, design_modes, joint) + MEASURED_SIGNALS
        names["design.weights"] = (_section(design, "weights"), (f"{owner.name} with {design_modes} modes", allowed))
    for key, (values, known) in names.items():
        if known is None:
            continue  # the schema reports the model
        what, allowed_names = known
        problems += [Problem(f"{where}.{key}.{name}", f"unknown name for {what}; allowed: "
                             f"{', '.join(allowed_names)}") for name in values if name not in allowed_names]
    reference = _section(maneuver, "reference")
    if maneuver.get("feedforward") is True and _name(reference.get("kind")) in REFERENCES \
            and not REFERENCES[reference["kind"]].gives_acceleration:
        problems.append(Problem(f"{where}.feedforward", f"got true with reference.kind = {reference['kind']!r}; "
                                "allowed: a reference whose acceleration is known (prescribed, Eq. 43), or "
                                "feedforward false"))
    return problems


def _drive_problems(where: str, case: Mapping) -> list[Problem]:
    """A drive turns the case's commands into volts: a voltage table needs one, an open-loop torque
    takes none, a design weighs the voltage with one and the torque without; the lumped design
    model needs a drive and its held-hub frequency; a sampled controller runs a design, with sensors
    its estimator can use."""
    maneuver = _section(case, "maneuver")
    record = MANEUVERS.get(_name(maneuver.get("kind")))
    if record is None:
        return []  # the schema reports the kind
    if "drive" in case and not isinstance(case["drive"], dict):
        return []  # the schema reports the drive; whether one is given is unknown
    driven = isinstance(case.get("drive"), dict)
    problems = []
    if record.needs_drive and not driven:
        problems.append(Problem(f"{where}.maneuver.kind", f"got {record.kind!r} without a drive; allowed: a case "
                                "with a drive section (its command is a voltage), or a torque_table"))
    if driven and not record.takes_drive:
        problems.append(Problem(f"{where}.drive", f"given with maneuver.kind = {record.kind!r}, an open-loop torque; "
                                "allowed: a voltage_table (or a controller) with a drive, or no drive"))
    if "design" in maneuver and not _design_model(maneuver):  # the schema reports the design
        return problems + _sampling_problems(f"{where}.maneuver", maneuver, None)
    design = _section(maneuver, "design")
    if "torque_weight" in design and driven:
        problems.append(Problem(f"{where}.maneuver.design.torque_weight", "given with a drive, whose input is the "
                                "voltage; allowed: voltage_weight (the same cost is R_tau torque_gain^2)"))
    if "voltage_weight" in design and not driven:
        problems.append(Problem(f"{where}.maneuver.design.voltage_weight", "given without a drive, whose input is "
                                "the hub torque; allowed: torque_weight, or a drive section"))
    lumped = design.get("model") in DESIGN_ONLY_MODELS
    if lumped and "held_frequency" not in design:
        problems.append(Problem(f"{where}.maneuver.design.held_frequency", f"missing for the {design['model']} "
                                "model; allowed: the link's held-hub frequency its spring is fitted to, Hz"))
    if lumped and not driven:
        problems.append(Problem(f"{where}.maneuver.design.model", f"got {design['model']!r} without a drive; "
                                "allowed: a hub-beam model, or a case with a drive (the lumped model's input is the "
                                "voltage)"))
    if "held_frequency" in design and _name(design.get("model")) in MODELS:
        problems.append(Problem(f"{where}.maneuver.design.held_frequency", f"given with model = "
                                f"{design['model']!r}; allowed: only with {', '.join(DESIGN_ONLY_MODELS)}"))
    return problems + _sampling_problems(f"{where}.maneuver", maneuver, lumped)


def _design_model(maneuver: Mapping) -> str | None:
    """The name of the model of ``maneuver``'s LQR design, None without a design or when the schema
    refuses the design or its model."""
    model = _name(_section(maneuver, "design").get("model"))
    return model if model in MODELS or model in DESIGN_ONLY_MODELS else None


def _sampling_problems(where: str, maneuver: Mapping, lumped: bool | None) -> list[Problem]:
    """A sampled controller runs a design; the exact estimator reads the design's states (no sensors),
    the filtered differences need the lumped design (``lumped``; None: a design the schema refuses)
    and its two angles, a Kalman filter sensors. What depends on an estimator the schema refuses is
    left to it."""
    sampling = _section(maneuver, "sampling")
    if not sampling:
        return []
    problems = []
    if "design" not in maneuver:
        problems.append(Problem(f"{where}.sampling", "given without a design; allowed: a design (LQR) to sample, "
                                "not gains or output_feedback"))
    estimator = sampling.get("estimator", {"kind": "exact"})
    estimator = estimator.get("kind") if isinstance(estimator, dict) else None
    if estimator not in ("exact", "kalman", "filtered_differences"):
        return problems  # the schema reports the estimator
    sensors = sampling.get("sensors") if isinstance(sampling.get("sensors"), list) else None
    signals = [sensor.get("signal") for sensor in sensors or [] if isinstance(sensor, dict)
               and isinstance(sensor.get("signal"), str)]  # the schema reports other signals
    if estimator == "exact" and sampling.get("reduce") is True:
        problems.append(Problem(f"{where}.sampling.reduce", "true with the exact estimator, whose readings are the "
                                "design's states (a truncated model's are modal coordinates); allowed: a kalman "
                                "estimator, or reduce false"))
    weights = _section(_section(maneuver, "design"), "weights")
    states = [name for name in weights if name not in MEASURED_SIGNALS]
    if sampling.get("reduce") is True and states:
        problems.append(Problem(f"{where}.design.weights.{states[0]}", "a state's weight with sampling.reduce, whose "
                                "design model's states are modal coordinates; allowed: weights on measured signals "
                                f"({', '.join(MEASURED_SIGNALS)})"))
    if estimator == "exact" and sensors is not None:
        problems.append(Problem(f"{where}.sampling.sensors", "given with the exact estimator, which reads the "
                                "design's states; allowed: no sensors, or a kalman or filtered_differences estimator"))
    if estimator != "exact" and sensors is None:
        problems.append(Problem(f"{where}.sampling.sensors", f"missing for the {estimator} estimator; allowed: "
                                "a list of sensors"))
    if estimator == "filtered_differences":
        if lumped is False:
            problems.append(Problem(f"{where}.sampling.estimator.kind", "got 'filtered_differences' with a design "
                                    f"on a hub-beam model; allowed: a design on {', '.join(DESIGN_ONLY_MODELS)} "
                                    "(its states are the measured angles and their rates), or kalman or exact"))
        if sensors is not None and sorted(signals) != ["deflection_angle", "hub_angle"]:
            problems.append(Problem(f"{where}.sampling.sensors", f"measure {signals}; allowed: hub_angle and "
                                    "deflection_angle, once each, for the filtered differences"))
    if len(set(signals)) < len(signals):
        problems.append(Problem(f"{where}.sampling.sensors", f"measure {signals}; allowed: each signal once"))
    return problems + _process_noise_problems(f"{where}.sampling.estimator", _section(sampling, "estimator"))


def _process_noise_problems(where: str, estimator: Mapping) -> list[Problem]:
    """A Kalman filter needs process noise: without any (``input_noise`` 0, its default, and no
    ``state_noise``) it leaves the free hub's rigid-body mode (``z = 1``, which every design has)
    undisturbed, and ``hubbeam.control.kalman`` refuses it."""
    if estimator.get("kind") != "kalman":
        return []
    noise, states = estimator.get("input_noise", 0.0), estimator.get("state_noise", {})
    if _number(noise) != 0.0 or not isinstance(states, dict) or any(_number(v) != 0.0 for v in states.values()):
        return []  # process noise given, or a value the schema reports
    given = f"got {noise!r}" if "input_noise" in estimator else "missing (default 0)"
    return [Problem(f"{where}.input_noise", f"{given} with no state_noise: the Kalman filter would have no process "
                    "noise, which leaves the free hub's rigid-body mode (z = 1) undisturbed, and the filter is "
                    "refused; allowed: input_noise > 0 (process noise on the input: N m, or V with a drive), or "
                    "state_noise > 0 on a state that moves that mode (such as theta_dot)")]


def _functions_problems(where: str, case: Mapping, beam: Mapping, length: float | None) -> list[Problem]:
    """The loaded beam's modes (``transverse_functions: tip_body``, ``hubbeam.model.matrices.transverse_load``)
    are those of a uniform beam carrying the tip mass or body at its end."""
    if case.get("transverse_functions") != TIP_BODY:
        return []
    if "sections" in beam:
        return [Problem(f"{where}.transverse_functions", f"got {TIP_BODY!r} with a beam of sections; allowed: "
                        f"{CLAMPED_FREE!r} (the loaded beam's modes are those of a uniform beam)")]
    position = _number(_section(case, "tip_mass").get("position"))
    if position is not None and length is not None and position != length:
        return [Problem(f"{where}.transverse_functions", f"got {TIP_BODY!r} with tip_mass.position = {position}; "
                        f"allowed: {CLAMPED_FREE!r}, or the tip mass at the beam's end, beam.length = {length}")]
    return []


def _shaper_problems(where: str, case: Mapping, modes: int | None) -> list[Problem]:
    """A shaper is tuned on a model or given its frequencies, not both; damping goes with given
    frequencies, one ratio each; ``v_tol`` is EI's; the modes tuned to exist."""
    shaper = _section(case, "shaper")
    if not shaper:
        return []
    problems = []
    frequencies = shaper.get("frequencies")
    if frequencies is not None:
        tuning = [key for key in ("model", "speed", "modes", "frequency_ratio") if key in shaper]
        problems += [Problem(f"{where}.{key}", "given with frequencies; allowed: either frequencies (and damping) "
                             "or the tuning keys model, speed, modes and frequency_ratio") for key in tuning]
        damping = shaper.get("damping")
        if isinstance(damping, list) and isinstance(frequencies, list) and len(damping) != len(frequencies):
            problems.append(Problem(f"{where}.damping", f"got {len(damping)} ratios; allowed: one per frequency "
                                    f"({len(frequencies)})"))
    elif "damping" in shaper:
        problems.append(Problem(f"{where}.damping", "given without frequencies; allowed: damping of given "
                                "frequencies (a tuned shaper takes the model's damping)"))
    if "v_tol" in shaper and shaper.get("kind") != "EI":
        problems.append(Problem(f"{where}.v_tol", f"given with kind = {shaper.get('kind')!r}; allowed: only for EI"))
    numbers = shaper.get("modes") if isinstance(shaper.get("modes"), list) else []
    beyond = [mode for mode in numbers if _integer(mode) is not None and modes is not None and mode > modes]
    if beyond:
        problems.append(Problem(f"{where}.modes", f"got {numbers}; allowed: modes 1..{modes} of the case"))
    return problems


#: the forms of a beam (schema ``beam.allOf``): (a validator of its condition, title, the keys of the form)
BEAM_FORMS = tuple((Validator(rule["if"]), rule["then"]["title"], tuple(rule["then"]["required"]))
                   for rule in SCHEMA["properties"]["beam"]["allOf"])


def _beam_problems(beam: Mapping, length: float | None) -> list[Problem]:
    """A beam has the keys of one form only (:data:`BEAM_FORMS`; the schema requires the form's
    keys); stations run from 0 to L."""
    own = next((keys for condition, _, keys in BEAM_FORMS if condition.is_valid(beam)), ())
    given = next((key for key in own if key in beam), None)
    forms = "; ".join(f"{title.removeprefix('for ')}: {', '.join(keys)}" for _, title, keys in BEAM_FORMS)
    problems = [Problem(f"beam.{key}", f"got {show(beam[key])}; not allowed together with beam.{given} "
                        f"(allowed: the keys of one form of the beam -- {forms})")
                for _, _, keys in BEAM_FORMS if keys is not own for key in keys if key in beam and given]
    sections = _section(beam, "sections")
    problems += _table_problems("beam.sections", sections, "x", ("rhoA", "EI", "EA"), "m")
    x = sections.get("x")
    if isinstance(x, list) and x and all(_number(v) is not None for v in x):
        if x[0] != 0:
            problems.append(Problem("beam.sections.x", f"starts at {x[0]}; allowed: the first "
                                    "station at the root, x = 0"))
        if length is not None and abs(x[-1] - length) > 1e-9 * length:
            problems.append(Problem("beam.sections.x", f"ends at {x[-1]}; allowed: the last "
                                    f"station at the tip, x = beam.length = {length}"))
    return problems


def _study_problems(cfg: Mapping, eigen: Mapping, cases: Mapping) -> list[Problem]:
    """A study keeps out of the paper's folders, compares its own cases and ends its eigen grid of
    positions at the tip; the paper's products (``products: [paper]``) need ``eigen.table2_speed``
    for Table 2."""
    problems = []
    products = cfg.get("products")
    if isinstance(products, list) and PAPER in products and "table2_speed" not in eigen:
        problems.append(Problem("eigen.table2_speed", "missing (required for the paper's Table 2, "
                                f"`products: [{PAPER}]`); allowed: {allowed(['eigen', 'table2_speed'], SCHEMA)}"))
    if "study" not in cfg:
        return problems
    study = _section(cfg, "study")
    if study.get("name") in PAPER_FOLDERS:
        problems.append(Problem("study.name", f"got {study['name']!r}, a folder of the paper's "
                                f"products in results/; allowed: any other name ({', '.join(PAPER_FOLDERS)} "
                                "are taken)"))
    stop, length = _number(_section(eigen, "positions").get("stop")), _positive(_section(cfg, "beam").get("length"))
    if stop is not None and length is not None and stop < length:
        problems.append(Problem("eigen.positions.stop", f"got {stop}; allowed: beam.length = {length} "
                                "for a study (its Campbell diagram marks the critical speed with the "
                                "tip mass at the tip)"))
    for name, members in _section(study, "comparisons").items():
        for index, case in enumerate(members if isinstance(members, list) else []):
            if isinstance(case, str) and case not in cases:
                problems.append(Problem(f"study.comparisons.{name}[{index}]", f"got {case!r}; allowed: "
                                        f"a name of cases ({', '.join(sorted(map(str, cases)))})"))
    return problems


def _sweep_problems(sweeps: Mapping, length: float | None) -> list[Problem]:
    """A sweep's grids increase, and its fixed and swept parameters complete the maneuver and the
    tip mass without overlapping; the figure compares models of the sweep."""
    problems = []
    for name, spec in _section(sweeps, "maps").items():
        if not isinstance(spec, dict):
            continue
        where = f"sweeps.maps.{name}"
        grid = _section(spec, "grid")
        for key in grid:
            axis = _section(grid, key)
            start, stop = _number(axis.get("start")), _number(axis.get("stop"))
            if start is not None and stop is not None and stop <= start:
                problems.append(Problem(f"{where}.grid.{key}.stop", f"got {stop}; allowed: a value > "
                                        f"{where}.grid.{key}.start = {start}"))
            if key in ("wf", "tf", "tau_max") and start is not None and start <= 0:
                problems.append(Problem(f"{where}.grid.{key}.start", f"got {start}; allowed: a value > 0"))
            if key == "tip_position" and stop is not None and length is not None and stop > length:
                problems.append(Problem(f"{where}.grid.tip_position.stop", f"got {stop}; allowed: a "
                                        f"position on the beam, <= beam.length = {length}"))
        maneuver = _section(spec, "maneuver")
        needed = MANEUVER_PARAMETERS.get(_name(maneuver.get("kind")))
        if needed is not None:
            for key in ("wf", "tf", "tau_max"):
                fixed, swept = key in maneuver, key in grid
                if key not in needed and swept:
                    problems.append(Problem(f"{where}.grid.{key}", f"swept, but kind is {maneuver['kind']!r}; "
                                            f"allowed parameters: {', '.join(needed)}"))
                elif key not in needed and fixed:
                    problems.append(Problem(f"{where}.maneuver.{key}",
                                            f"got {show(maneuver[key])}; not allowed when kind is "
                                            f"{maneuver['kind']!r}; allowed keys: kind, {', '.join(needed)}"))
                elif key in needed and fixed == swept:
                    problems.append(Problem(f"{where}.maneuver.{key}",
                                            ("given both here and under grid" if fixed else "missing")
                                            + f"; allowed: exactly one of {where}.maneuver.{key} or "
                                            f"{where}.grid.{key}"))
        tip = _section(spec, "tip_mass")
        for key, grid_key in (("mass", "tip_mass"), ("position", "tip_position")):
            if key in tip and grid_key in grid:
                problems.append(Problem(f"{where}.tip_mass.{key}", f"given, but {grid_key} is swept; "
                                        f"allowed: either {where}.tip_mass.{key} or {where}.grid.{grid_key}"))
        position = _number(tip.get("position"))
        if position is not None and length is not None and position > length:
            problems.append(Problem(f"{where}.tip_mass.position",
                                    f"got {position}; allowed: 0 <= position <= beam.length = {length}"))
        models = spec.get("models") if isinstance(spec.get("models"), list) else []
        figure = _section(spec, "figure")
        if not models or not all(_name(model) in MODELS for model in models):
            continue  # the schema reports the models
        for key in ("model", "reference"):
            if key in figure and figure[key] not in models:
                problems.append(Problem(f"{where}.figure.{key}",
                                        f"got {figure[key]!r}; allowed: one of {where}.models = {models}"))
        if "model" in figure and figure.get("model") == figure.get("reference"):
            problems.append(Problem(f"{where}.figure.reference",
                                    f"got {figure['reference']!r}; allowed: a model other than figure.model"))
    return problems


def is_multiple(value: float, step: float) -> bool:
    """``value`` is a whole number of ``step`` (to 1e-9 relative): the rule of the startup checks
    and of the Exudyn model (``hubbeam.validation.exudyn_model``), which relies on them."""
    ratio = value / step
    return abs(ratio - round(ratio)) <= 1e-9 * max(ratio, 1.0)


def _validation_problems(validation: Mapping, length: float | None,
                         output_step: float | None) -> list[Problem]:
    """The validation section's mode counts increase, its grids and steps fit the output grid,
    and a tip mass sits on a node of every Exudyn mesh it is simulated on."""
    problems = []
    published = _section(validation, "published")
    modes = published.get("modes")
    if isinstance(modes, list) and all(_integer(m) is not None for m in modes):
        if any(later <= earlier for earlier, later in zip(modes, modes[1:])):
            problems.append(Problem("validation.published.modes", f"got {modes}; allowed: increasing "
                                    "integers (the largest count is the result)"))
    gammas = _section(published, "gammas")
    start, stop = _number(gammas.get("start")), _number(gammas.get("stop"))
    if start is not None and stop is not None and stop <= start:
        problems.append(Problem("validation.published.gammas.stop",
                                f"got {stop}; allowed: a value > validation.published.gammas.start = {start}"))
    exudyn, convergence = _section(validation, "exudyn"), _section(validation, "convergence")
    if output_step is not None:
        steps = [("validation.exudyn.time_step", exudyn.get("time_step"))]
        time_steps = convergence.get("time_steps")
        if isinstance(time_steps, list):
            steps += [(f"validation.convergence.time_steps[{i}]", v) for i, v in enumerate(time_steps)]
        for where, value in steps:
            step = _positive(value)
            if step is not None and not is_multiple(output_step, step):
                problems.append(Problem(where, f"got {step}; allowed: a step that divides "
                                        f"numerics.output_step = {output_step} a whole number of times"))
    meshes = [("validation.exudyn.elements", _integer(exudyn.get("elements")))]
    elements = convergence.get("elements")
    study_meshes = [(f"validation.convergence.elements[{i}]", _integer(e))
                    for i, e in enumerate(elements)] if isinstance(elements, list) else []
    for name, case in _section(validation, "cases").items():
        if not isinstance(case, dict):
            continue
        where = f"validation.cases.{name}"
        t_end = _positive(case.get("t_end"))
        if t_end is not None and output_step is not None and not is_multiple(t_end, output_step):
            problems.append(Problem(f"{where}.t_end", f"got {t_end}; allowed: a multiple of "
                                    f"numerics.output_step = {output_step}"))
        tip = _section(case, "tip_mass")
        position, mass = _number(tip.get("position")), _number(tip.get("mass"))
        if position is None or length is None:
            continue
        if position > length:
            problems.append(Problem(f"{where}.tip_mass.position",
                                    f"got {position}; allowed: 0 <= position <= beam.length = {length}"))
            continue
        if not mass:
            continue
        for mesh, count in meshes + (study_meshes if convergence.get("case") == name else []):
            if count is not None and count >= 1 and not is_multiple(position, length / count):
                problems.append(Problem(f"{where}.tip_mass.position", f"got {position}; allowed: a node "
                                        f"of the Exudyn mesh, a multiple of beam.length / {mesh} = "
                                        f"{length / count:g} m"))
    return problems


def _section(mapping: Mapping, key: str) -> Mapping:
    value = mapping.get(key)
    return value if isinstance(value, dict) else {}


def _number(value: Any) -> float | None:
    """``value`` as float if it is a finite YAML number, else None (the schema reports it)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
        return float(value)
    return None


def _positive(value: Any) -> float | None:
    """``value`` as float if it is a finite YAML number > 0, else None (the schema reports it)."""
    number = _number(value)
    return number if number is not None and number > 0.0 else None


def _integer(value: Any) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None


def _modes(value: Any) -> int | None:
    """``value`` if it is a number of modes the schema accepts (an integer in ``MIN_MODES..MAX_MODES``),
    else None: the schema reports it, and a check must not build names or sizes from it."""
    modes = _integer(value)
    return modes if modes is not None and limits.MIN_MODES <= modes <= limits.MAX_MODES else None


def _name(value: Any) -> str | None:
    """``value`` if it is text (a name to look up: a model, a kind), else None (the schema reports it)."""
    return value if isinstance(value, str) else None


def _non_finite_numbers_and_non_text_keys(node: Any, parts: list) -> list[Problem]:
    """Keys that are not text, and numbers that are not finite or beyond :data:`LARGEST_NUMBER`."""
    problems = []
    if isinstance(node, dict):
        for key, value in node.items():
            if not isinstance(key, str):
                problems.append(Problem(key_path(parts + [str(key)]),
                                        f"key {key!r} is read by YAML as {type_name(key)}; "
                                        f"allowed: text keys (write \"{key}\")"))
            problems += _non_finite_numbers_and_non_text_keys(value, parts + [str(key)])
    elif isinstance(node, list):
        for index, item in enumerate(node):
            problems += _non_finite_numbers_and_non_text_keys(item, parts + [index])
    elif isinstance(node, float) and not math.isfinite(node):
        problems.append(Problem(key_path(parts), f"got {node}; allowed: a finite number"))
    elif isinstance(node, (int, float)) and not isinstance(node, bool) and abs(node) > LARGEST_NUMBER:
        problems.append(Problem(key_path(parts), f"got {node:g}; allowed: a number of magnitude at most "
                                f"{LARGEST_NUMBER:g} (SI units; beyond, the products of the model's quantities "
                                "overflow double precision)"))
    return problems
