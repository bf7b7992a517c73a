"""The variables of a simulation dataset, and the memory a run's outputs take.

The tables here name every variable :func:`hubbeam.simulation.simulate.build_dataset` writes; the startup
checks (:mod:`hubbeam.configuration.load`) count them to estimate, before anything runs, the memory a case, a
validation run or a sweep needs (:func:`simulation_bytes`, :func:`sweep_bytes`) and reject one
above ``numerics.memory_budget_mb``. A case also holds arrays that grow with other counts than its
output times, counted here too: a sampled controller's arrays per sample (:func:`sampled_loop_bytes`)
and a command shaper's impulses, convolved with the maneuver's table (:func:`shaper_bytes`,
:func:`table_bytes`). Importing this module is cheap (no numba, no xarray).
"""

from __future__ import annotations

import math

from hubbeam.model.models import model

#: variable -> (dimensions, UDUNITS units, long name)
VARIABLES = {
    "theta": (("time",), "rad", "hub angle theta"),
    "theta_dot": (("time",), "rad s-1", "hub angular velocity"),
    "theta_ddot": (("time",), "rad s-2", "hub angular acceleration"),
    "hub_torque": (("time",), "N m",
                   "hub torque (applied to a free hub, or required by a prescribed motion)"),
    "Q_theta": (("time",), "N m", "velocity-dependent generalised force Q_theta (Eq. 32)"),
    "q1": (("time", "mode"), "kg1/2 m", "axial modal coordinates q1 (unit modal mass modes)"),
    "q2": (("time", "mode"), "kg1/2 m", "transverse modal coordinates q2 (unit modal mass modes)"),
    "tip_transverse": (("time",), "m", "transverse tip deflection v(L) = f2(L) q2"),
    "tip_axial": (("time",), "m", "pure axial tip deformation w1(L) = f1(L) q1"),
    "tip_foreshortening": (("time",), "m", "tip foreshortening wc(L) = -q2' S(L) q2 / 2"),
    "body_transverse": (("time",), "m", "transverse displacement of the tip body's centre "
                        "(f2(l) + e f2'(l)) q2 (the beam tip's without a tip mass)"),
    "body_axial": (("time",), "m", "axial displacement of the tip body's centre "
                   "f1(l) q1 - q2' (S(l) + e f2'(l)' f2'(l)) q2 / 2"),
    "energy": (("time",), "J", "total mechanical energy T + U"),
    "angular_momentum": (("time",), "kg m2 s-1", "angular momentum about the hub axis"),
}
#: cumulative integrals from t = 0 (``simulate.cumulative_integral``) -> (integrand: output
#: column names whose product it is, units, long name)
CUMULATIVE_VARIABLES = {
    "work": (("hub_torque", "theta_dot"), "J", "cumulative work of the hub torque"),
    "dissipated_energy": (("dissipation_rate",), "J", "cumulative energy dissipated by damping"),
}
#: a case with a drive only (``hubbeam.model.drive``): its voltage and the gearbox's torque
DRIVE_VARIABLES = {
    "hub_voltage": (("time",), "V", "voltage across the motor (a free hub's command clipped to the limit, or "
                    "what a prescribed motion needs)"),
    "motor_torque": (("time",), "N m", "torque of the gearbox on the hub before the hub's friction"),
}
#: a sampled controller only (``hubbeam.simulation.sampled``): its records at every sample ``t_k``
SAMPLE_VARIABLES = {
    "measured": (("sample", "sensor"), "1", "what the controller read from each sensor (noise and "
                 "quantisation included), in the sensor's unit (attribute sensor_units)"),
    "sensed": (("sample", "sensor"), "1", "each sensor's noise-free signal after its analog low-pass, in "
               "the sensor's unit"),
    "estimate": (("sample", "estimate_state"), "1", "the controller's estimate of the design's state "
                 "deviation from the reference, in the state's unit (attribute state_units)"),
    "command": (("sample",), "1", "the control law's command before saturation (V with a drive, else N m)"),
    "applied": (("sample",), "1", "the saturated command the hold applies after the delay (V with a drive, "
                "else N m)"),
}
#: runs with a compliant root only (``hubbeam.model.root``, ``docs/compliant-root.md``): ``theta``
#: and its rates are the beam's root's (their long names here), the hub's angle, rate and
#: acceleration (the motor side) join, and the spring's torque (``hub_torque``, ``energy``,
#: ``angular_momentum`` and ``dissipated_energy`` are the hub's and the whole system's, spring and
#: damper included)
JOINT_VARIABLES = {
    "theta": (("time",), "rad", "beam root angle theta"),
    "theta_dot": (("time",), "rad s-1", "beam root angular velocity"),
    "theta_ddot": (("time",), "rad s-2", "beam root angular acceleration"),
    "hub_angle": (("time",), "rad", "hub (motor side) angle phi"),
    "hub_speed": (("time",), "rad s-1", "hub (motor side) angular velocity"),
    "hub_acceleration": (("time",), "rad s-2", "hub (motor side) angular acceleration"),
    "spring_torque": (("time",), "N m", "torque of the root's spring and damper on the link, "
                      "k (phi - theta) + c (phi' - theta')"),
}
#: a compliant root's work of the hub torque: on the hub's rate, not the root's
JOINT_WORK = ("hub_torque", "hub_speed")
#: CFOAM only: the high-order terms FOAM drops, along the CFOAM trajectory (note 5, Fig. 3)
HIGH_ORDER_VARIABLES = {
    "dM_thth": (("time",), "kg m2", "CFOAM minus FOAM rotary inertia M_thth (Eq. 35)"),
    "dQ_theta": (("time",), "N m", "CFOAM minus FOAM generalised force of the theta equation"),
    "dQ_q1": (("time", "mode"), "N kg-1/2", "CFOAM minus FOAM axial generalised force"),
    "dQ_q2": (("time", "mode"), "N kg-1/2", "CFOAM minus FOAM transverse generalised force"),
}

