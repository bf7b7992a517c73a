"""System matrices of the hub-beam with a tip mass (Eqs. 13-20 and the Appendix).

With the point tip mass ``m_t`` at ``x = l`` every mass integral ``int_0^L (.) rho A dx`` gains the
term ``m_t (.)(l)``; for ``l = L`` this reproduces the Appendix, Eqs. (A1)-(A10), with
``(r_A + L)`` and ``S(L)``:

    J_b = int rho A (rA + x)^2 dx           + m_t (rA + l)^2                  (13), (A1)
    K_1 = int EA f1'^T f1' dx,  K_2 = int EI f2''^T f2'' dx                    (14), (15)
    M_i = int rho A f_i^T f_i dx            + m_t f_i(l)^T f_i(l)              (16), (A4), (A5)
    V_i = int rho A (rA + x) f_i dx         + m_t (rA + l) f_i(l)              (17), (A1), (A3)
    D   = int rho A (rA + x) S(x) dx        + m_t (rA + l) S(l)                (18), (A8)
    R   = int rho A f1^T f2 dx              + m_t f1(l)^T f2(l)                (19), (A6)
    S(x) = int_0^x f2'(xi)^T f2'(xi) dxi                                       (20)

``rho A``, ``EI`` and ``EA`` may vary along the beam (``hubbeam.model.beam.BeamSections``): they are
evaluated at the quadrature nodes, and the rule breaks at the stations of the tables
(``hubbeam.model.quadrature.beam_rule``). For the uniform beam they are the constants of Table 1.

The beam part of ``D`` is evaluated as the single integral ``int g(xi) f2'^T f2' dxi`` with
``g(xi) = int_xi^L rho A(x) (rA + x) dx`` (order of integration swapped; ``params.outboard_moment``,
exact for piecewise-linear ``rho A``, ``rho A (rA (L - xi) + (L^2 - xi^2) / 2)`` for a uniform
beam), so that one Gauss rule integrates the double integral. ``S`` at the point-cloud nodes uses
its own Gauss rule on ``[0, x]``.
"""

import math

import numpy as np

from hubbeam.core.system_matrices import SystemMatrices
from hubbeam.model.beam import beam_attributes
from hubbeam.model.modes import axial_modes, transverse_modes
from hubbeam.model.quadrature import beam_rule, effective_points, gauss_legendre, point_cloud


def _check_tip(params, mass, position):
    if not (math.isfinite(mass) and mass >= 0.0):
        raise ValueError(f"tip_mass.mass = {mass!r}: expected a finite mass >= 0 kg")
    if not (math.isfinite(position) and 0.0 <= position <= params.L):
        raise ValueError(
            f"tip_mass.position = {position!r}: expected 0 <= position <= L = {params.L} m"
        )


def _tip_values(params, tip):
    """(mass, position) of ``tip``; no tip mass is a zero mass at the beam tip."""
    if tip is None:
        return 0.0, float(params.L)
    mass, position = float(tip.mass), float(tip.position)
    _check_tip(params, mass, position)
    return mass, position


def _gram(values, weights):
    """``sum_k weights_k values_k^T values_k`` for ``values`` of shape (m, n), exactly symmetric."""
    product = (values.T * weights) @ values
    return 0.5 * (product + product.T)


def S_matrix(params, x, n_modes, n_quad=64):
    """``S(x) = int_0^x f2'(xi)^T f2'(xi) dxi`` (Eq. 20) at abscissae ``x``, shape (m, n, n).

    Each ``S(x_k)`` is integrated by its own Gauss-Legendre rule on ``[0, x_k]`` with
    ``effective_points(n_quad, n_modes)`` nodes. Units kg^-1 m^-1.
    """
    x = np.atleast_1d(np.asarray(x, dtype=float))
    nodes, weights = gauss_legendre(effective_points(n_quad, n_modes), np.zeros_like(x), x)
    slopes = transverse_modes(nodes.ravel(), n_modes, params, derivative=1)
    slopes = slopes.reshape(nodes.shape + (n_modes,))
    S = np.einsum("kq,kqi,kqj->kij", weights, slopes, slopes)
    return 0.5 * (S + np.swapaxes(S, -1, -2))


