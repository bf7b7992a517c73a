"""The fit: bounded weighted least squares from several starts, intervals, identifiability, validation.

:func:`fit` minimises ``sum r_i(p)^2`` over the free parameters ``p`` within their bounds, ``r``
the weighted residuals of every fitted experiment (:mod:`hubbeam.identification.predictions`), with
``scipy.optimize.least_squares`` (trust-region reflective, forward-difference Jacobian). The
parameters are scaled to their bounds, ``x = (p - lower) / (upper - lower)`` in ``[0, 1]``, so that
the problem is conditioned by the physics, not by the units. Least squares on a nonlinear model
has local minima (a mode matched to the wrong peak), so it starts from the parameters' starts and
from ``starts - 1`` points of a Latin hypercube over the bounds (``scipy.stats.qmc``, seeded), and
keeps the lowest cost.

At the minimum ``x*`` (Seber and Wild, *Nonlinear Regression*, 1989, Sec. 2.1 and 5.2):

* the Jacobian ``J = dr/dx`` by central differences (one-sided at a bound);
* the residuals' scale ``s^2 = |r|^2 / (m - q)`` (``m`` residuals, ``q`` parameters), which
  corrects the stated uncertainties of the data by a common factor;
* the covariance ``cov x = s^2 (J^T J)^-1``, ``cov p = S cov x S`` with ``S = diag(upper -
  lower)``; standard errors, the correlation matrix and 95 % intervals ``p +- t_{0.975, m-q}
  se`` (Student's t);
* identifiability, a result and not a failure: a parameter is *not identifiable* when it ends at
  a bound (within :data:`AT_BOUND` of the range), when the Jacobian is near singular (the ratio of
  its smallest to its largest singular value below :data:`SINGULAR`; the parameter with the
  largest share of the weakest direction is set aside and the test repeated), when its
  correlation with another parameter exceeds :data:`CORRELATED` in magnitude, or when the data do
  not narrow it: its 95 % interval is wider than its bounds (the Jacobian is near singular on the
  scale of the noise, though not of the rounding: the damping of a clamp seen only through the
  frequencies it barely moves). The intervals of the others are computed with those set aside
  held at their fitted values (a bound or a singular direction has no interval: NaN); correlated
  and unnarrowed parameters keep their (wide) intervals.

:func:`validate` predicts a held-out experiment with the fitted values and reports its errors.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import scipy.optimize
import scipy.stats

from hubbeam.identification.experiments import Experiment, FrequencyResponse, ModalTest, TimeSeries
from hubbeam.identification.parameters import Parameter, ParameterError, is_sensor, kind_of
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.predictions import Prediction, check_experiment, predict, weighted_residuals

#: a parameter within this fraction of its range from a bound is at the bound
AT_BOUND = 1e-6
#: the Jacobian (scaled to the bounds) is near singular below this ratio of extreme singular values
SINGULAR = 1e-6
#: two parameters whose correlation exceeds this in magnitude cannot be told apart
CORRELATED = 0.99
#: the interval's coverage
CONFIDENCE = 0.95


@dataclass(frozen=True, eq=False)
class Validation:
    """The fitted model on an experiment: the RMS of its weighted residuals (about 1 when the model
    explains it to the stated uncertainties) and a relative ``error``: the RMS relative frequency
    error (modal test), the RMS of ``|ln H_model / H|`` (frequency response, about the relative
    magnitude error), or ``1 - fit``, ``fit = 1 - |y - y_model| / |y - mean y|`` over the signals
    (time series, as MATLAB's ``compare`` reports it)."""

    experiment: str
    kind: str
    rms_weighted: float
    error: float
    prediction: Prediction
    residuals: np.ndarray


@dataclass(frozen=True, eq=False)
class FitResult:
    """The fit (module docstring): per parameter (in ``parameters``' order) the fitted ``value``,
    ``standard_error``, 95 % interval ``lower_95``, ``upper_95`` (NaN where there is none),
    ``identifiable`` and the ``reason`` when not; the ``correlation`` matrix; ``s2`` and ``dof``;
    the ``cost`` ``|r|^2 / 2`` and the cost from every start (``start_costs``, ``start_points``);
    per fitted experiment its residuals and prediction (``fitted``), per held-out one its
    :class:`Validation`; the Jacobian's singular values (scaled)."""

    case: str
    parameters: tuple[Parameter, ...]
    value: np.ndarray
    standard_error: np.ndarray
    lower_95: np.ndarray
    upper_95: np.ndarray
    correlation: np.ndarray
    identifiable: np.ndarray
    reason: tuple[str, ...]
    s2: float
    dof: int
    cost: float
    start_points: np.ndarray
    start_costs: np.ndarray
    singular_values: np.ndarray
    fitted: Mapping[str, Validation]
    validations: Mapping[str, Validation] = field(default_factory=dict)
    evaluations: int = 0
    seconds: float = 0.0
    message: str = ""

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(parameter.key for parameter in self.parameters)

    @property
    def values(self) -> dict[str, float]:
        """The fitted values by key."""
        return dict(zip(self.keys, self.value.tolist()))


class Problem:
    """The residual function of ``experiments`` on ``plant`` over ``parameters`` (scaled to their
    bounds); checks that every experiment can be predicted and every sensor's parameter measured."""

    def __init__(self, plant: CasePlant, experiments: Sequence[Experiment], parameters: Sequence[Parameter]):
        names = [experiment.name for experiment in experiments]
        if not experiments or len(set(names)) < len(names):
            raise ValueError(f"experiments {names}; allowed: at least one, with distinct names")
        for experiment in experiments:
            check_experiment(plant, experiment)
        measured = {signal for experiment in experiments if isinstance(experiment, TimeSeries)
                    for signal in experiment.signals}
        for parameter in parameters:
            kind_of(parameter.key)
            if is_sensor(parameter.key) and parameter.key.split(".")[1] not in measured:
                raise ParameterError(f"{parameter.key}: no fitted time series measures {parameter.key.split('.')[1]}; "
                                     f"allowed: sensors of {', '.join(sorted(measured)) or 'none'}")
        self.plant, self.experiments, self.parameters = plant, tuple(experiments), tuple(parameters)
        self.evaluations = 0

    def values(self, x) -> dict[str, float]:
        """The parameter values at the scaled point ``x``."""
        return {parameter.key: float(parameter.unscaled(xi)) for parameter, xi in zip(self.parameters, x)}

    def predictions(self, x) -> list[Prediction]:
        values = self.values(x)
        return [predict(self.plant, experiment, values) for experiment in self.experiments]

    def __call__(self, x) -> np.ndarray:
        self.evaluations += 1
        return np.concatenate([weighted_residuals(experiment, prediction)
                               for experiment, prediction in zip(self.experiments, self.predictions(x))])

    def jacobian(self, x, step: float) -> np.ndarray:
        """``dr/dx`` by central differences of ``step`` (forward or backward at a bound)."""
        columns = []
        for i in range(x.size):
            up, down = x.copy(), x.copy()
            up[i] = min(x[i] + step, 1.0)
            down[i] = max(x[i] - step, 0.0)
            columns.append((self(up) - self(down)) / (up[i] - down[i]))
        return np.column_stack(columns)


def _start_points(parameters: Sequence[Parameter], starts: int, seed: int) -> np.ndarray:
    first = np.array([parameter.scaled(parameter.start) for parameter in parameters])
    if starts <= 1:
        return first[None, :]
    sampled = scipy.stats.qmc.LatinHypercube(d=len(parameters), seed=seed).random(starts - 1)
    return np.vstack([first, sampled])


def _identifiability(J: np.ndarray, x: np.ndarray, keys: Sequence[str]):
    """``(kept, reasons)``: the columns of ``J`` that stay and the reason of every other
    (module docstring: bounds, then near-singular directions)."""
    reasons = [""] * x.size
    for i, xi in enumerate(x):
        if xi <= AT_BOUND or xi >= 1.0 - AT_BOUND:
            reasons[i] = f"at its {'lower' if xi <= 0.5 else 'upper'} bound"
    kept = [i for i in range(x.size) if not reasons[i]]
    while kept:
        # the full V (n x n) is needed only with fewer residuals than parameters (its last row is then
        # a null direction); the full U of a long Jacobian (m x m) never is
        sigma, vt = np.linalg.svd(J[:, kept], full_matrices=J.shape[0] < len(kept))[1:]
        sigma = np.concatenate([sigma, np.zeros(len(kept) - sigma.size)])  # fewer residuals than parameters
        if sigma[0] > 0.0 and sigma[-1] >= SINGULAR * sigma[0]:
            break
        weakest = kept[int(np.argmax(np.abs(vt[-1])))]
        ratio = sigma[-1] / sigma[0] if sigma[0] > 0.0 else 0.0
        reasons[weakest] = (f"near-singular Jacobian: singular value ratio {ratio:.2g} < {SINGULAR:g} in the "
                            f"direction of {keys[weakest]}")
        kept.remove(weakest)
    return kept, reasons


def fit(plant: CasePlant, experiments: Sequence[Experiment], parameters: Sequence[Parameter], *,
        starts: int = 5, seed: int = 0, diff_step: float | None = None, max_nfev: int = 200,
        validation: Sequence[Experiment] = ()) -> FitResult:
    """Fit ``parameters`` of the case of ``plant`` to ``experiments`` (module docstring): ``starts``
    starting points (the parameters' starts first), the Latin hypercube seeded by ``seed``;
    ``diff_step`` the finite-difference step in the scaled parameters (default ``1e-6``, ``1e-4``
    with a time series, whose integrator's error is larger); ``validation`` the held-out
    experiments predicted with the fitted values."""
    if not parameters:
        raise ValueError("parameters: none; allowed: at least one free parameter")
    began = time.perf_counter()
    problem = Problem(plant, experiments, parameters)
    for experiment in validation:
        check_experiment(plant, experiment)
    if diff_step is None:
        diff_step = 1e-4 if any(isinstance(e, TimeSeries) for e in experiments) else 1e-6
    points = _start_points(parameters, starts, seed)
    best, costs = None, []
    for x0 in points:
        found = scipy.optimize.least_squares(problem, x0, bounds=(0.0, 1.0), method="trf", x_scale=1.0,
                                             diff_step=diff_step, max_nfev=max_nfev, xtol=1e-10, ftol=1e-12,
                                             gtol=1e-10)
        costs.append(found.cost)
        if best is None or found.cost < best.cost:
            best = found
    x = np.clip(best.x, 0.0, 1.0)
    r = problem(x)
    J = problem.jacobian(x, 10.0 * diff_step)
    keys = [parameter.key for parameter in parameters]
    kept, reasons = _identifiability(J, x, keys)
    m, q = J.shape
    dof = m - q
    s2 = float(r @ r / dof) if dof > 0 else math.nan
    span = np.array([parameter.upper - parameter.lower for parameter in parameters])
    se = np.full(q, math.nan)
    correlation = np.full((q, q), math.nan)
    if kept and dof > 0:
        covariance = s2 * np.linalg.inv(J[:, kept].T @ J[:, kept])
        deviation = np.sqrt(np.diag(covariance))
        se[kept] = deviation * span[kept]
        correlation[np.ix_(kept, kept)] = covariance / np.outer(deviation, deviation)
        for a, i in enumerate(kept):
            for b, j in enumerate(kept):
                rho = covariance[a, b] / (deviation[a] * deviation[b])
                if i != j and abs(rho) > CORRELATED:
                    reasons[i] = reasons[i] or f"correlation {rho:+.4f} with {keys[j]} (|rho| > {CORRELATED:g})"
    value = np.array([parameter.unscaled(xi) for parameter, xi in zip(parameters, x)])
    quantile = scipy.stats.t.ppf(0.5 + CONFIDENCE / 2.0, dof) if dof > 0 else math.nan
    for i in kept:
        if 2.0 * quantile * se[i] > span[i]:
            reasons[i] = reasons[i] or (f"the data do not narrow it: its {CONFIDENCE:.0%} interval, "
                                        f"{2.0 * quantile * se[i]:.3g} wide, is wider than its bounds ({span[i]:.3g})")
    values = problem.values(x)
    fitted = {experiment.name: _validation(experiment, prediction)
              for experiment, prediction in zip(problem.experiments, problem.predictions(x))}
    held_out = {experiment.name: _validation(experiment, predict(plant, experiment, values))
                for experiment in validation}
    return FitResult(case=plant.case.label, parameters=tuple(parameters), value=value, standard_error=se,
                     lower_95=value - quantile * se, upper_95=value + quantile * se, correlation=correlation,
                     identifiable=np.array([not reason for reason in reasons]), reason=tuple(reasons), s2=s2, dof=dof,
                     cost=float(r @ r / 2.0), start_points=np.array([p.unscaled(points[:, i]) for i, p in
                                                                      enumerate(parameters)]).T,
                     start_costs=np.array(costs), singular_values=np.linalg.svd(J, compute_uv=False),
                     fitted=fitted, validations=held_out, evaluations=problem.evaluations,
                     seconds=time.perf_counter() - began, message=str(best.message))


def _validation(experiment: Experiment, prediction: Prediction) -> Validation:
    r = weighted_residuals(experiment, prediction)
    values = prediction.values
    if isinstance(experiment, ModalTest):
        error = float(np.sqrt(np.mean((values["frequency"] / experiment.frequency - 1.0) ** 2)))
    elif isinstance(experiment, FrequencyResponse):
        error = float(np.sqrt(np.mean(np.log(np.abs(values["response"] / experiment.response)) ** 2)))
    else:
        measured = np.concatenate([experiment.signals[s] - experiment.signals[s].mean() for s in experiment.signals])
        model = np.concatenate([values[s] - experiment.signals[s].mean() for s in experiment.signals])
        error = float(np.linalg.norm(model - measured) / np.linalg.norm(measured))
    return Validation(experiment.name, experiment.kind, float(np.sqrt(np.mean(r**2))), error, prediction, r)


def validate(plant: CasePlant, result: FitResult, experiment: Experiment) -> Validation:
    """The fitted model of ``result`` on the held-out ``experiment`` (:class:`Validation`)."""
    check_experiment(plant, experiment)
    return _validation(experiment, predict(plant, experiment, result.values))


__all__ = ["AT_BOUND", "CONFIDENCE", "CORRELATED", "SINGULAR", "FitResult", "Problem", "Validation", "fit",
           "validate"]
