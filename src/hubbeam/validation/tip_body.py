"""The clamped beam carrying a tip body: its frequency equation in closed form.

A uniform Euler-Bernoulli beam (``rho A``, ``EI``, length ``L``) is clamped at ``x = 0`` (the hub
held) and carries at ``x = L`` a rigid body: mass ``m`` with its centre ``e`` beyond the end along
the beam's tangent, rotary inertia ``J`` about that centre (``hubbeam.model.parameters.TipMass``,
``docs/tip-body.md``). Small free vibrations ``w(x, t) = W(x) cos(omega t)`` obey
``EI W'''' = rho A omega^2 W``; with ``xi = x / L``, ``z = beta L`` and ``beta^4 = rho A omega^2 /
EI``,

    W(xi) = c1 cosh(z xi) + c2 sinh(z xi) + c3 cos(z xi) + c4 sin(z xi).

The body's centre moves by ``w_c = w(L) + e w'(L)`` and the body turns by ``w'(L)``. Newton's laws
for the body, loaded by the beam's end shear ``EI w'''(L)`` and end moment ``-EI w''(L)`` (about
the end; the shear acts at the lever ``e`` from the centre), are

    translation:   m w_c''                = EI w'''(L)
    rotation:      J w'(L)'' + m e w_c''  = -EI w''(L)

(the second is the moment balance about the beam's end: the centre's inertia force ``m w_c''``
at the lever ``e`` and the body's rotary inertia balance the end moment). The same two conditions
are the natural boundary conditions of the Lagrangian ``int (rho A w'^2 - EI w''^2) dx / 2 +
m w_c'^2 / 2 + J w''(L)^2 / 2`` (dots as time rates). With the mass ratio ``mu = m / (rho A L)``,
the inertia ratio ``j = J / (rho A L^3)`` and ``eps = e / L`` they read, in ``xi``,

    W(0) = 0,   W'(0) = 0,
    W'''(1) + mu z^4 (W(1) + eps W'(1)) = 0,
    -W''(1) + z^4 (mu eps (W(1) + eps W'(1)) + j W'(1)) = 0,

four linear equations in ``(c1, c2, c3, c4)``, whose 4x4 determinant vanishes at the roots ``z``
(:func:`frequency_determinant`); ``omega = z^2 sqrt(EI / (rho A L^4))``. With ``j = eps = 0``
this is the tip-mass equation ``1 + cos z cosh z + mu z (cos z sinh z - sin z cosh z) = 0``
(``hubbeam.model.eigen.tip_mass_frequency_roots``), with ``mu = 0`` as well the clamped-free one
``1 + cos z cosh z = 0``.

The classic single link of De Luca and Siciliano (1991) is :data:`DE_LUCA_SICILIANO`;
:func:`ritz_convergence` sets hubbeam's frequencies (its Ritz model at rest, hub held) beside the
closed form, and ``python -m hubbeam.validation.tip_body`` prints them for that link.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.optimize

from hubbeam.model.eigen import natural_frequencies, transverse_frequencies
from hubbeam.model.matrices import assemble
from hubbeam.model.modes import transverse_modes
from hubbeam.model.parameters import BeamProducts, TipMass, UniformBeam, check_tip
from hubbeam.validation import fe_beam

#: De Luca, A. and Siciliano, B. (1991), "Closed-form dynamic model of planar multilink
#: lightweight robots", IEEE Transactions on Systems, Man, and Cybernetics 21(4), 826-839: the
#: flexible link (``rhoA`` kg m-1, ``L`` m, ``EI`` N m2) with its payload (``mass`` kg,
#: ``inertia`` kg m2 about its centre, at the tip) and the published first two frequencies of
#: the link clamped at the hub (``frequencies_hz``, printed to two decimals). Compared, never
#: used as inputs.
DE_LUCA_SICILIANO = {"rhoA": 0.2, "L": 0.5, "EI": 1.0, "mass": 0.1, "inertia": 0.0005,
                     "frequencies_hz": (2.18, 15.91)}

#: the grid step (in ``z``) on which sign changes of the determinant bracket the roots: fine
#: enough for the roots of the bodies of the tests, which the finite-element model confirms one
#: by one (two roots closer than the step could hide in one interval; a massive body with an
#: offset brings its rocking root within 0.2 of a beam root)
_GRID_STEP = math.pi / 256
#: the grid starts here: the determinant vanishes at z = 0 (the limit W = 0), no root is this low
#: for bodies below about 1e8 times the beam's mass
_GRID_START = 1e-2


def end_rows(z: float, mass_ratio: float, inertia_ratio: float, offset_ratio: float) -> np.ndarray:
    """The two boundary conditions at the loaded end ``xi = 1`` (module docstring) as rows on the
    solutions ``exp(z (xi - 1))``, ``exp(-z xi)``, ``cos(z xi)``, ``sin(z xi)``: the end shear against
    the centre's inertia and the end moment against both inertias (a free end without a body)."""
    mu, j, eps = mass_ratio, inertia_ratio, offset_ratio
    decay = math.exp(-z)
    c, s = math.cos(z), math.sin(z)
    # W and its xi-derivatives at xi = 1, column by column
    W = np.array([1.0, decay, c, s])
    W1 = z * np.array([1.0, -decay, -s, c])
    W2 = z**2 * np.array([1.0, decay, -c, -s])
    W3 = z**3 * np.array([1.0, -decay, s, -c])
    centre = W + eps * W1
    return np.array([W3 + mu * z**4 * centre, -W2 + z**4 * (mu * eps * centre + j * W1)])


