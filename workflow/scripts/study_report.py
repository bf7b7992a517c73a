"""Snakemake shim: the study report (Markdown, HTML) and its summary.csv, a row per case."""

import csv
import os
from pathlib import Path

from hubbeam.results.io import open_result, staged, write_text
from hubbeam.study.report import study_html, study_markdown
from hubbeam.study.summary import COLUMNS, case_summary
from hubbeam.study.trust import design_table

p = snakemake.params
out = snakemake.output
report_dir = Path(out.markdown).parent
datasets = {case: open_result(path) for case, path in zip(p.cases, snakemake.input.simulations)}
rows = [case_summary(case, ds) for case, ds in datasets.items()]
relative = {name: os.path.relpath(path, report_dir) for name, path in p.figures.items()}
markdown = study_markdown(
    p.study, p.beam, rows,
    case_figures={case: relative[f"case_{case}"] for case in p.cases},
    comparison_figures={name: relative[f"compare_{name}"] for name in p.study.get("comparisons", {})},
    eigen_figures={name: path for name, path in relative.items() if not name.startswith(("case_", "compare_"))},
    designs=design_table(datasets),
)
write_text(out.markdown, markdown)
write_text(out.html, study_html(markdown, p.study.get("title", p.study["name"]), report_dir))
with staged(out.summary) as (summary,), open(summary, "w", newline="") as handle:
    writer = csv.DictWriter(handle, fieldnames=COLUMNS)
    writer.writeheader()
    writer.writerows(rows)
with open(snakemake.log[0], "w") as log:
    print(f"{len(rows)} cases -> {out.markdown}, {out.html}, {out.summary}", file=log)