def point_mass_terms(params, mass, position, n_modes, n_quad=64):
    """Contributions of a point mass ``mass`` at ``position`` to Jb, M1, M2, V1, V2, D, R.

    ``mass`` and ``position`` broadcast against each other (shape ``s``); each returned array has
    shape ``s`` (Jb), ``s + (n,)`` (V1, V2) or ``s + (n, n)`` (M1, M2, D, R). This is the term
    ``m_t * integrand(l)`` of every mass integral (Appendix with ``L -> l``), shared by
    :func:`assemble` and the parameter sweeps of :mod:`hubbeam.model.eigen`.
    """
    mass, position = np.broadcast_arrays(np.asarray(mass, float), np.asarray(position, float))
    for m, l in zip(mass.ravel(), position.ravel()):
        _check_tip(params, float(m), float(l))
    shape = mass.shape
    flat_l = position.ravel()
    f1 = axial_modes(flat_l, n_modes, params).reshape(shape + (n_modes,))
    f2 = transverse_modes(flat_l, n_modes, params).reshape(shape + (n_modes,))
    S = S_matrix(params, flat_l, n_modes, n_quad).reshape(shape + (n_modes, n_modes))
    lever = params.rA + position
    m = mass[..., None]
    mm = mass[..., None, None]
    return {
        "Jb": mass * lever**2,
        "M1": mm * f1[..., :, None] * f1[..., None, :],
        "M2": mm * f2[..., :, None] * f2[..., None, :],
        "V1": m * lever[..., None] * f1,
        "V2": m * lever[..., None] * f2,
        "D": (mass * lever)[..., None, None] * S,
        "R": mm * f1[..., :, None] * f2[..., None, :],
    }


def assemble(params, tip=None, n_modes=5, n_quad=64):
    """Assemble :class:`SystemMatrices` for ``n_modes`` modes (Eqs. 13-20, Appendix).

    Parameters
    ----------
    params : BeamParameters or BeamSections
        Table 1 (``L, rho, A, E, I, Jh, rA``) or a beam with tabulated sections.
    tip : TipMass or None
        Point mass ``tip.mass`` (kg) at ``0 <= tip.position <= L`` (m); ``None`` for none.
    n_modes : int
        Number of assumed modes for each of q1 and q2 (1..20).
    n_quad : int
        Requested Gauss-Legendre nodes on ``[0, L]`` (config ``numerics.quadrature_points``).
        The rule actually used has ``effective_points(n_quad, n_modes) = max(n_quad,
        30 + 3 n_modes)`` nodes (64 for 5 modes with the configured 64, 90 for 20 modes), enough
        for every matrix to be converged to 1e-12 relative; the point cloud then has that many
        nodes plus the tip. A beam with sections gets a composite rule broken at its stations
        with at least that many nodes (``hubbeam.model.quadrature.beam_rule``).
    """
    mass, position = _tip_values(params, tip)
    nq = effective_points(n_quad, n_modes)
    x, w = point_cloud(params, mass, position, nq)
    xb, gauss = beam_rule(params, nq)  # the beam nodes of x and their plain weights
    wb, lever = w[:-1], params.rA + xb
    F1 = axial_modes(x, n_modes, params)
    F2 = transverse_modes(x, n_modes, params)
    F1b, F2b = F1[:-1], F2[:-1]
    dF1 = axial_modes(xb, n_modes, params, derivative=1)
    dF2 = transverse_modes(xb, n_modes, params, derivative=1)
    ddF2 = transverse_modes(xb, n_modes, params, derivative=2)

    tip_terms = point_mass_terms(params, mass, position, n_modes, n_quad)
    S = S_matrix(params, x, n_modes, n_quad)
    return SystemMatrices(
        Jh=float(params.Jh),
        Jb=float(wb @ lever**2 + tip_terms["Jb"]),
        K1=_gram(dF1, params.EA_at(xb) * gauss),
        K2=_gram(ddF2, params.EI_at(xb) * gauss),
        M1=_gram(F1b, wb) + tip_terms["M1"],
        M2=_gram(F2b, wb) + tip_terms["M2"],
        V1=(wb * lever) @ F1b + tip_terms["V1"],
        V2=(wb * lever) @ F2b + tip_terms["V2"],
        D=_gram(dF2, gauss * params.outboard_moment(xb)) + tip_terms["D"],
        R=(F1b.T * wb) @ F2b + tip_terms["R"],
        rA=float(params.rA),
        x=x,
        w=w,
        F1=F1,
        F2=F2,
        S=S,
        f1L=axial_modes(params.L, n_modes, params)[0],
        f2L=transverse_modes(params.L, n_modes, params)[0],
        SL=S_matrix(params, params.L, n_modes, n_quad)[0],
    )


