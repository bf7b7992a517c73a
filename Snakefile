"""hubbeam: reproduce Bai et al. (2009), dynamic stiffening of a rotating beam with a tip mass.

`snakemake` builds everything (cores come from profiles/default), `snakemake -n` shows the plan,
`snakemake results/simulations/<case>.nc` one case. See README.md.

`snakemake --configfile studies/<name>.yaml` runs a study instead (docs/studies.md): a config with
a `study` section replaces the paper's config/config.yaml entirely (Snakemake would otherwise merge
the two), and its products go to results/<name>/ only.
"""

import sys
from pathlib import Path

from snakemake.utils import min_version

from hubbeam.config import ConfigError, validate_config
from hubbeam.config_schema import CASE_NAME_PATTERN
from hubbeam.products import PAPER_PRODUCTS, ProductError, check_product_cases
from hubbeam.study import StudyError, claim_results_dir, is_study, results_dir
from hubbeam.tabular import resolve_files

min_version("9.0")


# The paper is the default study; a config file with a `study` section (given with --configfile)
# stands alone and inherits nothing from it.
if not is_study(config):

    configfile: "config/config.yaml"


STUDY = is_study(config)
# Tables given as `file:` (beam sections, maneuver profiles) are read relative to the last config
# file and inlined; then the schema (hubbeam/schemas/config.schema.yaml) and the physical checks,
# every problem in one message: a bad config stops here, before any rule, without a traceback.
try:
    config.update(resolve_files(config, Path(workflow.configfiles[-1]).parent))
    validate_config(config, files=workflow.configfiles)
    if STUDY:
        claim_results_dir(results_dir(config), workflow.configfiles[-1])
    else:
        check_product_cases(PAPER_PRODUCTS, config["cases"])
except (ConfigError, ProductError, StudyError) as error:
    sys.exit(str(error))


wildcard_constraints:
    case=CASE_NAME_PATTERN,


include: "workflow/rules/common.smk"


# Every rule file, after common.smk in alphabetical order: what a file uses at parse time must be
# defined in common.smk or in a file sorted before it. A study has the generic rules (matrices,
# simulations, the optional `validate` target) and its own (study.smk); the paper every other file.
GENERIC_RULE_FILES = ("matrices.smk", "simulate.smk", "validate.smk")
RULE_FILES = sorted(Path(workflow.basedir, "workflow", "rules").glob("*.smk"))
for rule_file in RULE_FILES:
    wanted = rule_file.name in GENERIC_RULE_FILES or (rule_file.name == "study.smk") == STUDY
    if rule_file.name != "common.smk" and wanted:

        include: rule_file


rule all:
    default_target: True
    localrule: True
    input:
        study_targets() if STUDY else final_targets(),
