"""The results archive (SHA-256 manifest, atomic write) and the whole workflow on a tiny config."""

from __future__ import annotations

import importlib.util
import io
import shutil
import subprocess
import sys
import tarfile
from pathlib import Path

import pytest
import yaml

from synthetic_results import CONFIG_FILE, REPO, SCRIPTS

spec = importlib.util.spec_from_file_location("hubbeam_archive_script", SCRIPTS / "archive.py")
archive = importlib.util.module_from_spec(spec)
spec.loader.exec_module(archive)


@pytest.fixture
def files(tmp_path):
    names = ["results/simulations/a.nc", "results/figures/fig03.pdf", "results/tables/table1.csv"]
    for k, name in enumerate(names):
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(bytes([k]) * (100 + k))
    return tmp_path, names


def members(path):
    with tarfile.open(path, "r:gz") as tar:
        return {m.name: tar.extractfile(m).read() for m in tar.getmembers() if m.isfile()}


def test_archive_holds_files_config_and_a_manifest_that_verifies(files):
    root, names = files
    out = archive.build_archive(names, {"beam": {"length": 8.0}, "cases": {}}, root / "out.tar.gz", root=root)
    assert archive.verify_archive(out) == []
    contents = members(out)
    top = archive.TOP
    assert set(contents) == {f"{top}/{n}" for n in [*names, archive.CONFIG_NAME, archive.MANIFEST]}
    manifest = contents[f"{top}/{archive.MANIFEST}"].decode().splitlines()
    assert len(manifest) == len(names) + 1
    assert yaml.safe_load(contents[f"{top}/{archive.CONFIG_NAME}"]) == {"beam": {"length": 8.0}, "cases": {}}
    assert [p.name for p in root.iterdir() if p.name.endswith(".tmp")] == []


def test_manifest_is_checked_by_sha256sum(files, tmp_path_factory):
    if shutil.which("sha256sum") is None:
        pytest.skip("sha256sum not installed")
    root, names = files
    out = archive.build_archive(names, {}, root / "out.tar.gz", root=root)
    target = tmp_path_factory.mktemp("extract")
    # extraction filters exist from Python 3.11.4 (and 3.12) on; the README allows any 3.11
    safe = {"filter": "data"} if hasattr(tarfile, "data_filter") else {}
    with tarfile.open(out, "r:gz") as tar:
        tar.extractall(target, **safe)
    check = subprocess.run(["sha256sum", "-c", archive.MANIFEST], cwd=target / archive.TOP,
                           capture_output=True, text=True)
    assert check.returncode == 0, check.stdout + check.stderr


def test_verification_finds_changed_missing_and_unlisted_files(files):
    root, names = files
    out = archive.build_archive(names, {}, root / "out.tar.gz", root=root)
    contents = members(out)
    top = archive.TOP
    contents[f"{top}/{names[0]}"] = b"tampered"
    del contents[f"{top}/{names[1]}"]
    contents[f"{top}/extra.txt"] = b"x"
    forged = root / "forged.tar.gz"
    with tarfile.open(forged, "w:gz") as tar:
        for name, data in contents.items():
            info = tarfile.TarInfo(name)
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
    problems = archive.verify_archive(forged)
    assert f"{names[0]}: SHA-256 does not match {archive.MANIFEST}" in problems
    assert f"{names[1]}: listed in {archive.MANIFEST} but missing" in problems
    assert f"extra.txt: not listed in {archive.MANIFEST}" in problems


def test_a_missing_input_leaves_no_archive_behind(files):
    root, names = files
    out = root / "out.tar.gz"
    with pytest.raises(FileNotFoundError, match="results/figures/fig99.pdf"):
        archive.build_archive([*names, "results/figures/fig99.pdf"], {}, out, root=root)
    assert not out.exists()
    assert [p.name for p in root.iterdir() if p.name.endswith(".tmp")] == []


# --- the whole workflow on a tiny configuration --------------------------------------------------