def scaled_determinant(rows: np.ndarray) -> float:
    """The determinant of ``rows``, each divided by its largest entry: positive factors, which move
    no root and keep the determinant's rounding error near the machine epsilon."""
    return float(np.linalg.det(rows / np.max(np.abs(rows), axis=1, keepdims=True)))


def frequency_determinant(z: float, mass_ratio: float, inertia_ratio: float, offset_ratio: float) -> float:
    """The 4x4 determinant of the boundary conditions (module docstring) at ``z = beta L``.

    Evaluated in the basis ``exp(z (xi - 1))``, ``exp(-z xi)``, ``cos(z xi)``, ``sin(z xi)`` of
    the same solutions (``cosh`` and ``sinh`` would make two columns equal to ``e^-z`` at large
    ``z``), each row divided by its largest entry (:func:`scaled_determinant`).
    """
    decay = math.exp(-z)
    clamped = np.array([
        [decay, 1.0, 1.0, 0.0],  # W(0) = 0
        [decay, -1.0, 0.0, 1.0],  # W'(0) / z = 0
    ])
    return scaled_determinant(np.vstack([clamped, end_rows(z, mass_ratio, inertia_ratio, offset_ratio)]))


def determinant_roots(equation, count: int) -> np.ndarray:
    """The first ``count`` roots ``z`` of ``equation(z)`` (a frequency determinant), ascending:
    each sign change on a grid of step :data:`_GRID_STEP` from :data:`_GRID_START`, refined by
    Brent's method to ``xtol = 1e-15`` (about 1e-15 relative for ``z`` of order 1 to 100; the
    rounding of the determinant allows about 1e-14)."""
    if not (isinstance(count, (int, np.integer)) and count >= 1):
        raise ValueError(f"count = {count!r}: expected an integer >= 1")
    roots = []
    a, fa = _GRID_START, equation(_GRID_START)
    while len(roots) < count:
        b = a + _GRID_STEP
        fb = equation(b)
        if fa == 0.0:
            roots.append(a)
        elif fa * fb < 0.0:
            roots.append(scipy.optimize.brentq(equation, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps))
        a, fa = b, fb
    return np.array(roots)


def check_ratios(**ratios) -> None:
    """``ValueError`` naming the first ratio that is not finite and ``>= 0``."""
    for name, value in ratios.items():
        if not (math.isfinite(value) and value >= 0.0):
            raise ValueError(f"{name} = {value!r}: expected a finite ratio >= 0")


def body_frequency_roots(mass_ratio: float, inertia_ratio: float, offset_ratio: float,
                         count: int) -> np.ndarray:
    """The first ``count`` roots ``z = beta L`` of :func:`frequency_determinant`, ascending
    (:func:`determinant_roots`)."""
    if not (isinstance(count, (int, np.integer)) and count >= 1):
        raise ValueError(f"count = {count!r}: expected an integer >= 1")
    check_ratios(mass_ratio=mass_ratio, inertia_ratio=inertia_ratio)
    if not math.isfinite(offset_ratio):
        raise ValueError(f"offset_ratio = {offset_ratio!r}: expected a finite ratio")
    return determinant_roots(lambda z: frequency_determinant(z, mass_ratio, inertia_ratio, offset_ratio), count)


def body_frequencies(beam: UniformBeam, tip: TipMass, count: int) -> np.ndarray:
    """Circular frequencies (rad s-1) of the uniform ``beam`` clamped at the hub (held) with the
    body ``tip`` at its end (``tip.position = L``): the first ``count`` roots of
    :func:`body_frequency_roots` as ``omega = z^2 sqrt(EI / (rho A L^4))``."""
    if not isinstance(beam, UniformBeam):
        raise ValueError(f"beam = {beam!r}: expected a uniform beam (BeamParameters or BeamProducts)")
    check_tip(tip, beam.L)
    if tip.position != beam.L:
        raise ValueError(f"tip_mass.position = {tip.position!r}: expected the beam's end L = {beam.L} m "
                         "(the closed form has the body at the end)")
    rhoA, L = beam.rhoA, beam.L
    z = body_frequency_roots(tip.mass / (rhoA * L), tip.inertia / (rhoA * L**3), tip.offset / L, count)
    return z**2 * math.sqrt(beam.EI / (rhoA * L**4))


