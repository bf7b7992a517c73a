"""Snakemake shim: the report of `snakemake validate`, Markdown and HTML."""

from pathlib import Path

from hubbeam.reporting.document import markdown_to_html
from hubbeam.results.io import write_text
from hubbeam.validation.report import validation_markdown

inputs = dict(snakemake.input.items())
out = Path(snakemake.output.markdown)
exudyn = ({key: inputs[key] for key in ("comparison", "mode_study", "convergence", "figure")}
          if "comparison" in inputs else None)
text = validation_markdown(out.parent, inputs["ritz_fe"], inputs.get("pybmodes"), exudyn)
write_text(out, text)
write_text(snakemake.output.html,
           markdown_to_html(text, out.parent, title="hubbeam validation against independent models"))
with open(snakemake.log[0], "w") as log:
    print(f"{out}: written from {', '.join(inputs[key] for key in inputs if key != 'code')}", file=log)
