"""Snakemake shim: the reproduction report (Markdown and self-contained HTML).

The published-table validation and the claims under alternative readings are read when the rule
has those inputs (the config has a `validation` or `readings` section, see
`published_validation_inputs` and `reading_inputs` in common.smk).
"""

from pathlib import Path

from hubbeam.paper.claims import read_claims
from hubbeam.paper.explain import section
from hubbeam.paper.readings import read_rows
from hubbeam.paper.report import reproduction_markdown
from hubbeam.reporting.document import markdown_to_html
from hubbeam.results.io import open_result, write_text
from hubbeam.validation.report import published_section

out = Path(snakemake.output.markdown)
figures = {Path(path).stem: path for path in snakemake.input.figures}
tables = {Path(path).stem: path for path in snakemake.input.tables}
files = zip(snakemake.params.cases, snakemake.input.datasets)
datasets = {case: open_result(path) for case, path in files}
validation = None
if "published" in snakemake.input.keys():
    validation = published_section(snakemake.input.published, snakemake.input.tip_mass,
                                   snakemake.input.curves, snakemake.input.published_figure,
                                   out.parent)
claims = read_claims(snakemake.input.claims)
readings = None
if "readings" in snakemake.input.keys():
    readings = section(claims, read_rows(snakemake.input.readings), snakemake.params.readings)
text = reproduction_markdown(claims, figures, tables, datasets, snakemake.params.numerics, out.parent,
                             validation=validation, readings=readings)
write_text(out, text)
write_text(snakemake.output.html, markdown_to_html(text, out.parent))
with open(snakemake.log[0], "w") as log:
    print(f"{out}: {len(figures)} figures, {len(tables)} tables, {len(datasets)} runs, "
          f"validation: {validation.summary if validation else 'not configured'}", file=log)
