"""Snakemake shim: the linear models of every model and hub condition over the speed grid, one
netCDF and one MATLAB file per model, hub and tip mass (``hubbeam.linear.export``)."""

import numpy as np

from hubbeam.configuration.settings import damping_settings
from hubbeam.linear.export import to_dataset, write_dataset, write_mat
from hubbeam.model.beam import beam_from_config
from hubbeam.model.damping import damping_matrices
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import TipMass

p = snakemake.params
beam = beam_from_config(p.beam)
damping = damping_settings(p.damping)
speeds = np.linspace(**p.speeds)
with open(snakemake.log[0], "w") as log:
    for k, mass in enumerate(p.tip_masses):
        tip = TipMass(mass=float(mass), position=float(beam.L)) if mass > 0 else None
        sm = assemble(beam, tip, p.n_modes, p.n_quad)
        C = None if damping is None else damping_matrices(damping, sm)
        for model, hub, netcdf, matlab in (entry[1:] for entry in p.files if entry[0] == k):
            ds = to_dataset(beam, sm, model, speeds, hub, tip, C)
            write_dataset(ds, netcdf)
            write_mat(ds, matlab)
            print(f"{model}, {hub} hub, tip mass {mass} kg: {speeds.size} speeds -> {netcdf}, {matlab}",
                  file=log)
