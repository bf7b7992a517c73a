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

A tip body (``TipMass`` with ``offset`` e, ``docs/tip-body.md``) has its centre of mass ``e``
beyond the attachment along the deformed beam's end tangent: to the order of the models at the
transverse displacement ``(f2(l) + e f2'(l)) q2`` and the axial ``f1(l) q1 - q2^T (S(l) + e
f2'(l)^T f2'(l)) q2 / 2`` from the abscissa ``l + e``. The mass terms above take these values
(:func:`body_centre`) in place of ``f2(l)``, ``S(l)`` and ``l``; the body's rotary inertia is kept
apart (``SystemMatrices.Jt``, ``dF2t``).

The transverse functions are the clamped-free beam's modes (``hubbeam.model.modes``), or, on
request (``functions = "tip_body"``), the modes of the uniform beam clamped at the hub and loaded by
the case's tip body at rest, with which the frequencies converge fast when a body loads the tip
(docs/tip-body.md): :func:`transverse_load` gives their load, :func:`functions_load` recognises it
in assembled matrices.

``rho A``, ``EI`` and ``EA`` may vary along the beam (``hubbeam.model.beam.BeamSections``): they are
evaluated at the quadrature nodes, and the rule breaks at the stations of the tables
(``hubbeam.model.quadrature.beam_rule``). For the uniform beam they are the constants of Table 1.

