"""Figures of the paper (Figs. 3-10) and beyond, drawn from result datasets only.

``render(key, datasets, pdf_path)`` draws figure ``key`` in the hubbeam style and writes the PDF
with a PNG beside it. The simulation figures take ``{case name: Dataset}``; which cases feed which
figure is decided by :func:`hubbeam.plotting.figures.cases_for`.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from pathlib import Path

from hubbeam.io import open_result

from hubbeam.plotting.figures import FIGURE_CASE_PREFIXES, FigureDataError, cases_for
from hubbeam.plotting.style import save_figure, styled

#: figure key -> module whose ``plot(...)`` draws it (simulation figures; the eigen figures
#: ``fig09`` and ``campbell`` have their own functions in ``fig09.py`` and ``campbell.py``).
SIMULATION_FIGURES = {
    "fig03": "fig03", "fig04": "fig04", "fig05": "fig05", "fig06": "fig06",
    "fig07": "fig07", "fig08": "fig08", "fig10": "fig10", "convergence": "convergence",
}


def plotter(key: str):
    """The ``plot`` function of simulation figure ``key``."""
    if key not in SIMULATION_FIGURES:
        raise KeyError(f"unknown figure {key!r}; allowed: {sorted(SIMULATION_FIGURES)}")
    return importlib.import_module(f"hubbeam.plotting.{SIMULATION_FIGURES[key]}").plot


def draw(plot, pdf_path, *args, **kwargs) -> tuple[Path, Path]:
    """Call ``plot(*args, **kwargs)`` in the hubbeam style and save its figure (PDF + PNG)."""
    with styled():
        fig = plot(*args, **kwargs)
        return save_figure(fig, pdf_path)


def render(key: str, datasets, pdf_path, **kwargs) -> tuple[Path, Path]:
    """Draw simulation figure ``key`` from ``{case: Dataset}`` and write ``pdf_path`` + PNG."""
    return draw(plotter(key), pdf_path, datasets, **kwargs)


def render_files(key: str, case_files: Mapping[str, str | Path], pdf_path) -> tuple[Path, Path]:
    """:func:`render` from result files ``{case: path}``; a missing or unreadable file raises
    :class:`hubbeam.io.ResultFileError` naming it."""
    return render(key, {case: open_result(path) for case, path in case_files.items()}, pdf_path)


__all__ = ["FIGURE_CASE_PREFIXES", "FigureDataError", "SIMULATION_FIGURES", "cases_for", "draw",
           "plotter", "render", "render_files"]
