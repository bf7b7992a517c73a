"""Documents of hubbeam: Markdown assembled from the Jinja2 templates of ``hubbeam/templates``
and rendered to self-contained HTML (images embedded) by markdown-it-py.

The prose of the reports lives in the templates; the modules that write a report compute its
numbers and tables and hand them to :func:`render`.
"""

from __future__ import annotations

import base64
import html
import math
from functools import cache
from pathlib import Path

import jinja2
from markdown_it import MarkdownIt

#: the templates :func:`render` reads (package data: the rules that render them depend on them)
PACKAGE_DATA = ("templates/*.j2",)
CSS = ("body{font-family:sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;line-height:1.45}"
       "table{border-collapse:collapse;margin:1rem 0;font-size:.9rem}"
       "th,td{border:1px solid #ccc;padding:.25rem .5rem;vertical-align:top}th{background:#f2f2f2}"
       "img{max-width:100%;display:block}.caption{display:block;font-size:.9rem;color:#444}"
       "code{background:#f5f5f5;padding:0 .2rem}")


def number(value, digits: int = 4) -> str:
    """A table cell (the templates' ``number`` filter): ``-`` for NaN, ``yes``/``no`` for flags,
    ``digits`` significant figures for other floats."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return "-" if math.isnan(value) else f"{value:.{digits}g}"
    return str(value)


@cache
def _environment() -> jinja2.Environment:
    environment = jinja2.Environment(loader=jinja2.PackageLoader("hubbeam", "templates"),
                                     undefined=jinja2.StrictUndefined, trim_blocks=True,
                                     lstrip_blocks=True, keep_trailing_newline=True, autoescape=False)
    environment.filters["number"] = number
    return environment


def render(template: str, **context) -> str:
    """The template ``hubbeam/templates/<template>`` rendered with ``context``."""
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
