"""hubbeam: reproduce Bai et al. (2009), dynamic stiffening of a rotating beam with a tip mass.

`snakemake` builds everything (cores come from profiles/default), `snakemake -n` shows the plan,
`snakemake results/simulations/<case>.nc` one case. See README.md.
"""

import sys
from pathlib import Path

from snakemake.utils import min_version

from hubbeam.config import CASE_NAME_PATTERN, ConfigError, validate_config
from hubbeam.products import PAPER_PRODUCTS, ProductError, check_product_cases

min_version("9.0")


configfile: "config/config.yaml"


# Schema (workflow/schemas/config.schema.yaml) and physical checks of the merged config, every
# problem in one message; a bad config stops here, before any rule, without a traceback.
try:
    validate_config(config, files=workflow.configfiles)
    check_product_cases(PAPER_PRODUCTS, config["cases"])
except (ConfigError, ProductError) as error:
    sys.exit(str(error))


wildcard_constraints:
    case=CASE_NAME_PATTERN,


include: "workflow/rules/common.smk"


# Every rule file, after common.smk in alphabetical order: what a file uses at parse time must be
# defined in common.smk or in a file sorted before it.
RULE_FILES = sorted(Path(workflow.basedir, "workflow", "rules").glob("*.smk"))
for rule_file in RULE_FILES:
    if rule_file.name != "common.smk":

        include: rule_file


rule all:
    default_target: True
    localrule: True
    input:
        final_targets(),
