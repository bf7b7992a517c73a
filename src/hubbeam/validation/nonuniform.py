"""Validation of non-uniform beams: Ritz model vs our finite elements vs pyBModes.

Three independent solutions of the rotating-beam frequencies at constant hub speed:

* the Ritz (assumed-mode) model of the simulations, ``(K2 + Omega^2 D - c Omega^2 M2, M2)``
  (Eq. 31 with the tip-mass terms; ``c = 1`` in the plane of rotation, the FOAM frequencies of
  ``hubbeam.model.eigen.transverse_frequencies``; ``c = 0`` flapwise, see
  ``hubbeam.validation.rotating_eigen``), with the clamped-free modes of the uniform beam as the
  basis;
* the cubic Hermite finite elements of :mod:`hubbeam.validation.fe_beam`;
* pyBModes (the Python port of NREL's BModes), a rotating-blade FE code with its own elements
  and centrifugal terms. It holds the section properties constant on each element (their values
  at the element midpoints), which makes its frequencies converge as ``h^2`` for a tapered beam;
  :func:`pybmodes_frequencies` extrapolates three meshes to ``h -> 0`` (Richardson). pyBModes adds
  a tip mass to the mass matrix only, without its centrifugal tension, so cases with a tip mass
  are compared with our finite elements only.

The tables give frequencies in Hz and relative differences per direction, hub speed and mode.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from hubbeam.model.beam import BeamSections
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import TipMass
from hubbeam.validation import fe_beam, rotating_eigen

#: our FE direction -> the Ritz direction of rotating_eigen (the q2 problem without q1)
RITZ_DIRECTION = {"flapwise": "flapwise", "inplane": "chordwise_uncoupled"}
HZ = 1.0 / (2.0 * np.pi)
#: pyBModes meshes (elements) whose frequencies are extrapolated to h -> 0
PYBMODES_MESHES = (25, 50, 100)
#: stiffness factor of the other bending direction in a pyBModes run, so that its modes lie far
#: above the ones compared (frequencies 100 times higher)
_OTHER_DIRECTION_STIFFNESS = 1.0e4


#: ratio of tip to root section of :func:`tapered_beam` by default
TAPER_RATIO = 0.5
#: elements of our FE model in the comparisons
FE_ELEMENTS = 160


def tapered_beam(base, tip_ratio: float = TAPER_RATIO) -> BeamSections:
    """A linearly tapered version of the uniform beam ``base``: the width of the section falls
    linearly from its root value to ``tip_ratio`` times it at the tip, so ``rho A``, ``E I`` and
    ``E A`` (all proportional to the width) are linear from ``base``'s values to ``tip_ratio``
    times them."""
    if not (np.isfinite(tip_ratio) and tip_ratio > 0.0):
        raise ValueError(f"tip_ratio = {tip_ratio!r}: expected a finite ratio > 0")
    return BeamSections(L=base.L, Jh=base.Jh, rA=base.rA, x=(0.0, base.L),
                        rhoA=(base.rhoA, tip_ratio * base.rhoA),
                        EI=(base.EI, tip_ratio * base.EI), EA=(base.EA, tip_ratio * base.EA))


def ritz_frequencies(params, speeds, direction: str, tip=None, n_modes: int = 20,
                     n_quad: int = 64) -> np.ndarray:
    """Ritz circular frequencies (rad s-1), shape ``(len(speeds), n_modes)``, ascending."""
    sm = assemble(params, tip, n_modes, n_quad)
    return np.array([rotating_eigen.frequencies(sm, speed, RITZ_DIRECTION[direction])
                     for speed in np.atleast_1d(speeds)])


def ritz_vs_fe(params, speeds, tip=None, modes=(5, 10, 20), n_frequencies: int = 4,
               n_elements: int = FE_ELEMENTS) -> pd.DataFrame:
    """Ritz frequencies with ``modes`` assumed modes against our FE model, both directions.

    Columns ``direction, speed_rad_s, mode, n_modes, ritz_hz, fe_hz, rel_diff`` (``ritz / fe -
    1``, the Ritz model's error while the FE error is far smaller, see ``fe_beam``).
    """
    rows = []
    for direction in fe_beam.DIRECTIONS:
        fe = fe_beam.frequencies(params, speeds, direction, tip, n_elements, n_frequencies)
        for n in modes:
            ritz = ritz_frequencies(params, speeds, direction, tip, n)[:, :n_frequencies]
            for s, speed in enumerate(np.atleast_1d(speeds)):
                for k in range(min(n, n_frequencies)):
                    rows.append({"direction": direction, "speed_rad_s": float(speed),
                                 "mode": k + 1, "n_modes": n, "ritz_hz": ritz[s, k] * HZ,
                                 "fe_hz": fe[s, k] * HZ, "rel_diff": ritz[s, k] / fe[s, k] - 1})
    return pd.DataFrame(rows)


def _pybmodes_run(params, speed: float, direction: str, n_elements: int, n_frequencies: int):
    """Frequencies (Hz) of the lowest ``n_frequencies`` modes of ``direction``, one pyBModes run.

    The beam is a blade (``beam_type`` 1, clamped) from the hub radius ``rA`` to ``rA + L``,
    without twist, offsets or pre-cone; the section table samples the properties at 201 points
    (exact for piecewise-linear tables whose stations are among them, which holds for
    :func:`tapered_beam`). Sectional rotary inertia is set negligible, torsion stiff; the other
    bending direction is made stiff so that the lowest modes are pure ``direction`` bending.
    """
    from pybmodes.io.bmi import BMIFile, ScalingFactors, TipMassProps
    from pybmodes.io.sec_props import SectionProperties
    from pybmodes.models._pipeline import run_fem

    x = np.union1d(np.linspace(0.0, params.L, 201), params.stations)
    zero = np.zeros(x.size)
    EI = params.EI_at(x)
    stiff = _OTHER_DIRECTION_STIFFNESS * EI
    sections = SectionProperties(
        title="hubbeam beam", n_secs=x.size, span_loc=x / params.L, str_tw=zero, tw_iner=zero,
        mass_den=params.rhoA_at(x), flp_iner=np.full(x.size, 1e-9),
        edge_iner=np.full(x.size, 1e-9),
        flp_stff=EI if direction == "flapwise" else stiff,
        edge_stff=EI if direction == "inplane" else stiff, tor_stff=stiff,
        axial_stff=params.EA_at(x), cg_offst=zero, sc_offst=zero, tc_offst=zero)
    no_tip = TipMassProps(mass=0.0, cm_offset=0.0, cm_axial=0.0, ixx=0.0, iyy=0.0, izz=0.0,
                          ixy=0.0, izx=0.0, iyz=0.0)
    n_modes = 2 * n_frequencies + 4
    bmi = BMIFile(title="hubbeam beam", echo=False, beam_type=1, rot_rpm=speed * 30.0 / np.pi,
                  rpm_mult=1.0, radius=params.rA + params.L, hub_rad=params.rA, precone=0.0,
                  bl_thp=0.0, hub_conn=1, n_modes_print=n_modes, tab_delim=True,
                  mid_node_tw=False, tip_mass=no_tip, id_mat=1, sec_props_file="",
                  scaling=ScalingFactors(), n_elements=n_elements,
                  el_loc=np.linspace(0.0, 1.0, n_elements + 1))
    result = run_fem(bmi, n_modes=n_modes, sp=sections)
    displacement = "flap_disp" if direction == "flapwise" else "lag_disp"
    other = "lag_disp" if direction == "flapwise" else "flap_disp"
    found = [f for f, shape in zip(result.frequencies, result.shapes)
             if np.linalg.norm(getattr(shape, displacement)) > np.linalg.norm(getattr(shape, other))]
    if len(found) < n_frequencies:
        raise RuntimeError(f"pyBModes gave {len(found)} {direction} modes among {n_modes}; "
                           f"expected {n_frequencies}")
    return np.array(found[:n_frequencies])


def pybmodes_frequencies(params, speeds, direction: str, n_frequencies: int = 4,
                         meshes=PYBMODES_MESHES) -> pd.DataFrame:
    """pyBModes frequencies (Hz) of ``direction`` on three meshes and extrapolated to ``h -> 0``.

    Columns ``direction, speed_rad_s, mode, pybmodes_hz`` (extrapolated), ``order`` (the observed
    convergence order in ``h``, 2 for properties constant per element) and one column
    ``pybmodes_<n>el_hz`` per mesh. The extrapolation is
    :func:`hubbeam.validation.rotating_eigen.richardson` with ``1 / n_elements`` as the level.
    """
    if params.rA <= 0.0:
        raise ValueError(f"hub radius rA = {params.rA!r}: pyBModes needs a blade root off the "
                         "axis, rA > 0 m")
    rows = []
    for speed in np.atleast_1d(speeds):
        runs = np.array([_pybmodes_run(params, float(speed), direction, n, n_frequencies)
                         for n in meshes])
        for k in range(n_frequencies):
            # richardson() extrapolates in a count n (error ~ n^-p): the elements are that count
            value, order = rotating_eigen.richardson(meshes, runs[:, k])
            rows.append({"direction": direction, "speed_rad_s": float(speed), "mode": k + 1,
                         "pybmodes_hz": value, "order": order}
                        | {f"pybmodes_{n}el_hz": runs[i, k] for i, n in enumerate(meshes)})
    return pd.DataFrame(rows)


def pybmodes_comparison(params, speeds, n_frequencies: int = 4, ritz_modes: int = 20,
                        n_elements: int = FE_ELEMENTS) -> pd.DataFrame:
    """Extrapolated pyBModes frequencies against our Ritz and FE models, bare beam, both directions.

    Columns of :func:`pybmodes_frequencies` plus ``ritz_hz``, ``fe_hz``, ``rel_diff_ritz`` and
    ``rel_diff_fe`` (``ours / pybmodes - 1``).
    """
    tables = []
    for direction in fe_beam.DIRECTIONS:
        table = pybmodes_frequencies(params, speeds, direction, n_frequencies)
        ritz = ritz_frequencies(params, speeds, direction, None, ritz_modes)[:, :n_frequencies]
        fe = fe_beam.frequencies(params, speeds, direction, None, n_elements, n_frequencies)
        table["ritz_hz"] = ritz.ravel() * HZ
        table["fe_hz"] = fe.ravel() * HZ
        table["rel_diff_ritz"] = table["ritz_hz"] / table["pybmodes_hz"] - 1
        table["rel_diff_fe"] = table["fe_hz"] / table["pybmodes_hz"] - 1
        tables.append(table)
    return pd.concat(tables, ignore_index=True)


#: tip mass of the checks with a tip mass: this fraction of the beam's mass, at the tip
TIP_MASS_RATIO = 0.5
#: hub speeds of the checks, in units of the beam's first flapwise frequency at rest
SPEED_RATIOS = (0.0, 2.0, 4.0)
#: assumed-mode counts of the Ritz model in the checks
RITZ_MODES = (5, 10, 20)


def validation_beam(params):
    """The non-uniform beam the checks of ``snakemake validate`` use: ``params`` itself when it
    is a section table, else its :func:`tapered_beam`."""
    return params if isinstance(params, BeamSections) else tapered_beam(params)


def check_speeds(params) -> np.ndarray:
    """Hub speeds (rad s-1) of the checks: :data:`SPEED_RATIOS` times the first flapwise frequency
    at rest of ``params`` (our finite elements), so that every beam is checked from rest to well
    above its first frequency."""
    first = fe_beam.frequencies(params, [0.0], "flapwise", None, n_frequencies=1)[0, 0]
    return np.asarray(SPEED_RATIOS) * first


def nonuniform_tables(params, pybmodes: bool = True) -> dict[str, pd.DataFrame]:
    """The tables of the non-uniform checks of :func:`validation_beam` ``(params)``: the
    frequencies at constant hub speed of the Ritz model (Eq. 31 with the tip-mass terms) against
    the independent solutions.

    ``ritz_fe``: :func:`ritz_vs_fe` for the bare beam and with a tip mass of
    :data:`TIP_MASS_RATIO` times the beam's mass at the tip (column ``case``: ``bare`` or
    ``tip_mass``; ``tip_mass_kg``). ``pybmodes`` (when ``pybmodes``; pyBModes needs ``rA > 0``):
    :func:`pybmodes_comparison` for the bare beam, since pyBModes's tip mass lacks the centrifugal
    tension (module docstring).
    """
    beam = validation_beam(params)
    speeds = check_speeds(beam)
    tip = TipMass(mass=TIP_MASS_RATIO * beam.beam_mass, position=beam.L)
    tables = [ritz_vs_fe(beam, speeds, None, RITZ_MODES).assign(case="bare", tip_mass_kg=0.0),
              ritz_vs_fe(beam, speeds, tip, RITZ_MODES).assign(case="tip_mass",
                                                               tip_mass_kg=tip.mass)]
    result = {"ritz_fe": pd.concat(tables, ignore_index=True)}
    if pybmodes:
        result["pybmodes"] = pybmodes_comparison(beam, speeds, ritz_modes=RITZ_MODES[-1])
    return result
