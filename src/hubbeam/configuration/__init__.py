"""The configuration of a run or study: loading and validating it against the schema (package data
``schemas/``), the checks the schema cannot express, defaults, settings, tabulated inputs read from
files and the generated reference of every key."""
