"""hubbeam: reproduce Bai et al. (2009), dynamic stiffening of a rotating beam with a tip mass.

`snakemake` builds everything (cores come from profiles/default), `snakemake -n` shows the plan,
`snakemake results/simulations/<case>.nc` one case. See README.md.

The paper is the default study (config/config.yaml, products directly under results/).
`snakemake --configfile studies/<name>.yaml` runs a study instead (docs/studies.md): a config with
a `study` section replaces config/config.yaml entirely (Snakemake would otherwise merge the two),
and its products go to results/<name>/ only. What each configuration builds, with which inputs and
params, is its plan (hubbeam.pipeline.plan, docs/pipeline.md): one rule per step the families of
hubbeam.pipeline.families declare (workflow/rules/steps.smk), their target rules
(workflow/rules/targets.smk) and `all`.
"""

import sys
from pathlib import Path

from snakemake.utils import min_version

from hubbeam.configuration.schema import CASE_NAME_PATTERN
from hubbeam.pipeline.plan import PlanError, build_plan
from hubbeam.study import base_config_files

min_version("9.0")


# config/config.yaml, unless the config files given (--configfile) stand alone (a study's)
for base_config_file in base_config_files(config):

    configfile: base_config_file


# The configuration checked once, every problem in one message (the schema, the physical checks,
# the designs, sampled controllers and shapers, the readings, the products' cases, the study's
# folder), and turned into the plan every rule reads: a bad config stops here, before any rule,
# without a traceback.
try:
    PLAN = build_plan(config, workflow.configfiles, workflow.basedir)
except PlanError as error:
    sys.exit(str(error))


wildcard_constraints:
    case=CASE_NAME_PATTERN,
    comparison=CASE_NAME_PATTERN,


include: "workflow/rules/common.smk"


# Every rule file, after common.smk in alphabetical order.
RULE_FILES = sorted(Path(workflow.basedir, "workflow", "rules").glob("*.smk"))
for rule_file in RULE_FILES:
    if rule_file.name != "common.smk":

        include: rule_file


rule all:
    default_target: True
    localrule: True
    input:
        PLAN.targets,