def tiny_config() -> dict:
    """config/config.yaml shrunk: at most 2 modes, 6 s runs with the maneuver over 4 s (short enough
    to be quick, long enough that the hub acceleration does not make the bounded runs diverge),
    coarse output and eigen grids, sweep maps of 3 x 3 points."""
    config = yaml.safe_load(CONFIG_FILE.read_text())
    # numerics.modes stays: it sets the eigen-analysis (Table 2 has five modes); every case below
    # states its own mode count
    config["numerics"] |= {"quadrature_points": 16, "rtol": 1e-6, "atol": 1e-8, "output_step": 0.05}
    config["eigen"] |= {"speeds": {"start": 0.0, "stop": 4.0, "num": 9},
                        "positions": {"start": 0.0, "stop": config["beam"]["length"], "num": 5}}
    for case in config["cases"].values():
        case["t_end"] = 6.0
        case["maneuver"]["tf"] = 4.0
        case["modes"] = min(case.get("modes", 2), 2)
    for sweep in config["sweeps"]["maps"].values():
        for axis in sweep["grid"].values():
            axis["num"] = 3
    return config


@pytest.mark.skipif(not (REPO / "workflow" / "rules" / "simulate.smk").is_file(),
                    reason="needs the simulation rules (workflow/rules/simulate.smk), not written yet")
def test_workflow_builds_every_product_on_a_tiny_config(tmp_path):
    config = tiny_config()
    (tmp_path / "config").mkdir()
    config_file = tmp_path / "config" / "config.yaml"
    config_file.write_text(yaml.safe_dump(config))
    snakemake = Path(sys.executable).with_name("snakemake")
    run = subprocess.run([str(snakemake), "--snakefile", str(REPO / "Snakefile"), "--directory", str(tmp_path),
                          "--configfile", str(config_file), "--cores", "2", "archive", "all"],
                         capture_output=True, text=True, timeout=1800)
    assert run.returncode == 0, run.stderr[-4000:]
    expected = [f"results/figures/{k}.{e}" for k in ("fig03", "fig04", "fig05", "fig06", "fig07", "fig08",
                                                      "fig09", "fig10", "campbell", "critical_map",
                                                      "convergence") for e in ("pdf", "png")]
    expected += [f"results/tables/table{i}.{e}" for i in (1, 2, 3) for e in ("csv", "md", "tex")]
    expected += [f"results/report/{name}" for name in ("claims.csv", "reproduction.md", "reproduction.html")]
    expected += [f"results/validation/{name}" for name in (  # the published-table validation is in `all`
        "published_comparison.csv", "tip_mass_comparison.csv", "rotating_eigen.nc",
        "rotating_frequencies.pdf", "rotating_frequencies.png")]
    expected += [f"results/simulations/{case}.nc" for case in config["cases"]]
    expected += [f"results/sweeps/{name}.nc" for name in config["sweeps"]["maps"]]
    expected += [f"results/figures/sweep_{name}.{e}" for name in config["sweeps"]["maps"]
                 for e in ("pdf", "png")]
    expected += ["results/hubbeam-results.tar.gz"]
    missing = [name for name in expected if not (tmp_path / name).is_file()]
    assert missing == []
    assert archive.verify_archive(tmp_path / "results" / "hubbeam-results.tar.gz") == []
    with tarfile.open(tmp_path / "results" / "hubbeam-results.tar.gz", "r:gz") as tar:
        bundled = set(tar.getnames())
    assert {f"{archive.TOP}/{name}" for name in expected[:-1]} <= bundled  # every product but itself
    report = (tmp_path / "results" / "report" / "reproduction.md").read_text()
    assert "## Validation" in report and "published rotating-cantilever first frequencies" in report
    assert not (tmp_path / "results" / "report" / "validation_exudyn.md").exists()  # `validate` only
    claims = (tmp_path / "results" / "report" / "claims.csv").read_text().splitlines()
    assert len(claims) > 40


def test_without_a_validation_section_the_plan_has_no_validation_and_the_report_says_so(tmp_path):
    config = yaml.safe_load(CONFIG_FILE.read_text())
    del config["validation"]
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "config.yaml").write_text(yaml.safe_dump(config))
    snakemake = Path(sys.executable).with_name("snakemake")
    run = subprocess.run([str(snakemake), "--snakefile", str(REPO / "Snakefile"), "--directory", str(tmp_path),
                          "--dry-run", "all"], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-4000:]
    plan = run.stdout + run.stderr
    assert "reproduction_report" in plan and "archive" in plan
    assert "validate_published" not in plan and "results/validation/" not in plan