#: every value is a float64 (or int64) of 8 bytes
BYTES_PER_VALUE = 8
MIB = 2**20


def output_count(t_end: float, output_step: float) -> int:
    """Times of the uniform output grid ``0, dt, 2 dt, ...`` up to the last multiple of ``dt``
    <= ``t_end`` (to 1e-9 steps)."""
    return int(math.floor(t_end / output_step + 1e-9)) + 1


def dataset_variables(name: str, driven: bool = False, joint: bool = False) -> dict:
    """The variables on the output grid (besides :data:`CUMULATIVE_VARIABLES`) of a simulation
    dataset of the model ``name``: :data:`VARIABLES`, :data:`HIGH_ORDER_VARIABLES` for a model with
    ``high_order_outputs`` (``hubbeam.model.models``), :data:`DRIVE_VARIABLES` for a ``driven``
    hub and, with a compliant root (``joint``), :data:`JOINT_VARIABLES`."""
    return (VARIABLES | (HIGH_ORDER_VARIABLES if model(name).high_order_outputs else {})
            | (DRIVE_VARIABLES if driven else {}) | (JOINT_VARIABLES if joint else {}))


def values_per_time(name: str, modes: int) -> int:
    """Values a simulation dataset of the model ``name`` with ``modes`` modes stores per output
    time: one per scalar variable, ``modes`` per modal one, the cumulative integrals and the
    time."""
    variables = dataset_variables(name)
    return (sum(modes if "mode" in dims else 1 for dims, _, _ in variables.values())
            + len(CUMULATIVE_VARIABLES) + 1)


def simulation_bytes(model: str, modes: int, t_end: float, output_step: float) -> int:
    """Bytes of the outputs of one simulation: output times x :func:`values_per_time` x 8, plus
    the mode coordinate. The kernel's output array holds about as much again while the dataset
    is built from it."""
    return BYTES_PER_VALUE * (output_count(t_end, output_step) * values_per_time(model, modes) + modes)


#: values a sweep keeps per run besides its ``outputs``: the kernel's results (peak, peak time,
#: residual, stop time), status and six counters (``hubbeam.core.sweep``), and the dataset's
#: diverged, status, stopped_at, n_steps and n_rhs (``hubbeam.simulation.sweep.build_dataset``)
SWEEP_VALUES_PER_RUN = 4 + 1 + 6 + 5


def sweep_bytes(points: int, stored: int, t_end: float, output_step: float, modes: int,
                threads: int) -> int:
    """Bytes of a sweep of ``points`` runs that keeps ``stored`` values per run, the longest
    running to ``t_end``: the per-run values, plus, on each of ``threads`` threads, the dense
    output of one run (times, positions and velocities of at most ``1 + 2 modes`` coordinates
    on the output grid of ``hubbeam.core.sweep.output_grid``, which has at most two more times
    than :func:`output_count`)."""
    per_run = (output_count(t_end, output_step) + 2) * (1 + 2 * (1 + 2 * modes))
    return BYTES_PER_VALUE * (points * stored + threads * per_run)


