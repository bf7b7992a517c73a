"""The results archive's machine-readable description: a Workflow Run RO-Crate.

:func:`crate_metadata` returns the ``ro-crate-metadata.json`` document (RO-Crate 1.1, built with
the ``rocrate`` library) that the archive carries at its root. It conforms to the Workflow Run
Crate profile 0.5 (with Process Run Crate 0.5 and Workflow RO-Crate 1.0) and describes:

- the workflow: ``Snakefile`` (the main entity, a Snakemake ``ComputationalWorkflow`` of the
  package version and git commit) with every file under ``workflow/`` (rules, scripts, report
  captions) as its parts;
- the software it ran with (``SoftwareApplication`` entities with ``softwareVersion``: Python,
  hubbeam and :data:`hubbeam.results.provenance.WORKFLOW_DISTRIBUTIONS`);
- the run, one ``CreateAction``: the workflow as ``instrument``, the configuration it ran with as
  ``object``, every result file as ``result``, ``startTime`` and ``endTime``;
- every file with ``encodingFormat`` (media type), ``sha256``, ``contentSize`` and a one-line
  ``description``: a netCDF file's ``title`` attribute, a product's title in the registry
  (``hubbeam.reporting.products``), else the first sentence of its caption file ``workflow/report/<key>.rst``,
  a workflow file's docstring.

The run's times are those of its products: ``startTime`` is the modification time of the oldest
result file, ``endTime`` that of the newest. Snakemake does not tell a job when the workflow
started, so the first product's time stands for the start; after a partial rerun the span runs
from the oldest kept product to the newest rebuilt one.
"""

from __future__ import annotations

import hashlib
import json
import platform
import re
from collections.abc import Iterable, Mapping
from pathlib import PurePosixPath
from typing import NamedTuple

import netCDF4
from rocrate.model.contextentity import ContextEntity
from rocrate.rocrate import ROCrate

from hubbeam import __version__
from hubbeam.reporting.products import PAPER_PRODUCTS
from hubbeam.results.provenance import WORKFLOW_DISTRIBUTIONS, git_commit, iso_utc, timestamp, versions

METADATA_NAME = "ro-crate-metadata.json"
RO_CRATE_VERSION = "1.1"  # the RO-Crate version Workflow Run Crate 0.5 is a profile of
MAIN_WORKFLOW = "Snakefile"
WORKFLOW_DIR = "workflow/"
#: The profiles the crate conforms to (id -> name, version).
PROFILES = {
    "https://w3id.org/ro/wfrun/process/0.5": ("Process Run Crate", "0.5"),
    "https://w3id.org/ro/wfrun/workflow/0.5": ("Workflow Run Crate", "0.5"),
    "https://w3id.org/workflowhub/workflow-ro-crate/1.0": ("Workflow RO-Crate", "1.0"),
}
#: ``sha256`` is not in the RO-Crate 1.1 context; later RO-Crate contexts map it to this IRI.
EXTRA_TERMS = {"sha256": "http://schema.org/sha256"}
DEVELOPERS = {"@id": "#hubbeam-developers", "@type": "Organization", "name": "hubbeam developers"}
#: The project has not chosen a licence; Workflow RO-Crate requires the property, so it says so.
LICENSE = {"@id": "#no-licence", "@type": "CreativeWork", "name": "No licence chosen",
           "description": "The hubbeam project has not chosen a licence; no rights are granted "
                          "beyond those of copyright law."}


class Format(NamedTuple):
    media_type: str
    name: str


#: File name suffix -> format (``Snakefile`` has none).
FORMATS = {
    ".nc": Format("application/x-netcdf", "netCDF"),
    ".pdf": Format("application/pdf", "PDF"),
    ".png": Format("image/png", "PNG"),
    ".csv": Format("text/csv", "CSV"),
    ".md": Format("text/markdown", "Markdown"),
    ".tex": Format("application/x-tex", "LaTeX"),
    ".mat": Format("application/x-matlab-data", "MATLAB MAT-file (version 5)"),
    ".html": Format("text/html", "HTML"),
    ".yaml": Format("application/yaml", "YAML"),
    ".py": Format("text/x-python", "Python"),
    ".smk": Format("text/plain", "Snakemake rules"),
    ".rst": Format("text/x-rst", "reStructuredText"),
    ".json": Format("application/json", "JSON"),
    "": Format("text/plain", "Snakemake workflow"),
}