The beam part of ``D`` is evaluated as the single integral ``int g(xi) f2'^T f2' dxi`` with
``g(xi) = int_xi^L rho A(x) (rA + x) dx`` (order of integration swapped; ``params.outboard_moment``,
exact for piecewise-linear ``rho A``, ``rho A (rA (L - xi) + (L^2 - xi^2) / 2)`` for a uniform
beam), so that one Gauss rule integrates the double integral. ``S`` at the point-cloud nodes uses
its own Gauss rule on ``[0, x]``.
"""

import numpy as np

from hubbeam.core.system_matrices import SystemMatrices
from hubbeam.model.beam import beam_attributes
from hubbeam.model.modes import CLAMPED_FREE, TIP_BODY, TRANSVERSE_FUNCTIONS, axial_modes, transverse_modes
from hubbeam.model.parameters import TipMass, UniformBeam, check_tip
from hubbeam.model.quadrature import beam_rule, effective_points, gauss_legendre, point_cloud


def checked_tip(params, tip):
    """``tip`` checked on the beam ``params`` (``check_tip``); no tip mass is a zero point mass at
    the beam tip."""
    if tip is None:
        return TipMass(0.0, float(params.L))
    check_tip(tip, params.L)
    return tip


def transverse_load(params, tip: TipMass, functions: str = CLAMPED_FREE):
    """The load of the transverse functions named ``functions`` (``hubbeam.model.modes``): None for
    the clamped-free functions; for ``"tip_body"`` the ratios ``(m / (rho A L), J / (rho A L^3), e /
    L)`` of the checked body ``tip``, which must sit at the end of a uniform beam (the closed form
    of the loaded beam's modes). A ``ValueError`` names what is not allowed."""
    if functions not in TRANSVERSE_FUNCTIONS:
        raise ValueError(f"functions = {functions!r}; allowed: one of {', '.join(TRANSVERSE_FUNCTIONS)}")
    if functions == CLAMPED_FREE:
        return None
    if not isinstance(params, UniformBeam):
        raise ValueError(f"functions = {TIP_BODY!r} with a beam of sections; allowed: a uniform beam (the "
                         "loaded beam's modes are those of a uniform beam)")
    if tip.position != params.L:
        raise ValueError(f"functions = {TIP_BODY!r} with tip_mass.position = {tip.position!r}; allowed: the "
                         f"beam's end L = {params.L} m (the loaded beam's modes carry the body at the end)")
    rhoA, L = float(params.rhoA), float(params.L)
    return (tip.mass / (rhoA * L), tip.inertia / (rhoA * L**3), tip.offset / L)


def functions_load(params, sm):
    """The load of the transverse functions ``sm`` was assembled with on the beam ``params``: None
    for the clamped-free functions, the tip body's ratios for its ``"tip_body"`` functions (the body
    read from the point cloud's last point, at the beam's end); recognised by ``f2(L)``. A
    ``ValueError`` when neither gives ``sm.f2L`` (matrices of another beam)."""
    n = sm.M2.shape[0]

    def gives_f2L(load):
        return np.allclose(sm.f2L, transverse_modes(params.L, n, params, load=load)[0], rtol=1e-12, atol=0.0)

    if gives_f2L(None):
        return None
    if isinstance(params, UniformBeam):
        rhoA, L = float(params.rhoA), float(params.L)
        load = (float(sm.w[-1]) / (rhoA * L), float(sm.Jt) / (rhoA * L**3), (float(sm.x[-1]) - L) / L)
        if gives_f2L(load):
            return load
    raise ValueError("sm: system matrices assembled for another beam; allowed: "
                     "hubbeam.model.matrices.assemble(beam, tip, n_modes) of this beam")


def body_centre(f2, S, slope, offset):
    """``f2`` and ``S`` at the centre of a body ``offset`` beyond its attachment, from ``f2``,
    ``S`` and the slope functions ``slope = f2'`` there: ``f2 + e f2'`` and ``S + e f2'^T f2'``.

    The centre lies ``e`` along the deformed beam's tangent at the attachment, turned by the
    slope ``phi = f2' q2``: it moves ``e sin(phi) = e f2' q2`` across and ``e (cos(phi) - 1) =
    -e (f2' q2)^2 / 2`` along the beam to the second order, the order of the foreshortening
    ``-q2^T S q2 / 2`` (Eq. 20). Arrays of shape ``s + (n,)`` and ``s + (n, n)`` with ``offset`` of
    shape ``s``.
    """
    e = np.asarray(offset, dtype=float)[..., None]
    return f2 + e * slope, S + e[..., None] * slope[..., :, None] * slope[..., None, :]


def _gram(values, weights):
    """``sum_k weights_k values_k^T values_k`` for ``values`` of shape (m, n), exactly symmetric."""
    product = (values.T * weights) @ values
    return 0.5 * (product + product.T)


def S_matrix(params, x, n_modes, n_quad=64, load=None):
    """``S(x) = int_0^x f2'(xi)^T f2'(xi) dxi`` (Eq. 20) at abscissae ``x``, shape (m, n, n).

    Each ``S(x_k)`` is integrated by its own Gauss-Legendre rule on ``[0, x_k]`` with
    ``effective_points(n_quad, n_modes)`` nodes. Units kg^-1 m^-1. ``load``: the transverse
    functions' (:func:`transverse_load`).
    """
    x = np.atleast_1d(np.asarray(x, dtype=float))
    nodes, weights = gauss_legendre(effective_points(n_quad, n_modes), np.zeros_like(x), x)
    slopes = transverse_modes(nodes.ravel(), n_modes, params, derivative=1, load=load)
    slopes = slopes.reshape(nodes.shape + (n_modes,))
    S = np.einsum("kq,kqi,kqj->kij", weights, slopes, slopes)
    return 0.5 * (S + np.swapaxes(S, -1, -2))


def point_mass_terms(params, mass, position, n_modes, n_quad=64, offset=0.0, load=None):
    """Contributions of a mass ``mass`` attached at ``position`` to Jb, M1, M2, V1, V2, D, R.

    ``mass``, ``position`` and ``offset`` broadcast against each other (shape ``s``); each returned
    array has shape ``s`` (Jb), ``s + (n,)`` (V1, V2) or ``s + (n, n)`` (M1, M2, D, R). This is the
    term ``m_t * integrand(l)`` of every mass integral (Appendix with ``L -> l``), shared by
    :func:`assemble` and the parameter sweeps of :mod:`hubbeam.model.eigen`; a nonzero ``offset``
    moves the mass to its body's centre (:func:`body_centre`, lever ``rA + l + e``); ``load``: the
    transverse functions' (:func:`transverse_load`).
    """
    mass, position, offset = np.broadcast_arrays(np.asarray(mass, float), np.asarray(position, float),
                                                 np.asarray(offset, float))
    for m, l, e in zip(mass.ravel(), position.ravel(), offset.ravel()):
        check_tip(TipMass(m, l, 0.0, e), params.L)
    shape = mass.shape
    flat_l = position.ravel()
    f1 = axial_modes(flat_l, n_modes, params).reshape(shape + (n_modes,))
    f2 = transverse_modes(flat_l, n_modes, params, load=load).reshape(shape + (n_modes,))
    S = S_matrix(params, flat_l, n_modes, n_quad, load).reshape(shape + (n_modes, n_modes))
    lever = params.rA + position
    if np.any(offset != 0.0):
        slope = transverse_modes(flat_l, n_modes, params, derivative=1, load=load).reshape(shape + (n_modes,))
        f2, S = body_centre(f2, S, slope, offset)
        lever = lever + offset
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


def assemble(params, tip=None, n_modes=5, n_quad=64, functions=CLAMPED_FREE):
    """Assemble :class:`SystemMatrices` for ``n_modes`` modes (Eqs. 13-20, Appendix).

    Parameters
    ----------
    params : BeamParameters or BeamSections
        Table 1 (``L, rho, A, E, I, Jh, rA``) or a beam with tabulated sections.
    tip : TipMass or None
        Tip mass ``tip.mass`` (kg) at ``0 <= tip.position <= L`` (m), a point mass or a body with
        rotary inertia ``tip.inertia`` and offset ``tip.offset`` (``docs/tip-body.md``); ``None``
        for none. Checked by ``hubbeam.model.parameters.check_tip``.
    n_modes : int
        Number of assumed modes for each of q1 and q2 (1..20).
    n_quad : int
        Requested Gauss-Legendre nodes on ``[0, L]`` (config ``numerics.quadrature_points``).
        The rule actually used has ``effective_points(n_quad, n_modes) = max(n_quad,
        30 + 3 n_modes)`` nodes (64 for 5 modes with the configured 64, 90 for 20 modes), enough
        for every matrix to be converged to 1e-12 relative; the point cloud then has that many
        nodes plus the tip body's centre. A beam with sections gets a composite rule broken at its
        stations with at least that many nodes (``hubbeam.model.quadrature.beam_rule``).
    functions : str
        The admissible transverse functions (``hubbeam.model.modes.TRANSVERSE_FUNCTIONS``):
        ``"clamped_free"``, the clamped-free beam's modes (the paper's, the default), or
        ``"tip_body"``, the modes of the uniform beam clamped at the hub and loaded by ``tip`` at
        its end, at rest (:func:`transverse_load`), with which the frequencies converge fast
        when a body loads the tip (docs/tip-body.md).
    """
    tip = checked_tip(params, tip)
    load = transverse_load(params, tip, functions)
    mass, position = tip.mass, tip.position
    nq = effective_points(n_quad, n_modes)
    x, w = point_cloud(params, mass, position, nq)
    xb, gauss = beam_rule(params, nq)  # the beam nodes of x and their plain weights
    wb, lever = w[:-1], params.rA + xb
    F1 = axial_modes(x, n_modes, params)
    F2 = transverse_modes(x, n_modes, params, load=load)
    F1b, F2b = F1[:-1], F2[:-1]
    dF1 = axial_modes(xb, n_modes, params, derivative=1)
    dF2 = transverse_modes(xb, n_modes, params, derivative=1, load=load)
    ddF2 = transverse_modes(xb, n_modes, params, derivative=2, load=load)

    tip_terms = point_mass_terms(params, mass, position, n_modes, n_quad, tip.offset, load)
    S = S_matrix(params, x, n_modes, n_quad, load)
    slope = transverse_modes(position, n_modes, params, derivative=1, load=load)[0]
    if tip.offset != 0.0:  # the last point of the cloud is the body's centre
        x[-1] = position + tip.offset
        F2[-1], S[-1] = body_centre(F2[-1], S[-1], slope, tip.offset)
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
        f2L=transverse_modes(params.L, n_modes, params, load=load)[0],
        SL=S_matrix(params, params.L, n_modes, n_quad, load)[0],
        Jt=tip.inertia,
        dF2t=slope,
    )


