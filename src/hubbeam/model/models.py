"""The one table of the hub-beam models: TLAM, FOAM, SFOAM and CFOAM (Section 3 of the paper).

Every trait that decides what is computed for a model is stated here once, and every other part of
hubbeam (the kernels' dispatch, the dataset's variables, the constant-speed linearisation, the
validity checks, the workflow's wildcard constraints and kernel families, the linear models) reads
it from :data:`MODELS`. Code outside this module does not compare a model's name to decide what to
compute (``tests/test_models.py`` fails when it does).

Traits of a model (:class:`Model`):

* ``keeps_axial``: the axial coordinates ``q1`` are integrated (SFOAM holds them at zero, Eq. 40);
* ``softening_terms``: the underlined ``D`` terms of Eqs. (25), (31), (32) are kept (all but TLAM);
* ``hub_velocity_force``: the velocity-dependent generalised force ``Q_theta`` of Eq. (32) acts on
  the hub (SFOAM deletes it, Eq. 40);
* ``exact_kinetic_energy``: the equations come from the exact kinetic energy of Eqs. (8)-(9)
  (CFOAM) instead of its first-order expansion, Eqs. (24)-(34);
* ``linearisation``: the variant of the constant-speed equations, Eq. (31), that linearises it
  about a steady spin (``hubbeam.model.linearised.CENTRIFUGAL_TERMS``): TLAM's for TLAM, FOAM's for the
  others. CFOAM's high-order terms are of second order in the elastic coordinates (reproduction
  note 5); about ``q2 = 0`` they leave only products of the steady axial stretch ``q1s`` with the
  deflection, a relative change of the order of the stretch ``f1(L) q1s / L`` (3e-6 for the
  paper's beam at 2 rad/s; ``tests/test_initial_state.py`` measures it), which FOAM's
  linearisation neglects;
* ``high_order_outputs``: the dataset carries CFOAM-minus-FOAM terms along the trajectory
  (``hubbeam.results.variables.HIGH_ORDER_VARIABLES``).

Derived from them: :attr:`Model.traits`, the flags the jitted kernels receive
(:class:`hubbeam.core.inputs.ModelTraits`), and :attr:`Model.family`, the compiled kernel that
integrates the model (``"foam"``: the constant modal mass of Eq. (24) inverted once,
``hubbeam.core.foam_rhs``; ``"cfoam"``: the exact kinetic energy, ``hubbeam.core.cfoam_rhs``).
Importing this module is cheap (no numba).
"""

from __future__ import annotations

from dataclasses import dataclass

from hubbeam.core import inputs


@dataclass(frozen=True)
class Model:
    """One hub-beam model and the traits that decide what is computed for it."""

    name: str
    keeps_axial: bool
    softening_terms: bool
    hub_velocity_force: bool
    exact_kinetic_energy: bool
    linearisation: str
    high_order_outputs: bool
    description: str

    @property
    def traits(self) -> inputs.ModelTraits:
        """The flags the jitted kernels branch on."""
        return inputs.ModelTraits(self.keeps_axial, self.softening_terms, self.hub_velocity_force,
                                  self.exact_kinetic_energy)

    def state_names(self, n: int) -> tuple[str, ...]:
        """The states of the model with ``n`` modes, as its linear models and its feedback gains name
        them: ``theta``, ``q1_1..q1_n`` (a model that keeps ``q1``), ``q2_1..q2_n``, then their rates
        ``*_dot``."""
        blocks = ("q1", "q2") if self.keeps_axial else ("q2",)
        coordinates = ("theta",) + tuple(f"{b}_{i}" for b in blocks for i in range(1, n + 1))
        return coordinates + tuple(f"{c}_dot" for c in coordinates)

    @property
    def family(self) -> str:
        """The compiled kernel family that integrates the model (``hubbeam.core.inputs.FAMILIES``)."""
        return inputs.family(self.traits)


#: the models, in the paper's order
MODELS: dict[str, Model] = {model.name: model for model in (
    Model("TLAM", keeps_axial=True, softening_terms=False, hub_velocity_force=True,
          exact_kinetic_energy=False, linearisation="TLAM", high_order_outputs=False,
          description="traditional linear approximation model: no foreshortening terms"),
    Model("FOAM", keeps_axial=True, softening_terms=True, hub_velocity_force=True,
          exact_kinetic_energy=False, linearisation="FOAM", high_order_outputs=False,
          description="first-order approximation model, Eqs. (24)-(34)"),
    Model("SFOAM", keeps_axial=False, softening_terms=True, hub_velocity_force=False,
          exact_kinetic_energy=False, linearisation="FOAM", high_order_outputs=False,
          description="simplified first-order model, Eq. (40): q1 and Q_theta dropped"),
    Model("CFOAM", keeps_axial=True, softening_terms=True, hub_velocity_force=True,
          exact_kinetic_energy=True, linearisation="FOAM", high_order_outputs=True,
          description="complete model: the exact kinetic energy of Eqs. (8)-(9)"),
)}

#: models that controllers may be designed on but that hubbeam does not simulate: ``lumped``, the
#: Quanser courseware's four-state model of a flexible link (``hubbeam.linear.lumped``)
DESIGN_ONLY_MODELS: tuple[str, ...] = ("lumped",)

#: the kernel families the models use, each compiled once (``hubbeam.core.integrate.FAMILY_KERNELS``)
FAMILIES: tuple[str, ...] = tuple(dict.fromkeys(model.family for model in MODELS.values()))


class UnknownModelError(ValueError):
    """A model name that is not in :data:`MODELS`."""


def model(name: str) -> Model:
    """The :class:`Model` called ``name``; an :class:`UnknownModelError` names the allowed ones."""
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        raise UnknownModelError(f"model = {name!r}; allowed: one of {', '.join(MODELS)}") from None


def family_model(family: str) -> Model:
    """The first model (in the paper's order) that the kernel family ``family`` integrates."""
    return next(m for m in MODELS.values() if m.family == family)


def wildcard_pattern(values) -> str:
    """A regular expression for a Snakemake wildcard that matches exactly ``values``."""
    return "|".join(sorted(values, key=len, reverse=True))
