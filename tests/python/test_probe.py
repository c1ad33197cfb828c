# SPDX-License-Identifier: Apache-2.0
"""phasor.probe: the program's kernel explorer from Python."""
import gc
import math
import subprocess

import pytest

import phasor
from conftest import SCENES

LIBRARY = SCENES / "probe.wscene"  # materials only: no light, no detector


def test_probe_equals_the_program(phasor_bin):
    for args in (["glass", "60deg", "633nm"], ["paint", "30deg", "550nm"], ["lines", "20deg", "500nm"]):
        cli = subprocess.run([phasor_bin, "probe", str(LIBRARY), "--material", args[0], "--theta", args[1],
                              "--lambda", args[2], "--csv", "-", "--samples", "2000", "--seed", "3"],
                             capture_output=True, text=True, check=True).stdout
        p = phasor.probe(LIBRARY, args[0], args[1], args[2], samples=2000, seed=3)
        assert p.csv == cli


def test_probe_against_fresnel_with_si_quantities():
    n = 1.5
    p = phasor.probe(LIBRARY, "glass", 0.0, 633e-9)
    r0 = ((n - 1) / (n + 1)) ** 2
    assert p.R == pytest.approx(r0, abs=1e-12) and p.T == pytest.approx(1 - r0, abs=1e-12)
    assert [l["kind"] for l in p.lobes] == ["reflection", "transmission"]
    assert p.lobes[1]["theta_o"] == pytest.approx(math.pi)
    assert not p.continuous and p.R_stderr == 0
    # A Lambertian reflector of albedo 0.37: R by Monte Carlo within 4 standard errors.
    lam = phasor.probe(LIBRARY, "matte", "20deg", "450nm", defines={"albedo": 0.37}, samples=20000)
    assert lam.continuous and abs(lam.R - 0.37) < 4 * lam.R_stderr + 1e-12 and lam.T == 0


def test_probe_errors():
    with pytest.raises(phasor.PhasorError, match="no material named 'glas'.*did you mean 'glass'"):
        phasor.probe(LIBRARY, "glas", "0deg", "550nm")
    with pytest.raises(phasor.PhasorError, match="footprint-aware"):
        phasor.probe(LIBRARY, "slit", "0deg", "550nm")
    with pytest.raises(ValueError, match="'lam' expects a length"):
        phasor.probe(LIBRARY, "glass", "0deg", "550")
    with pytest.raises(ValueError, match="grazing"):
        phasor.probe(LIBRARY, "glass", "90deg", "550nm")
    with pytest.raises(phasor.SceneError, match="ior"):
        phasor.probe(LIBRARY, "glass", "0deg", "550nm", defines={"n_glass": -1})


def test_probe_of_a_loaded_scene_keeps_it_alive(small_scene):
    p = phasor.probe(phasor.load(small_scene), "white", "10deg", "550nm", samples=4000)
    gc.collect()
    assert abs(p.R - 0.5) <= 4 * p.R_stderr + 1e-12  # (a Lambertian's weight is its albedo exactly)
    assert p.scene.render(spp=1, progress=False).width == 32


def test_probe_plot(tmp_path):
    phasor.probe(LIBRARY, "paint", "30deg", "550nm", samples=1000, plot=tmp_path / "paint.png")
    assert (tmp_path / "paint.png").read_bytes()[:4] == b"\x89PNG"
