"""Calibrating a case's physical model to a rig's measurements, with intervals.

The experiments are data files (:mod:`~hubbeam.identification.experiments`: natural frequencies,
frequency responses, time series; read by :mod:`~hubbeam.identification.files`, the CSV tables of
:mod:`hubbeam.configuration.tabular` with a unit in every column's header), the free parameters are
named by the configuration keys of the case (:mod:`~hubbeam.identification.parameters`), the
predictions come from the case's model through one adapter (:mod:`~hubbeam.identification.plant`,
:mod:`~hubbeam.identification.predictions`), the fit is bounded weighted least squares from several
starts with intervals from the Jacobian and a verdict on identifiability
(:mod:`~hubbeam.identification.fit`), written as a CF dataset
(:mod:`~hubbeam.identification.dataset`). :mod:`~hubbeam.identification.spectra` estimates a
frequency response and a free decay from a time series, :mod:`~hubbeam.identification.synthetic`
makes a rig's experiments from CFOAM, :mod:`~hubbeam.identification.section` checks the planned
``identify`` section of a study. ``docs/identification.md`` describes all of it.
"""