def ritz_convergence(beam: UniformBeam, tip: TipMass, modes, count: int = 3, functions: str = "clamped_free"):
    """The closed-form frequencies (rad s-1) of ``beam`` with ``tip`` at its end (hub held) and
    hubbeam's (``hubbeam.model.eigen.natural_frequencies`` of ``assemble(beam, tip, n, functions=
    functions)``) for each ``n`` of ``modes``: ``(exact, ritz)`` of shapes ``(count,)`` and
    ``(len(modes), count)``.
    """
    exact = body_frequencies(beam, tip, count)
    ritz = np.array([natural_frequencies(assemble(beam, tip, int(n), functions=functions))[:count] for n in modes])
    return exact, ritz


def speed_convergence(beam: UniformBeam, tip: TipMass, speeds, modes, functions: str, count: int = 3,
                      n_elements: int = 80) -> np.ndarray:
    """Relative errors of FOAM's first ``count`` in-plane frequencies at ``speeds`` (rad s-1) with
    ``modes`` assumed modes of the transverse ``functions``, against the finite-element model with
    the body (``hubbeam.validation.fe_beam``, ``n_elements``): shape ``(len(modes), len(speeds),
    count)``."""
    speeds = np.asarray(speeds, dtype=float)
    fe = fe_beam.frequencies(beam, speeds, "inplane", tip, n_elements, count)
    return np.array([transverse_frequencies(assemble(beam, tip, int(n), functions=functions), "FOAM", speeds)
                     [:, :count] / fe - 1.0 for n in modes])


def main() -> None:
    """Print the De Luca and Siciliano link's frequencies: published, closed form, and hubbeam's
    with 5 to 20 modes of the clamped-free functions and of the functions loaded by the body, for
    the payload and for the payload as a point mass; then, with the payload 3 cm beyond the tip on
    a 5 cm hub, FOAM's errors at speed against the finite-element model in both functions and in
    the clamped-free functions augmented by the static shapes of a tip force and moment
    (:func:`static_augmented`)."""
    link = DE_LUCA_SICILIANO
    beam = BeamProducts(L=link["L"], rhoA=link["rhoA"], EI=link["EI"], EA=1.0e4, Jh=0.1, rA=0.0)
    modes = (5, 10, 15, 20)
    hz = 1.0 / (2.0 * math.pi)
    print(f"De Luca and Siciliano (1991) link, clamped at the hub; published: {link['frequencies_hz']} Hz")
    for label, inertia in (("payload", link["inertia"]), ("point mass", 0.0)):
        for functions in ("clamped_free", "tip_body"):
            exact, ritz = ritz_convergence(beam, TipMass(link["mass"], link["L"], inertia), modes, functions=functions)
            print(f"{label}: closed form " + ", ".join(f"{f:.6f}" for f in exact * hz) + " Hz")
            for n, row in zip(modes, ritz):
                print(f"  hubbeam, {n:2d} modes ({functions} functions): "
                      + ", ".join(f"{f:.6f} ({f / e - 1:+.2e})" for f, e in zip(row * hz, exact * hz)))
    spinning = BeamProducts(L=link["L"], rhoA=link["rhoA"], EI=link["EI"], EA=1.0e4, Jh=0.1, rA=0.05)
    body = TipMass(link["mass"], link["L"], link["inertia"], 0.03)
    speeds = (10.0, 25.0, 50.0)
    print("FOAM at speed, the payload 3 cm beyond the tip on a 5 cm hub, against 80 finite elements")
    fe = fe_beam.frequencies(spinning, speeds, "inplane", body, 80, 3)
    errors = {functions: speed_convergence(spinning, body, speeds, modes, functions)
              for functions in ("clamped_free", "tip_body")}
    # the alternative not taken: the clamped-free functions with the static shapes of a tip force
    # and a tip moment in place of the last two, projected on the elements
    errors["clamped_free + static tip force, moment"] = np.array([fe_beam.ritz_frequencies(
        spinning, speeds, lambda x, k, n=n: static_augmented(spinning, x, k, n), body) / fe - 1.0 for n in modes])
    for label, table in errors.items():
        for n, rows in zip(modes, table):
            print(f"  {label}, {n:2d} modes: " + "; ".join(
                f"{speed:g} rad/s " + ", ".join(f"{e:+.1e}" for e in row) for speed, row in zip(speeds, rows)))


def static_augmented(beam: UniformBeam, x, derivative: int, n_modes: int) -> np.ndarray:
    """``n_modes`` trial functions at ``x`` (or their first ``derivative``): the first ``n_modes -
    2`` clamped-free functions and the static deflections of the cantilever under a tip force,
    ``x^2 (3 L - x) / 6``, and a tip moment, ``x^2 / 2`` (up to ``1 / EI``)."""
    x = np.asarray(x, dtype=float)
    L = beam.L
    force = x**2 * (3.0 * L - x) / 6.0 if derivative == 0 else x * (2.0 * L - x) / 2.0
    moment = x**2 / 2.0 if derivative == 0 else x
    return np.column_stack([transverse_modes(x, n_modes - 2, beam, derivative), force, moment])


if __name__ == "__main__":
    main()