class Member(NamedTuple):
    """A file of the archive: its path inside the archive, content and modification time."""
    name: str
    data: bytes
    mtime: float


def sha256(data: bytes) -> str:
    """SHA-256 hex digest (of the manifest's lines and the crate's ``sha256``)."""
    return hashlib.sha256(data).hexdigest()


def file_format(name: str) -> Format:
    """The format of the file ``name`` by its suffix; ValueError naming it if unknown."""
    suffix = PurePosixPath(name).suffix
    if suffix not in FORMATS:
        raise ValueError(f"archive file {name!r} has suffix {suffix!r}; the crate describes "
                         f"{', '.join(repr(s) for s in FORMATS)}")
    return FORMATS[suffix]


def crate_metadata(members: Iterable[Member], config_name: str) -> str:
    """``ro-crate-metadata.json`` of an archive of ``members`` (its text, JSON).

    ``members`` are the workflow (``Snakefile``, ``workflow/...``), the configuration
    ``config_name`` and the results (everything else). ValueError if the workflow, the
    configuration or any result is missing, or a file has a suffix not in :data:`FORMATS`.
    """
    members = sorted(members)
    by_name = {member.name: member for member in members}
    results = [m for m in members if not _is_workflow(m.name) and m.name != config_name]
    missing = [name for name in (MAIN_WORKFLOW, config_name) if name not in by_name]
    if missing or not results:
        raise ValueError(f"an archive's crate needs {MAIN_WORKFLOW}, {config_name} and results; "
                         f"missing: {', '.join(missing) or 'results'}")
    crate = ROCrate(version=RO_CRATE_VERSION)
    crate.metadata.extra_terms.update(EXTRA_TERMS)
    entities = {m.name: crate.add_file(None, m.name, properties=_file_properties(m, by_name, config_name))
                for m in members if m.name != MAIN_WORKFLOW}
    commit = git_commit()
    software = _software(crate, commit)
    workflow = crate.add_workflow(None, MAIN_WORKFLOW, main=True, lang="snakemake", properties={
        **_file_properties(by_name[MAIN_WORKFLOW], by_name, config_name),
        "name": "hubbeam workflow",
        "version": __version__,
        "description": f"Snakemake workflow of hubbeam {__version__} (git commit {commit}): "
                       "eigen-analysis, simulations, figures, tables and report of the "
                       "reproduction of Bai et al. (2009).",
        "hasPart": [entities[m.name] for m in members if _is_workflow(m.name) and m.name != MAIN_WORKFLOW],
        "softwareRequirements": software,
    })
    run = crate.add_action(workflow, identifier="#run", object=entities[config_name],
                           result=[entities[m.name] for m in results], properties={
                               "name": f"Run of the hubbeam {__version__} workflow",
                               "description": "The workflow run that produced the results, with "
                                              "the configuration it ran with; its times are "
                                              "those of the first and the last result written.",
                               "startTime": iso_utc(min(m.mtime for m in results)),
                               "endTime": iso_utc(max(m.mtime for m in results)),
                           })
    developers = crate.add(ContextEntity(crate, DEVELOPERS["@id"], properties=DEVELOPERS))
    root = crate.root_dataset
    root["mentions"] = run
    root["author"] = root["publisher"] = developers
    root["name"] = "hubbeam results"
    root["description"] = ("Results of hubbeam's reproduction of Bai, Ben-Tzvi, Zhou and Huang "
                           "(2009), A Study on Dynamic Stiffening of a Rotating Beam with a Tip "
                           "Mass: netCDF results, figures, tables and report, with the workflow "
                           "and the configuration that produced them.")
    root["datePublished"] = timestamp()
    root["license"] = crate.add(ContextEntity(crate, LICENSE["@id"], properties=LICENSE))
    for identifier, (name, version) in PROFILES.items():
        profile = crate.get(identifier) or crate.add(ContextEntity(
            crate, identifier, properties={"@type": "CreativeWork", "name": name, "version": version}))
        root.append_to("conformsTo", profile)
    return json.dumps(crate.metadata.generate(), indent=2, ensure_ascii=False) + "\n"


