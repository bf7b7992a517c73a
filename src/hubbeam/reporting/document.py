"""Documents of hubbeam: Markdown assembled from the Jinja2 templates of ``hubbeam/reporting/templates``
and rendered to self-contained HTML (images embedded) by markdown-it-py.

The prose of the reports lives in the templates; the modules that write a report compute its
numbers (written by :mod:`hubbeam.reporting.formatting`) and tables (rendered by :func:`markdown_table`, the
one renderer of a Markdown table) and hand them to :func:`render`.
"""

from __future__ import annotations

import base64
import html
from collections.abc import Iterable, Sequence
from functools import cache
from pathlib import Path

import jinja2
from markdown_it import MarkdownIt

from hubbeam.reporting.formatting import number

#: the templates :func:`render` reads (package data: the rules that render them depend on them)
PACKAGE_DATA = ("templates/*.j2",)
CSS = ("body{font-family:sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;line-height:1.45}"
       "table{border-collapse:collapse;margin:1rem 0;font-size:.9rem}"
       "th,td{border:1px solid #ccc;padding:.25rem .5rem;vertical-align:top}th{background:#f2f2f2}"
       "img{max-width:100%;display:block}.caption{display:block;font-size:.9rem;color:#444}"
       "code{background:#f5f5f5;padding:0 .2rem}")


#: column alignments of :func:`markdown_table`: left, right, centre
ALIGNMENTS = {"l": "---", "r": "---:", "c": ":---:"}


def markdown_table(columns: Sequence[str], rows: Iterable[Sequence], align: str | None = None) -> str:
    """The one renderer of a Markdown (pipe) table: a header row of ``columns``, the separator
    and one line per row, without a trailing newline.

    ``align`` gives one letter of :data:`ALIGNMENTS` per column (default: all left). A cell that is
    not text is written by :func:`hubbeam.reporting.formatting.number` (4 significant figures, ``-`` when
    missing); ``|`` in a cell is escaped and a line break becomes a space, so a cell never splits
    the table.
    """
    align = align or "l" * len(columns)
    if len(align) != len(columns) or set(align) - set(ALIGNMENTS):
        raise ValueError(f"align: got {align!r} for {len(columns)} columns; allowed: one of "
                         f"{', '.join(ALIGNMENTS)} per column")
    lines = [_row(columns), "|" + "|".join(ALIGNMENTS[a] for a in align) + "|"]
    for row in rows:
        row = list(row)
        if len(row) != len(columns):
            raise ValueError(f"table row {row!r}: {len(row)} cells; allowed: {len(columns)} "
                             f"({', '.join(columns)})")
        lines.append(_row(row))
    return "\n".join(lines)


def _row(cells) -> str:
    text = (cell if isinstance(cell, str) else number(cell) for cell in cells)
    return "| " + " | ".join(" ".join(t.replace("|", "\\|").splitlines()) for t in text) + " |"


@cache
def _environment() -> jinja2.Environment:
    environment = jinja2.Environment(loader=jinja2.PackageLoader("hubbeam.reporting", "templates"),
                                     undefined=jinja2.StrictUndefined, trim_blocks=True,
                                     lstrip_blocks=True, keep_trailing_newline=True, autoescape=False)
    environment.filters["number"] = number  # a number in the prose, as in the tables
    return environment


def render(template: str, **context) -> str:
    """The template ``hubbeam/reporting/templates/<template>`` rendered with ``context``."""
    return _environment().get_template(template).render(**context)


def _image_renderer(base: Path):
    def image(self, tokens, idx, options, env):
        token = tokens[idx]
        src = token.attrGet("src")
        path = (base / src).resolve()
        if not path.is_file():
            raise FileNotFoundError(f"report image {path} (linked as {src!r}) does not exist")
        data = base64.b64encode(path.read_bytes()).decode("ascii")
        mime = "image/png" if path.suffix.lower() == ".png" else "image/svg+xml"
        alt = self.renderInlineAsText(token.children or [], options, env)
        return (f'<img alt="{html.escape(alt)}" src="data:{mime};base64,{data}">'
                f'<span class="caption">{html.escape(alt)}</span>')
    return image


def markdown_to_html(markdown: str, base_dir, title: str = "hubbeam reproduction report") -> str:
    """Self-contained HTML of ``markdown`` (CommonMark with pipe tables); images are embedded as
    base64, their paths relative to ``base_dir``; a missing image raises ``FileNotFoundError``."""
    parser = MarkdownIt("commonmark").enable("table")
    parser.add_render_rule("image", _image_renderer(Path(base_dir)))
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(title)}</title><style>{CSS}</style></head><body>\n"
            + parser.render(markdown) + "</body></html>\n")