#: units and long names of the SystemMatrices fields (CF/UDUNITS strings)
_FIELD_META = {
    "Jh": ("kg m2", "hub moment of inertia J_h", ()),
    "Jb": ("kg m2", "beam and tip-mass moment of inertia about the hub axis J_b (Eq. 13), the tip "
                    "body's rotary inertia J_t apart", ()),
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
    "x": ("m", "point-cloud abscissa (Gauss nodes on [0, L], then the tip body's centre)", ("point",)),
    "w": ("kg", "point-cloud mass (rho A(x) times Gauss weight, then m_t)", ("point",)),
    "F1": ("kg-1/2", "axial admissible functions f1 at the points", ("point", "mode")),
    "F2": ("kg-1/2", "transverse admissible functions f2 at the points", ("point", "mode")),
    "S": ("kg-1 m-1", "foreshortening matrix S(x) at the points (Eq. 20)",
          ("point", "mode", "mode_j")),
    "f1L": ("kg-1/2", "axial admissible functions at the beam tip f1(L)", ("mode",)),
    "f2L": ("kg-1/2", "transverse admissible functions at the beam tip f2(L)", ("mode",)),
    "SL": ("kg-1 m-1", "foreshortening matrix at the beam tip S(L) (Eq. 20)", ("mode", "mode_j")),
    "Jt": ("kg m2", "rotary inertia J_t of the tip body about its centre of mass", ()),
    "dF2t": ("kg-1/2 m-1", "slope functions f2'(l) at the tip body's attachment", ("mode",)),
}