def _is_workflow(name: str) -> bool:
    return name == MAIN_WORKFLOW or name.startswith(WORKFLOW_DIR)


def _software(crate: ROCrate, commit: str) -> list:
    """SoftwareApplication entities: Python, hubbeam and every recorded distribution, named by
    their release pages (hubbeam, unpublished, by a local identifier)."""
    python = platform.python_version()
    applications = [(f"https://www.python.org/downloads/release/python-{python.replace('.', '')}/",
                     "Python", python, {}),
                    ("#software-hubbeam", "hubbeam", __version__, {"description": f"git commit {commit}"})]
    applications += [(f"https://pypi.org/project/{name}/{version}/", name, version, {})
                     for name, version in versions(WORKFLOW_DISTRIBUTIONS).items()]
    return [crate.add(ContextEntity(crate, identifier, properties={
        "@type": "SoftwareApplication", "name": name, "softwareVersion": version,
        **({"url": identifier} if identifier.startswith("https://") else {}), **extra}))
        for identifier, name, version, extra in applications]


def _file_properties(member: Member, by_name: Mapping[str, Member], config_name: str) -> dict:
    kind = file_format(member.name)
    return {"name": PurePosixPath(member.name).name, "encodingFormat": kind.media_type,
            "sha256": sha256(member.data), "contentSize": str(len(member.data)),
            "description": describe(member, by_name, config_name)}


def describe(member: Member, by_name: Mapping[str, Member], config_name: str) -> str:
    """One line saying what the file ``member`` is (see the module docstring)."""
    path = PurePosixPath(member.name)
    kind = file_format(member.name).name
    if member.name == config_name:
        return f"The configuration the workflow ran with ({kind})"
    if path.suffix == ".nc":
        with netCDF4.Dataset(path.name, memory=member.data) as nc:
            title = getattr(nc, "title", "")
        return f"{title} (netCDF)" if title else f"{path.stem} (netCDF, no title)"
    if _is_workflow(member.name):
        if path.suffix == ".rst":
            return f"Caption of {path.stem} in the Snakemake report"
        docstring = _docstring(member.data.decode())
        return f"{first_sentence(docstring)} ({kind})" if docstring else f"Workflow file {path} ({kind})"
    product = PAPER_PRODUCTS.get(path.stem)
    if product is not None:
        return f"{product.title} ({kind})"
    caption = by_name.get(f"{WORKFLOW_DIR}report/{_caption_key(path)}.rst")
    if caption is not None:
        return f"{first_sentence(caption.data.decode())} ({kind})"
    return f"{path.stem.replace('_', ' ').capitalize()} ({kind})"


def _caption_key(path: PurePosixPath) -> str:
    """The caption file of a product: the sweep maps share one, every other has its own."""
    return "sweep" if path.stem.startswith("sweep_") else path.stem


def _docstring(text: str) -> str:
    """The module docstring of a Python or Snakemake file ('' if it has none)."""
    found = re.match(r'\s*(?:#[^\n]*\n\s*)*[rRuU]?"""(.*?)"""', text, re.DOTALL)
    return found[1] if found else ""


def first_sentence(text: str, at_least: int = 60) -> str:
    """The first paragraph of ``text`` on one line, without reStructuredText emphasis, up to the
    first sentence end at least ``at_least`` characters in (so that "Fig. 5." is not one)."""
    paragraph = " ".join(text.strip().split("\n\n")[0].split())
    paragraph = paragraph.replace("**", "").replace("``", "")
    for end in re.finditer(r"[.!?](?=\s+[A-Z])", paragraph):
        if end.end() >= at_least:
            return paragraph[:end.end()]
    return paragraph
