# SPDX-License-Identifier: Apache-2.0
"""Every example of examples/python runs at its small size and gets its physics right."""
import importlib
import sys

import numpy as np
import pytest

from conftest import SOURCE

sys.path.insert(0, str(SOURCE / "examples" / "python"))


def run(name, tmp_path):
    return importlib.import_module(name).main(["--small", "--out", str(tmp_path)])


def test_thin_film_sweep_matches_airy(tmp_path):
    r = run("thin_film_sweep", tmp_path)
    # The GR's angular average moves a 0–600 nm film's R by < 1e-4 (theory D15); Airy's R spans 0.004–0.06.
    assert r["max_error"] < 1e-4
    assert np.ptp(r["airy"]) > 0.03
    assert (tmp_path / "thin_film_sweep.png").exists()


def test_double_slit_contrast_matches_its_closed_form(tmp_path):
    r = run("double_slit_contrast", tmp_path)
    # grt's Monte-Carlo noise at 256 spp is about 2e-3 in C; C itself falls from 0.56 to 0.03.
    assert r["max_error"] < 6e-3
    assert r["closed_form"][0] > 0.5 and r["closed_form"][-1] < 0.05
    assert (tmp_path / "double_slit_contrast.png").exists()


def test_sheen_kernel_passes_the_contract_suite_and_renders(tmp_path):
    r = run("sheen_kernel", tmp_path)
    assert r["report"].passed and len(r["report"].cases) == 14
    # The sheen sphere (left) reflects more than the plain Lambertian one (right) of the same ρ.
    assert r["left"] > r["right"] > 0
    assert (tmp_path / "sheen_kernel.png").read_bytes()[:4] == b"\x89PNG"


def test_compare_integrators(tmp_path):
    r = run("compare_integrators", tmp_path)
    rows = {row["integrator"]: row for row in r["comparison"].table if row["role"] == "compared"}
    assert set(rows) == {"grt", "ray"}
    for row in rows.values():
        assert row["status"] == "ok" and 0 < row["rel_mse"] < 1
    assert (tmp_path / "compare_integrators.png").exists()
