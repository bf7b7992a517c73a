"""Independent validation of the hub-beam models.

* :mod:`hubbeam.validation.published` -- published first frequencies of rotating cantilevers
  (flapwise and chordwise, against the dimensionless speed) and of a cantilever with a tip mass,
  exactly as printed, with their sources.
* :mod:`hubbeam.validation.rotating_eigen` -- the constant-speed linearisation of FOAM in
  dimensionless form (quadratic eigenproblem with the Coriolis coupling of the axial and
  transverse coordinates) and the comparison with the published tables.
* :mod:`hubbeam.validation.exudyn_model` -- the same hub-beam in Exudyn with geometrically exact
  2D ANCF cable elements, a prescribed rotating clamp and an optional tip mass (optional
  dependency, ``pip install -e .[validation]``).
* :mod:`hubbeam.validation.comparison` -- tip-deflection metrics of FOAM, CFOAM and TLAM against
  the Exudyn reference and the comparison figure.
"""
