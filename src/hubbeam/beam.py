"""Beam parameters from the ``beam`` section of a config (uniform beam of Table 1).

:func:`beam_from_config` is the one entry point the workflow uses to build a beam. This version
knows the uniform beam only; a beam given by ``sections`` (stations of rhoA, EI, EA) is refused
with a clear message until the non-uniform assembly exists.
"""

from __future__ import annotations

from collections.abc import Mapping

from hubbeam.parameters import BeamParameters


def beam_from_config(beam: Mapping) -> BeamParameters:
    """The beam of a validated ``beam`` section (uniform keys of Table 1)."""
    if "sections" in beam:
        raise NotImplementedError(
            "beam.sections: non-uniform beams (stations of rhoA, EI, EA) are not supported by "
            "this version of hubbeam; allowed: the uniform keys density, area, youngs_modulus, "
            "second_moment")
    return BeamParameters.from_config({"beam": beam})
