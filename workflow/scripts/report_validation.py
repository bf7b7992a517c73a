"""Snakemake shim: the report of the Exudyn comparison (`snakemake validate`), Markdown and HTML."""

from pathlib import Path

from hubbeam.document import markdown_to_html
from hubbeam.io import write_text
from hubbeam.validation.report import exudyn_markdown

out = Path(snakemake.output.markdown)
text = exudyn_markdown(snakemake.input.comparison, snakemake.input.mode_study,
                       snakemake.input.convergence, snakemake.input.figure, out.parent)
write_text(out, text)
write_text(snakemake.output.html,
           markdown_to_html(text, out.parent, title="hubbeam validation against Exudyn"))
with open(snakemake.log[0], "w") as log:
    print(f"{out}: written from {snakemake.input.comparison}", file=log)
