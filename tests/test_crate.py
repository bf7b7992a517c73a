"""The Workflow Run RO-Crate of the results archive (hubbeam.reporting.crate), on small synthetic archives
(the crate of a real workflow run is checked in test_archive.py), and CITATION.cff."""

from __future__ import annotations

import json

import pytest
import xarray as xr
import yaml

import hubbeam
from hubbeam.reporting import crate
from hubbeam.reporting.crate import Member, crate_metadata, first_sentence
from hubbeam.results import provenance
from hubbeam.results.io import write_netcdf

CONFIG = "config/config.used.yaml"


def netcdf_bytes(tmp_path, title: str) -> bytes:
    path = write_netcdf(xr.Dataset({"x": ("n", [1.0, 2.0])}, attrs={"title": title}), tmp_path / "r.nc")
    return path.read_bytes()


@pytest.fixture
def members(tmp_path) -> list[Member]:
    return [
        Member("Snakefile", b'"""Reproduce the paper.\n\nMore text."""\n', 10.0),
        Member("workflow/scripts/draw.py", b'"""Snakemake shim: draw one figure from its case files."""\n', 10.0),
        Member("workflow/report/fig05.rst", b"**Fig. 5.** TLAM against FOAM for spin-ups to 2.8 and 3.5 "
                                            b"rad/s, transverse tip deflection. Drawn until divergence.\n", 10.0),
        Member(CONFIG, b"cases: {}\n", 300.0),
        Member("results/simulations/case.nc", netcdf_bytes(tmp_path, "hubbeam simulation case"), 100.0),
        Member("results/figures/fig05.png", b"png", 200.0),
        Member("results/tables/table2.md", b"| a |", 250.0),
        Member("results/validation/tip_mass_comparison.csv", b"a,b\n", 150.0),
    ]


def graph_of(members) -> dict:
    return {entity["@id"]: entity for entity in json.loads(crate_metadata(members, CONFIG))["@graph"]}


def test_each_file_is_described_by_what_it_is(members):
    graph = graph_of(members)
    descriptions = {m.name: graph[m.name]["description"] for m in members}
    assert descriptions.pop("Snakefile").startswith(
        f"Snakemake workflow of hubbeam {hubbeam.__version__} (git commit {provenance.git_commit()}): ")
    assert descriptions == {
        "workflow/scripts/draw.py": "Snakemake shim: draw one figure from its case files. (Python)",
        "workflow/report/fig05.rst": "Caption of fig05 in the Snakemake report",
        CONFIG: "The configuration the workflow ran with (YAML)",
        "results/simulations/case.nc": "hubbeam simulation case (netCDF)",
        "results/figures/fig05.png": "Fig. 5: TLAM against FOAM (PNG)",
        "results/tables/table2.md": "Table 2: vibration frequencies (Markdown)",
        "results/validation/tip_mass_comparison.csv": "Tip mass comparison (CSV)",
    }
    assert graph["results/figures/fig05.png"]["encodingFormat"] == "image/png"
    assert graph["results/simulations/case.nc"]["encodingFormat"] == "application/x-netcdf"
    assert graph["results/tables/table2.md"]["sha256"] == crate.sha256(b"| a |")
    assert graph["results/tables/table2.md"]["contentSize"] == "5"


def test_the_run_spans_the_results_and_uses_the_config(members):
    graph = graph_of(members)
    run = graph["#run"]
    assert run["@type"] == "CreateAction" and run["instrument"] == {"@id": "Snakefile"}
    assert run["object"] == {"@id": CONFIG}
    assert sorted(item["@id"] for item in run["result"]) == sorted(m.name for m in members
                                                                   if m.name.startswith("results/"))
    # the oldest and newest result, not the configuration (written with the archive)
    assert (run["startTime"], run["endTime"]) == ("1970-01-01T00:01:40+00:00", "1970-01-01T00:04:10+00:00")
    workflow = graph["Snakefile"]
    assert workflow["version"] == hubbeam.__version__
    assert sorted(item["@id"] for item in workflow["hasPart"]) == ["workflow/report/fig05.rst",
                                                                    "workflow/scripts/draw.py"]


def test_the_crate_context_defines_sha256(members):
    context = json.loads(crate_metadata(members, CONFIG))["@context"]
    assert context == ["https://w3id.org/ro/crate/1.1/context", {"sha256": "http://schema.org/sha256"}]


def test_an_unknown_file_type_is_named(members):
    with pytest.raises(ValueError, match=r"'results/data.bin' has suffix '.bin'.*'.nc'"):
        crate_metadata([*members, Member("results/data.bin", b"", 1.0)], CONFIG)


@pytest.mark.parametrize("absent", ["Snakefile", CONFIG])
def test_an_archive_without_workflow_or_config_is_refused(members, absent):
    with pytest.raises(ValueError, match=f"missing: {absent}"):
        crate_metadata([m for m in members if m.name != absent], CONFIG)


def test_first_sentence():
    assert first_sentence("**Fig. 5.** A caption that is long enough to be a sentence, "
                          "really. Next one.\n\nSecond paragraph.") == (
        "Fig. 5. A caption that is long enough to be a sentence, really.")
    assert first_sentence("Short. Text without a later\nsentence end") == "Short. Text without a later sentence end"


def test_citation_file_names_the_package_version_and_the_paper(repo_root):
    citation = yaml.safe_load((repo_root / "CITATION.cff").read_text())
    assert citation["cff-version"] == "1.2.0" and citation["version"] == hubbeam.__version__
    assert citation["authors"] == [{"name": "hubbeam developers"}]
    (paper,) = citation["references"]
    assert [author["family-names"] for author in paper["authors"]] == ["Bai", "Ben-Tzvi", "Zhou", "Huang"]
    assert paper["title"] == "A Study on Dynamic Stiffening of a Rotating Beam with a Tip Mass"
    assert (paper["year"], paper["start"], paper["end"]) == (2009, 53, 68)
