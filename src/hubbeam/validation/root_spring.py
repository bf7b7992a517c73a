"""A beam on a compliant root in closed form: the root restrained in rotation, the lag hinge, the two-mass arm.

The root's hinge sits on the hub at the hub radius ``a``; a torsional spring ``k`` (damping aside)
holds the beam's root, which carries a clamp of rotary inertia ``J_c``, to the hub
(``hubbeam.model.root.RootSpring``, ``docs/compliant-root.md``). Three closed forms check hubbeam's
compliant root, each independent of its assumed modes.

**The root restrained in rotation (hub held, at rest).** A uniform Euler-Bernoulli beam (``rho A``,
``EI``, length ``L``), its root on a hinge held in place, free or carrying a tip body at its end.
``w(x, t) = W(x) cos(omega t)`` with ``EI W'''' = rho A omega^2 W``; in ``xi = x / L``, ``z = beta
L``, ``beta^4 = rho A omega^2 / EI``, ``W(xi) = c1 exp(z (xi - 1)) + c2 exp(-z xi) + c3 cos(z xi)
+ c4 sin(z xi)``. The Lagrangian ``int (rho A w'^2 - EI w''^2) dx / 2 - k w_x(0)^2 / 2 + J_c
w_x(0)'^2 / 2`` (dots: time rates; the root turns by ``w_x(0)``) has, beside ``w(0) = 0``, the
natural condition of the root's rotation: the beam's root moment ``EI w_xx(0)`` balances the
spring and the clamp's inertia, ``EI w_xx(0) = (k - J_c omega^2) w_x(0)``, in ``xi``

    W(0) = 0,      W''(0) = (kappa - j_c z^4) W'(0),      kappa = k L / EI,  j_c = J_c / (rho A L^3),

and at the end the free end's (or a tip body's) two conditions (``hubbeam.validation.tip_body``).
The four homogeneous equations in ``(c1, c2, c3, c4)`` have the 4x4 determinant of
:func:`frequency_determinant`, whose roots give ``omega = z^2 sqrt(EI / (rho A L^4))``. As
``kappa`` grows the root row tends to ``W'(0) = 0``, the clamped beam's, and each frequency to
the clamped one from below by ``O(1 / kappa)`` (the first-order change of a Rayleigh quotient
whose root slope the spring lets go).

**The lag hinge (a rigid link, hub held at speed).** In the frame turning with the hub at ``Omega``
the hinge is fixed at ``(a, 0)``; a rigid link turned by ``alpha`` from the radial direction
feels the centrifugal field ``Omega^2 r``, whose moment about the hinge is ``-Omega^2 a S sin
alpha`` (``S`` the link's first moment about the hinge); the Coriolis forces of its rotation about
the hinge point along the link and have no moment about it. With the link's inertia about the
hinge ``I`` (clamp and tip body included), ``I alpha'' + (k + Omega^2 a S) alpha = 0``:

    omega_lag^2 = (k + Omega^2 a S) / I,

the lag frequency of a helicopter blade on an offset lag hinge with a lag spring (Johnson,
Helicopter Theory, 1980, Sec. 9.3).

**The two-mass arm (a rigid link on a free hub, at rest).** The hub (``J``) and the link turn by
``phi`` and ``theta``; the link's points move with the hinge, ``a phi'``, and about it, so the
kinetic energy is ``(J + a^2 m) phi'^2 / 2 + a S phi' theta' + I theta'^2 / 2`` at rest (``m`` the
link's mass) and the spring's energy ``k (phi - theta)^2 / 2``. Besides the rigid rotation,

    omega^2 = k (J + a^2 m + 2 a S + I) / ((J + a^2 m) I - a^2 S^2),

which for ``a = 0`` is the two-inertia frequency ``k (1 / J + 1 / I)`` of the flexible-joint arm
(Spong, 1987). The numerator is the whole arm's inertia about the hub axis.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.optimize

from hubbeam.model.parameters import TipMass, UniformBeam, check_tip
from hubbeam.model.root import RootSpring, checked_spring
from hubbeam.validation.tip_body import check_ratios, determinant_roots, end_rows, scaled_determinant


def frequency_determinant(z: float, stiffness_ratio: float, clamp_ratio: float, mass_ratio: float = 0.0,
                          inertia_ratio: float = 0.0, offset_ratio: float = 0.0) -> float:
    """The 4x4 determinant of the restrained root's boundary conditions (module docstring) at ``z =
    beta L``: ``stiffness_ratio = k L / EI``, ``clamp_ratio = J_c / (rho A L^3)`` and a tip body's
    ratios as in ``hubbeam.validation.tip_body`` (zero: a free end). Rows on the solutions
    ``exp(z (xi - 1))``, ``exp(-z xi)``, ``cos(z xi)``, ``sin(z xi)``, each divided by its largest
    entry; the root row is divided by ``z``."""
    decay = math.exp(-z)
    value = np.array([decay, 1.0, 1.0, 0.0])  # W(0)
    slope = np.array([decay, -1.0, 0.0, 1.0])  # W'(0) / z
    curvature = np.array([decay, 1.0, -1.0, 0.0])  # W''(0) / z^2
    root = z * curvature - (stiffness_ratio - clamp_ratio * z**4) * slope
    return scaled_determinant(np.vstack([value, root, end_rows(z, mass_ratio, inertia_ratio, offset_ratio)]))


def _uniform(beam: UniformBeam, tip: TipMass | None) -> TipMass:
    """``tip`` (a zero point mass for None) checked at the end of the uniform ``beam``."""
    if not isinstance(beam, UniformBeam):
        raise ValueError(f"beam = {beam!r}: expected a uniform beam (BeamParameters or BeamProducts)")
    tip = TipMass(0.0, beam.L) if tip is None else tip
    check_tip(tip, beam.L)
    if tip.position != beam.L:
        raise ValueError(f"tip_mass.position = {tip.position!r}: expected the beam's end L = {beam.L} m "
                         "(the closed forms have the body at the end)")
    return tip


def restrained_frequencies(beam: UniformBeam, spring: RootSpring, count: int, tip: TipMass | None = None) -> np.ndarray:
    """Circular frequencies (rad s-1) of the uniform ``beam`` whose root is restrained by ``spring``
    (its stiffness and clamp inertia; the hub held, at rest), free or with the body ``tip`` at its
    end: the first ``count`` roots of :func:`frequency_determinant`."""
    spring = checked_spring(spring)
    tip = _uniform(beam, tip)
    rhoA, L, EI = beam.rhoA, beam.L, beam.EI
    ratios = (spring.stiffness * L / EI, spring.clamp_inertia / (rhoA * L**3), tip.mass / (rhoA * L),
              tip.inertia / (rhoA * L**3), tip.offset / L)
    check_ratios(stiffness_ratio=ratios[0], clamp_ratio=ratios[1])
    z = determinant_roots(lambda z: frequency_determinant(z, *ratios), count)
    return z**2 * math.sqrt(EI / (rhoA * L**4))


def rigid_link(beam: UniformBeam, spring: RootSpring, tip: TipMass | None = None) -> dict:
    """The rigid link of the uniform ``beam`` (with the body ``tip`` at its end) about its hinge:
    ``mass`` (kg), first moment ``S`` (kg m) and inertia ``I`` (kg m2, the clamp's and the body's
    rotary inertia included)."""
    tip = _uniform(beam, tip)
    rhoA, L = beam.rhoA, beam.L
    centre = L + tip.offset
    return {"mass": rhoA * L + tip.mass, "S": rhoA * L**2 / 2.0 + tip.mass * centre,
            "I": rhoA * L**3 / 3.0 + tip.mass * centre**2 + tip.inertia + spring.clamp_inertia}


def lag_frequency(beam: UniformBeam, spring: RootSpring, speed: float, tip: TipMass | None = None) -> float:
    """The lag-hinge frequency (rad s-1) of the rigid link on the root ``spring`` with the hub held
    at ``speed`` (rad s-1): ``sqrt((k + Omega^2 a S) / I)`` (module docstring)."""
    spring = checked_spring(spring)
    link = rigid_link(beam, spring, tip)
    return math.sqrt((spring.stiffness + speed**2 * beam.rA * link["S"]) / link["I"])


def two_mass_frequency(beam: UniformBeam, spring: RootSpring, tip: TipMass | None = None) -> float:
    """The vibration frequency (rad s-1) of the rigid link on the root ``spring`` and the free hub
    of inertia ``beam.Jh``, at rest (module docstring)."""
    spring = checked_spring(spring)
    link = rigid_link(beam, spring, tip)
    a, S, I = beam.rA, link["S"], link["I"]
    hub = beam.Jh + a * a * link["mass"]
    return math.sqrt(spring.stiffness * (hub + 2.0 * a * S + I) / (hub * I - (a * S) ** 2))


def main() -> None:
    """Print the checks of the compliant root on De Luca and Siciliano's link (``rho A = 0.2 kg/m``,
    ``L = 0.5 m``, ``EI = 1 N m2``, a 2 cm hub): hubbeam's frequencies at rest, hub held, against the
    restrained root's closed form (5 to 20 modes), the approach to the clamped beam as ``1 / k``, the
    stiffness that lowers the first frequency by 4 %, the lag hinge of the link made rigid at speed
    and its two-mass frequency on a free hub."""
    from hubbeam.model.eigen import natural_frequencies, root_frequencies
    from hubbeam.model.matrices import assemble
    from hubbeam.model.parameters import BeamProducts

    link = BeamProducts(L=0.5, rhoA=0.2, EI=1.0, EA=1.0e4, Jh=0.01, rA=0.02)
    hz = 1.0 / (2.0 * math.pi)
    print("De Luca and Siciliano's link on a root spring, hub held, at rest (clamp 1e-4 kg m2)")
    for k in (0.5, 5.0, 50.0):
        spring = RootSpring(k, 0.0, 1e-4)
        exact = restrained_frequencies(link, spring, 3)
        print(f"  k = {k:g} N m/rad: closed form " + ", ".join(f"{f * hz:.6f}" for f in exact) + " Hz")
        for n in (5, 10, 20):
            ritz = natural_frequencies(assemble(link, None, n), spring)[:3]
            print(f"    hubbeam, {n:2d} modes: " + ", ".join(f"{r / e - 1:+.2e}" for r, e in zip(ritz, exact)))
    clamped = restrained_frequencies(link, RootSpring(1e15), 3)
    print(f"  towards the clamped beam, k (omega / omega_c - 1) -> -2 EI / L = {-2 * link.EI / link.L:g}:")
    for k in (1e2, 1e3, 1e4, 1e5):
        gap = restrained_frequencies(link, RootSpring(k), 3) / clamped - 1.0
        print(f"    k = {k:g}: " + ", ".join(f"{k * g:.5f}" for g in gap))
    four = scipy.optimize.brentq(lambda k: restrained_frequencies(link, RootSpring(k), 1)[0] / clamped[0] - 0.96,
                                 1.0, 1e4)
    print(f"  a root stiffness of {four:.4g} N m/rad = {four * link.L / link.EI:.4g} EI / L lowers the first "
          "frequency by 4 %")
    stiff = BeamProducts(L=0.5, rhoA=0.2, EI=1.0e6, EA=1.0e12, Jh=0.01, rA=0.02)
    spring = RootSpring(2.0, 0.0, 1e-4)
    sm = assemble(stiff, None, 4)
    print("the link made rigid (EI = 1e6 N m2) on a 2 N m/rad spring:")
    for speed in (0.0, 10.0, 30.0):
        lag = lag_frequency(stiff, spring, speed)
        ritz = root_frequencies(sm, spring, "CFOAM", speed, "held")[0]
        print(f"  hub held at {speed:g} rad/s: lag hinge {lag:.8f} rad/s, hubbeam (CFOAM) {ritz / lag - 1:+.2e}")
    free = root_frequencies(sm, spring, "FOAM", 0.0, "free")[1]
    two_mass = two_mass_frequency(stiff, spring)
    print(f"  free hub at rest: two-mass frequency {two_mass:.8f} rad/s, hubbeam {free / two_mass - 1:+.2e}")


if __name__ == "__main__":
    main()