MODE_NORMALISATION = (
    "f1 and f2 normalised to unit modal mass of the bare beam, int_0^L rho A f_i f_j dx = "
    "delta_ij (units kg-1/2); f2: clamped-free Euler-Bernoulli modes, f1: clamped-free rod modes; "
    "for a beam with tabulated sections those of the uniform beam of the same length and mass "
    "(rho A = beam mass / L)"
)


def configuration_name(tip, functions=CLAMPED_FREE):
    """Wildcard-safe name of a tip-mass configuration: ``mt0``, ``mt0p1_l8``, ``mt0p5_l7p5``; a
    body adds its rotary inertia and offset, ``mt0p1_l0p5_J0p0005_e0p02``; transverse functions
    other than the clamped-free ones add their name, ``mt0p1_l0p5_J0p0005_tip_body``."""
    name = _tip_name(tip)
    return name if functions == CLAMPED_FREE else f"{name}_{functions}"


def _tip_name(tip):

    def token(value):
        return f"{float(value):.10g}".replace("-", "m").replace(".", "p").replace("+", "")

    if tip is None or (float(tip.mass) == 0.0 and tip.is_point):
        return "mt0"
    name = f"mt{token(tip.mass)}_l{token(tip.position)}"
    if tip.inertia != 0.0:
        name += f"_J{token(tip.inertia)}"
    if tip.offset != 0.0:
        name += f"_e{token(tip.offset)}"
    return name


def to_dataset(sm, params, tip, n_quad_requested=None, functions=CLAMPED_FREE):
    """Self-describing :class:`xarray.Dataset` of ``sm`` (units, long names, mode coordinates).

    Global attributes record a ``title``, the configuration name, the tip mass (and the body's
    rotary inertia and offset), the beam under its config keys
    (``hubbeam.model.beam.beam_attributes``), the number of modes and of Gauss nodes,
    and the mode normalisation; matrices assembled with other transverse ``functions`` than the
    clamped-free ones (:func:`assemble`) record them as ``transverse_functions``. Provenance
    attributes (``Conventions``, ``history``, ...) are added by the writer.
    """
    import xarray as xr

    body = checked_tip(params, tip)
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
                  {"long_name": "point-cloud index (last = tip body's centre)", "units": "1"}),
    }
    attrs = {
        "title": f"hub-beam system matrices, configuration {configuration_name(tip, functions)}",
        "configuration": configuration_name(tip, functions),
        "tip_mass_kg": body.mass,
        "tip_position_m": body.position,
        "tip_inertia_kg_m2": body.inertia,
        "tip_offset_m": body.offset,
        "n_modes": n,
        "n_quad": sm.x.size - 1,
        "mode_normalisation": MODE_NORMALISATION,
    }
    if n_quad_requested is not None:
        attrs["n_quad_requested"] = int(n_quad_requested)
    if functions != CLAMPED_FREE:
        transverse_load(params, body, functions)
        attrs["transverse_functions"] = functions
        attrs["mode_normalisation"] = MODE_NORMALISATION.replace(
            "f2: clamped-free Euler-Bernoulli modes", "f2: modes of the uniform beam clamped at the hub and loaded "
            "by the tip body at rest")
    attrs |= beam_attributes(params)
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def from_dataset(ds, modes=None):
    """The :class:`SystemMatrices` stored in a dataset written from :func:`to_dataset`; with ``modes``,
    those of its first ``modes`` modes (the leading blocks: the functions of a count are the first
    of a larger count's)."""
    if modes is not None:
        ds = ds.isel(mode=slice(0, modes), mode_j=slice(0, modes))
    fields = {}
    for name, (_, _, dims) in _FIELD_META.items():
        value = ds[name].values
        fields[name] = float(value) if dims == () else np.ascontiguousarray(value, dtype=float)
    return SystemMatrices(**fields)
