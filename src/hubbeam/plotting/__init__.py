"""Figures of the paper (Figs. 3-10) and beyond, drawn from result datasets only.

Each figure module has a ``plot(...)`` function returning a matplotlib figure; which cases or
result files feed it is declared in :mod:`hubbeam.reporting.products`. :func:`draw` calls a plot function in
the hubbeam style and writes the PDF with a PNG beside it.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from hubbeam.plotting.style import save_figure, styled
from hubbeam.results.io import open_result


def draw(plot, pdf_path, *args, **kwargs) -> tuple[Path, Path]:
    """Call ``plot(*args, **kwargs)`` in the hubbeam style and save its figure (PDF + PNG)."""
    with styled():
        fig = plot(*args, **kwargs)
        return save_figure(fig, pdf_path)


def render_files(plot, case_files: Mapping[str, str | Path], pdf_path) -> tuple[Path, Path]:
    """Draw ``plot({case: Dataset})`` from result files ``{case: path}`` and write ``pdf_path`` + PNG;
    a missing or unreadable file raises :class:`hubbeam.results.io.ResultFileError` naming it."""
    return draw(plot, pdf_path, {case: open_result(path) for case, path in case_files.items()})


__all__ = ["draw", "render_files"]