#: 8-byte values a sampled controller's run holds per sample ``t_k`` besides those of its sensors and
#: estimated states (``hubbeam.simulation.sampled.loop_arrays`` and ``held_table``): the sample time and
#: the switch time ``(k + D) Ts``, the stops of the integration (their union, two per sample, and the
#: concatenation and sorted copy numpy's ``union1d`` makes of them, four more), the held command's
#: table (a time and a value), and the records' ``t``, ``command`` and ``applied``
SAMPLE_VALUES = 2 + 2 + 4 + 2 + 3
#: values per sample and sensor: its noise draw and the records ``measured`` and ``sensed``
SENSOR_VALUES = 3
#: values per sample and estimated state: the record ``estimate``
ESTIMATE_VALUES = 1


def sample_count(t_end: float, sample_time: float) -> int:
    """Samples ``t_k = k Ts <= t_end`` of a sampled controller (``SampledLoop.sample_times``)."""
    return int(math.floor(t_end / sample_time + 1e-9)) + 1


def sample_values(sensors: int, estimated: int) -> int:
    """Values a sampled controller's run holds per sample with ``sensors`` sensors (readings) and
    ``estimated`` estimated states (:data:`SAMPLE_VALUES` and the rest)."""
    return SAMPLE_VALUES + SENSOR_VALUES * sensors + ESTIMATE_VALUES * estimated


def sampled_loop_bytes(t_end: float, sample_time: float, sensors: int, estimated: int) -> int:
    """Bytes of the per-sample arrays of a sampled controller run to ``t_end`` every ``sample_time``
    (:func:`sample_count` x :func:`sample_values` x 8): its records, which the dataset keeps, its
    noise, its sample and switch times, the stops of the integration and the held command's table."""
    return BYTES_PER_VALUE * sample_count(t_end, sample_time) * sample_values(sensors, estimated)


#: impulses of a shaper of each kind on one mode (``hubbeam.model.shapers``); a shaper on several modes
#: convolves one per mode, so it has at most their product
SHAPER_IMPULSES = {"ZV": 2, "ZVD": 3, "EI": 3}
#: values per impulse while a shaper on several modes is convolved and held
#: (``hubbeam.model.shapers.convolve``: the outer sums and products of times and amplitudes, the sorted
#: keys, their first indices and inverse, the merged amplitudes; the kernel's array of times and amplitudes)
IMPULSE_VALUES = 2 + 4 + 2
#: values per impulse and stop of the maneuver the shaper shifts (``hubbeam.model.shapers.shaped_stops``:
#: the outer sum, its sorted copy, the distinct stops)
SHIFTED_STOP_VALUES = 3


def shaper_impulses(kind: str, modes: int) -> int:
    """The most impulses a ``kind`` shaper on ``modes`` modes has (:data:`SHAPER_IMPULSES`; coinciding
    impulses merge, so it may have fewer)."""
    return SHAPER_IMPULSES[kind] ** modes


def shaper_bytes(impulses: int, stops: int) -> int:
    """Bytes of a shaper of ``impulses`` impulses shaping a maneuver with ``stops`` stops (times where
    it is not smooth, besides its start): the convolution and the shifted stops."""
    return BYTES_PER_VALUE * impulses * (IMPULSE_VALUES + SHIFTED_STOP_VALUES * (stops + 1))


#: values a tabulated maneuver (or reference) holds per row while the kernels' packed table is built
#: (``hubbeam.model.maneuvers.packed_table``): the table (time, integral, four cubic coefficients), its
#: parts before they are joined, the row's time and value as floats and the spline's own coefficients
TABLE_VALUES = 6 + 6 + 2 + 4


def table_bytes(rows: int) -> int:
    """Bytes of the kernel's packed table of a tabulated maneuver of ``rows`` rows, and its spline."""
    return BYTES_PER_VALUE * rows * TABLE_VALUES


def size_text(size: int) -> str:
    """``size`` bytes in KiB to PiB, for a message."""
    exponent = min(max(int(math.log(max(size, 1), 1024)), 1), 5)
    unit = ("B", "KiB", "MiB", "GiB", "TiB", "PiB")[exponent]
    return f"{size / 1024**exponent:.4g} {unit}"


def budget_text(size: int, budget_mb: float) -> str:
    """``size`` bytes against a budget in MiB, for a message."""
    exponent = min(max(int(math.log(max(size, 1), 1024)), 2), 5)
    unit = ("B", "KiB", "MiB", "GiB", "TiB", "PiB")[exponent]
    return (f"{size / 1024**exponent:.4g} {unit}, above the memory budget numerics.memory_budget_mb = "
            f"{budget_mb:g} MiB")
