"""hubbeam: reproduce Bai et al. (2009), dynamic stiffening of a rotating beam with a tip mass.

`snakemake` builds everything (cores come from profiles/default), `snakemake -n` shows the plan,
`snakemake results/simulations/<case>.nc` one case. See README.md.

The paper is the default study (config/config.yaml, products directly under results/).
`snakemake --configfile studies/<name>.yaml` runs a study instead (docs/studies.md): a config with
a `study` section replaces config/config.yaml entirely (Snakemake would otherwise merge the two),
and its products go to results/<name>/ only. Every configuration runs the same rules; what it
builds is what its products ask for (hubbeam.reporting.products.products_for) and where is hubbeam.results.paths.
"""

import sys
from pathlib import Path

from snakemake.utils import min_version

from hubbeam.configuration.load import ConfigError, validate_config
from hubbeam.configuration.settings import from_config
from hubbeam.control.cases import check_cases
from hubbeam.configuration.schema import CASE_NAME_PATTERN
from hubbeam.results.paths import study_paths
from hubbeam.reporting.products import ProductError, check_product_cases, products_for
from hubbeam.study import StudyError, base_config_files, claim_folder
from hubbeam.configuration.tabular import resolve_files

min_version("9.0")


# config/config.yaml, unless the config files given (--configfile) stand alone (a study's)
for base_config_file in base_config_files(config):

    configfile: base_config_file


# Tables given as `file:` (beam sections, maneuver profiles) are read relative to the last config
# file and inlined; then the schema (hubbeam/configuration/schemas/config.schema.yaml) and the physical checks,
# every problem in one message; then the objects every job takes (`SETTINGS`) and the checks that need
# the cases' matrices (designs, sampled controllers, shapers): a bad config stops here, before any rule, without a traceback.
try:
    config.update(resolve_files(config, Path(workflow.configfiles[-1]).parent))
    validate_config(config, files=workflow.configfiles)
    SETTINGS = from_config(config)
    check_cases(SETTINGS, workflow.configfiles)
    claim_folder(study_paths(config), workflow.configfiles[-1])
    check_product_cases(products_for(config), config["cases"])
except (ConfigError, ProductError, StudyError) as error:
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
        all_targets(),
