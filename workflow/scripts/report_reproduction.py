"""Snakemake shim: the reproduction report (Markdown and self-contained HTML)."""

from pathlib import Path

from hubbeam.io import open_result
from hubbeam.report import markdown_to_html, read_claims, reproduction_markdown

out = Path(snakemake.output.markdown)
figures = {Path(path).stem: path for path in snakemake.input.figures}
tables = {Path(path).stem: path for path in snakemake.input.tables}
files = zip(snakemake.params.cases, snakemake.input.datasets)
datasets = {case: open_result(path) for case, path in files}
text = reproduction_markdown(read_claims(snakemake.input.claims), figures, tables, datasets,
                             snakemake.params.numerics, out.parent)
out.write_text(text)
Path(snakemake.output.html).write_text(markdown_to_html(text, out.parent))
with open(snakemake.log[0], "w") as log:
    print(f"{out}: {len(figures)} figures, {len(tables)} tables, {len(datasets)} runs", file=log)
