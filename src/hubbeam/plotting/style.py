"""The one look of every hubbeam figure: style sheet, model colours, labels, reproducible saving.

Every figure is drawn inside :func:`styled` (which applies ``hubbeam.mplstyle``) on a
:class:`matplotlib.figure.Figure` created without pyplot, so no global figure state leaks between
figures. :func:`save_figure` writes the PDF and a PNG beside it with the volatile metadata
(PDF ``CreationDate``/``Producer``, PNG ``Software``) removed, so a rerun gives identical bytes.
"""

from __future__ import annotations

import contextlib
import re
from pathlib import Path

import matplotlib
import matplotlib.style
from matplotlib.figure import Figure

STYLE_FILE = Path(__file__).with_name("hubbeam.mplstyle")

#: Fixed colour and line style per model, so a model looks the same in every figure.
MODEL_STYLE = {
    "TLAM": {"color": "#D55E00", "linestyle": "-"},
    "FOAM": {"color": "#0072B2", "linestyle": "-"},
    "CFOAM": {"color": "#009E73", "linestyle": "--"},
    "SFOAM": {"color": "#CC79A7", "linestyle": "--"},
}
#: Extra dash patterns for several curves of one model (e.g. 1, 3, 5 modes).
VARIANT_LINESTYLES = ("-", "--", ":", "-.", (0, (5, 1, 1, 1)), (0, (1, 1)))
#: Colours for curves that are not distinguished by model (modal coordinates, speeds, ...).
SEQUENCE_COLORS = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000")

#: Background of a text label drawn over data (time marks, critical speeds): the curves stay
#: visible through it, the label stays readable where a curve crosses it.
LABEL_BOX = {"boxstyle": "square,pad=0.15", "facecolor": "white", "edgecolor": "none", "alpha": 0.75}

PDF_METADATA = {"CreationDate": None, "Producer": None, "Creator": "hubbeam"}
PNG_METADATA = {"Software": None}
PNG_DPI = 200

_GREEK = {"theta": r"\theta", "tau": r"\tau", "omega": r"\omega", "Omega": r"\Omega"}


@contextlib.contextmanager
def styled():
    """Apply the hubbeam style (and only it) for the figures built inside the block."""
    with matplotlib.rc_context():
        matplotlib.style.use("default")
        matplotlib.style.use(STYLE_FILE)
        yield


def new_figure(nrows: int = 1, ncols: int = 1, *, height: float | None = None,
               width: float | None = None, sharex: bool | str = True, **subplot_kw):
    """A pyplot-free figure with a grid of axes; call inside :func:`styled`."""
    w, h = matplotlib.rcParams["figure.figsize"]
    fig = Figure(figsize=(width or w, height or h))
    axes = fig.subplots(nrows, ncols, sharex=sharex, squeeze=False, **subplot_kw)
    return fig, axes


def save_figure(fig: Figure, pdf_path) -> tuple[Path, Path]:
    """Write ``<name>.pdf`` and ``<name>.png`` beside it, without volatile metadata."""
    pdf_path = Path(pdf_path)
    if pdf_path.suffix != ".pdf":
        raise ValueError(f"figure output must end in .pdf, got {str(pdf_path)!r}")
    pdf_path.parent.mkdir(parents=True, exist_ok=True)
    png_path = pdf_path.with_suffix(".png")
    with styled():
        fig.savefig(pdf_path, format="pdf", metadata=PDF_METADATA)
        fig.savefig(png_path, format="png", dpi=PNG_DPI, metadata=PNG_METADATA)
    return pdf_path, png_path


def units_tex(units: str) -> str:
    """UDUNITS string to mathtext: ``"rad s-1"`` -> ``"rad s$^{-1}$"``, ``"kg1/2 m"`` -> ``"kg$^{1/2}$ m"``."""
    if not units or units == "1":
        return "-"
    return re.sub(r"(?<=[A-Za-z])(-?\d+(?:/\d+)?)", lambda m: "$^{" + m.group(1) + "}$", units)


def number_tex(value: float, digits: int = 2) -> str:
    """``value`` to ``digits`` significant figures in mathtext: ``0.21``, ``$4.4\\times10^{-5}$``."""
    mantissa, _, exponent = f"{value:.{digits - 1}e}".partition("e")
    power = int(exponent)
    if -2 <= power < 3:
        return f"{float(f'{value:.{digits}g}'):g}"
    return f"${mantissa}\\times10^{{{power}}}$"


def axis_label(quantity: str, units: str) -> str:
    """``"Tip deflection $v(L)$ (m)"`` style label: quantity followed by units in parentheses."""
    return f"{quantity} ({units_tex(units)})"


def symbol_tex(name: str) -> str:
    """Mathtext for a variable name such as ``dQ_theta`` or ``M_thth`` (``d`` prefix -> Delta)."""
    delta = r"\Delta " if name.startswith("d") and name[1:2].isupper() else ""
    base = name[1:] if delta else name
    head, _, sub = base.partition("_")
    sub = {"thth": r"\theta\theta"}.get(sub, _GREEK.get(sub, sub))
    sub = re.sub(r"q(\d)", r"q_{\1}", sub)
    return f"${delta}{head}_{{{sub}}}$" if sub else f"${delta}{head}$"


def model_style(model: str, variant: int = 0) -> dict:
    """Line properties of ``model``; ``variant`` > 0 changes only the dash pattern."""
    style = dict(MODEL_STYLE.get(model, {"color": "#000000", "linestyle": "-"}))
    if variant:
        style["linestyle"] = VARIANT_LINESTYLES[variant % len(VARIANT_LINESTYLES)]
    return style


def panel_title(ax, index: int, text: str) -> None:
    """Title ``(a) text`` for the ``index``-th panel (0-based)."""
    ax.set_title(f"({chr(ord('a') + index)}) {text}")


def mark_time(ax, t: float, text: str, color: str = "0.35") -> None:
    """A light vertical line at time ``t``, labelled along the line (left of it, from the top),
    so that several marks never overprint each other."""
    ax.axvline(t, color="0.55", linewidth=0.7, linestyle=":", zorder=0)
    ax.annotate(text, xy=(t, 1.0), xycoords=("data", "axes fraction"), xytext=(-2, -3),
                textcoords="offset points", ha="right", va="top", rotation=90, fontsize=7,
                color=color, bbox=LABEL_BOX)
