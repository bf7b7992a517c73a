"""The beam of a study: mass per unit length, bending and axial stiffness against the span.

Reads the dataset of :func:`hubbeam.model.shapes.beam_dataset`: one panel per property, its stations
marked (the properties are linear between them; a uniform beam has two, root and tip), and the tip
mass of every case that has one marked at its position.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.style import LABEL_BOX, axis_label, new_figure, panel_title

#: the properties drawn, top to bottom, with their symbols
PROPERTIES = (("rhoA", r"$\rho A$"), ("EI", "$EI$"), ("EA", "$EA$"))


def tip_masses(beam: xr.Dataset) -> list[tuple[float, float]]:
    """The distinct (mass kg, position m) of the cases' tip masses, without the zero ones."""
    pairs = zip(beam["case_tip_mass"].values, beam["case_tip_position"].values)
    return sorted({(float(mass), float(position)) for mass, position in pairs if mass > 0.0})


def plot(beam: xr.Dataset):
    """rhoA, EI and EA against x, stations and tip masses marked."""
    fig, axes = new_figure(len(PROPERTIES), 1, height=1.6 * len(PROPERTIES) + 0.6)
    masses = tip_masses(beam)
    for index, (name, symbol) in enumerate(PROPERTIES):
        ax = axes[index, 0]
        values = beam[name]
        ax.plot(beam["x"], values, color="#0072B2")
        ax.plot(beam["station"], beam[f"station_{name}"], linestyle="none", marker="o", markersize=3,
                color="#0072B2", label=f"stations ({beam.sizes['station']})" if index == 0 else None)
        ax.set_ylabel(axis_label(symbol, values.attrs["units"]))
        top = float(np.max(values))
        ax.set_ylim(0.0, 1.15 * top)
        panel_title(ax, index, values.attrs["long_name"])
        for mass, position in masses:
            ax.axvline(position, color="#D55E00", linewidth=0.8, linestyle="--")
            if index == 0:
                ax.annotate(f"$m_t$ = {mass:g} kg", xy=(position, 0.05), xycoords=("data", "axes fraction"),
                            xytext=(-3, 0), textcoords="offset points", ha="right", fontsize=7,
                            color="#D55E00", bbox=LABEL_BOX)
    axes[0, 0].legend(loc="lower left", fontsize=7)
    axes[-1, 0].set_xlabel(axis_label("distance from the root $x$", "m"))
    return fig
