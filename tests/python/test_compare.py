# SPDX-License-Identifier: Apache-2.0
"""phasor.compare: `phasor compare` from Python."""
import csv
import subprocess
import sys
import types

import numpy as np
import pytest

import phasor
from conftest import VALIDATION

DOUBLE_SLIT = VALIDATION / "double_slit.wscene"


def test_compare_matches_the_program(tmp_path, phasor_bin):
    # rs is deterministic, so the reference (rs) and grt's errors against it are equal to the program's.
    c = phasor.compare(DOUBLE_SLIT, ["grt", "rs"], spp=4, seed=2, progress=False, output=tmp_path / "py")
    subprocess.run([phasor_bin, "compare", str(DOUBLE_SLIT), "--integrators", "grt,rs", "--spp", "4", "--seed", "2",
                    "-o", str(tmp_path / "cli"), "--quiet"], check=True)
    with open(tmp_path / "cli" / "results.csv") as f:
        cli = {row["integrator"]: row for row in csv.DictReader(f)}
    assert c.reference["name"] == "rs"
    rows = {row["integrator"]: row for row in c.table}
    assert rows["rs"]["role"] == "reference" and rows["grt"]["role"] == "compared"
    for key in ("rmse", "rel_mse", "max_error", "chi2", "z"):
        assert rows["grt"][key] == pytest.approx(float(cli["grt"][key]), rel=1e-8)
    assert rows["grt"]["verdict"] == cli["grt"]["verdict"] and rows["grt"]["comparable"] is True
    assert rows["grt"]["spp"] == 4 and rows["grt"]["status"] == "ok"
    assert set(c.images) == {"grt", "rs"}
    cli_grt = phasor.read_image(tmp_path / "cli" / "grt.exr")
    assert np.array_equal(c.images["grt"].array, cli_grt.array)
    for name in ("index.html", "results.csv", "results.json", "grid.png", "grt.exr"):
        assert (tmp_path / "py" / name).exists()
    assert c.convergence and all(p["integrator"] == "grt" for p in c.convergence)


def test_compare_equal_time_and_failures():
    c = phasor.compare(DOUBLE_SLIT, ["grt", "ray"], time="0.3s", reference="none", progress=False)
    rows = {row["integrator"]: row for row in c.table}
    assert c.mode.startswith("equal time") and set(rows) == {"grt", "ray"} and c.reference["name"] == ""
    for row in rows.values():
        assert row["status"] == "ok" and row["seconds"] >= 0.3 and row["rmse"] is None
    with pytest.raises(ValueError, match="unknown integrator 'gtr'.*did you mean 'grt'"):
        phasor.compare(DOUBLE_SLIT, ["gtr"])
    with pytest.raises(ValueError, match="not both"):
        phasor.compare(DOUBLE_SLIT, ["grt"], spp=2, time=1)
    with pytest.raises(ValueError, match="unknown sampler 'sobl'; did you mean 'sobol'"):
        phasor.compare(DOUBLE_SLIT, ["grt"], sampler="sobl")
    # An integrator that cannot render the scene is a failed row; the others run.
    scene = phasor.load(DOUBLE_SLIT, defines={"source": "disc"})
    c = phasor.compare(scene, ["grt", "rs"], spp=2, progress=False)
    rows = {row["integrator"]: row for row in c.table}
    assert rows["rs"]["status"] == "failed" and "coherent field" in rows["rs"]["error"]
    assert rows["grt"]["status"] == "ok" and "rs" not in c.images
    # The reference is then grt again, from independent seeds (as `phasor compare` chooses it).
    assert rows["grt (reference)"]["role"] == "reference" and "grt (reference)" in c.images
    assert rows["grt"]["z"] is not None


def test_dataframe(monkeypatch):
    c = phasor.compare(DOUBLE_SLIT, ["grt", "rs"], spp=1, progress=False)
    fake = types.ModuleType("pandas")
    fake.DataFrame = lambda rows: ("frame", rows)
    monkeypatch.setitem(sys.modules, "pandas", fake)
    assert c.dataframe() == ("frame", c.table)
    monkeypatch.setitem(sys.modules, "pandas", None)  # not importable
    with pytest.raises(ImportError, match="python3-pandas"):
        c.dataframe()