#: units and long names of the SystemMatrices fields (CF/UDUNITS strings)
_FIELD_META = {
    "Jh": ("kg m2", "hub moment of inertia J_h", ()),
    "Jb": ("kg m2", "beam and tip-mass moment of inertia about the hub axis J_b (Eq. 13)", ()),
    "K1": ("s-2", "axial stiffness matrix K_1 per unit modal mass (Eq. 14)", ("mode", "mode_j")),
    "K2": ("s-2", "bending stiffness matrix K_2 per unit modal mass (Eq. 15)", ("mode", "mode_j")),
    "M1": ("1", "axial mass matrix M_1 incl. tip mass (Eq. 16, A4)", ("mode", "mode_j")),
    "M2": ("1", "transverse mass matrix M_2 incl. tip mass (Eq. 16, A5)", ("mode", "mode_j")),
    "V1": ("kg1/2 m", "axial first-moment vector V_1 incl. tip mass (Eq. 17)", ("mode",)),
    "V2": ("kg1/2 m", "transverse first-moment vector V_2 incl. tip mass (Eq. 17)", ("mode",)),
    "D": ("1", "foreshortening matrix D incl. m_t (rA + l) S(l) (Eq. 18, A8)", ("mode", "mode_j")),
    "R": ("1", "gyroscopic coupling matrix R incl. m_t f1(l)^T f2(l) (Eq. 19, A6)",
          ("mode", "mode_j")),
    "rA": ("m", "hub radius r_A", ()),
    "x": ("m", "point-cloud abscissa (Gauss nodes on [0, L], then the tip mass)", ("point",)),
    "w": ("kg", "point-cloud mass (rho A(x) times Gauss weight, then m_t)", ("point",)),
    "F1": ("kg-1/2", "axial admissible functions f1 at the points", ("point", "mode")),
    "F2": ("kg-1/2", "transverse admissible functions f2 at the points", ("point", "mode")),
    "S": ("kg-1 m-1", "foreshortening matrix S(x) at the points (Eq. 20)",
          ("point", "mode", "mode_j")),
    "f1L": ("kg-1/2", "axial admissible functions at the beam tip f1(L)", ("mode",)),
    "f2L": ("kg-1/2", "transverse admissible functions at the beam tip f2(L)", ("mode",)),
    "SL": ("kg-1 m-1", "foreshortening matrix at the beam tip S(L) (Eq. 20)", ("mode", "mode_j")),
}

MODE_NORMALISATION = (
    "f1 and f2 normalised to unit modal mass of the bare beam, int_0^L rho A f_i f_j dx = "
    "delta_ij (units kg-1/2); f2: clamped-free Euler-Bernoulli modes, f1: clamped-free rod modes; "
    "for a beam with tabulated sections those of the uniform beam of the same length and mass "
    "(rho A = beam mass / L)"
)


def configuration_name(tip):
    """Wildcard-safe name of a tip-mass configuration: ``mt0``, ``mt0p1_l8``, ``mt0p5_l7p5``."""

    def token(value):
        return f"{float(value):.10g}".replace("-", "m").replace(".", "p").replace("+", "")

    if tip is None or float(tip.mass) == 0.0:
        return "mt0"
    return f"mt{token(tip.mass)}_l{token(tip.position)}"


def to_dataset(sm, params, tip, n_quad_requested=None):
    """Self-describing :class:`xarray.Dataset` of ``sm`` (units, long names, mode coordinates).

    Global attributes record a ``title``, the configuration name, the tip mass, the beam under
    its config keys (``hubbeam.model.beam.beam_attributes``), the number of modes and of Gauss nodes,
    and the mode normalisation. Provenance
    attributes (``Conventions``, ``history``, ...) are added by the writer.
    """
    import xarray as xr

    mass, position = _tip_values(params, tip)
    n = sm.M1.shape[0]
    data_vars = {}
    for name, (units, long_name, dims) in _FIELD_META.items():
        data_vars[name] = xr.Variable(
            dims, np.asarray(getattr(sm, name), dtype=float),
            attrs={"units": units, "long_name": long_name},
        )
    coords = {
        "mode": ("mode", np.arange(1, n + 1), {"long_name": "mode number i (row)", "units": "1"}),
        "mode_j": ("mode_j", np.arange(1, n + 1),
                   {"long_name": "mode number j (column)", "units": "1"}),
        "point": ("point", np.arange(sm.x.size),
                  {"long_name": "point-cloud index (last = tip mass)", "units": "1"}),
    }
    attrs = {
        "title": f"hub-beam system matrices, configuration {configuration_name(tip)}",
        "configuration": configuration_name(tip),
        "tip_mass_kg": mass,
        "tip_position_m": position,
        "n_modes": n,
        "n_quad": sm.x.size - 1,
        "mode_normalisation": MODE_NORMALISATION,
    }
    if n_quad_requested is not None:
        attrs["n_quad_requested"] = int(n_quad_requested)
    attrs |= beam_attributes(params)
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def from_dataset(ds):
    """The :class:`SystemMatrices` stored in a dataset written from :func:`to_dataset`."""
    fields = {}
    for name, (_, _, dims) in _FIELD_META.items():
        value = ds[name].values
        fields[name] = float(value) if dims == () else np.ascontiguousarray(value, dtype=float)
    return SystemMatrices(**fields)
