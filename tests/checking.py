"""The one check as the configuration tests read it: a list of problems instead of an exception."""

from __future__ import annotations

from hubbeam.check import check_configuration
from hubbeam.configuration.load import ConfigError


def checked_configuration(config, files):
    """:func:`hubbeam.check.check_configuration` as ``(completed configuration, settings or None,
    problems)``."""
    try:
        checked = check_configuration(config, files)
    except ConfigError as error:
        return getattr(error, "config", config), None, list(error.problems)
    return checked.config, checked.settings, []
