#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""A diffraction kernel written in Python: a Lambertian reflector with a sheen, checked by the
generic kernel contract suite and rendered.

The kernel reflects f = (ρ/π)·(1 + s·h(cos θi)·h(cos θo)) with h(c) = (1 − c)²: a matte surface
whose reflection grows towards grazing incidence and exit (the soft rim of velvet or dust). It is
reciprocal (symmetric in θi, θo) and its albedo is ρ·(1 + s·h(cos θi)/6) ≤ ρ·(1 + s/6) — since
∫ h(cos θ) cos θ dω = π/6 — which the constructor keeps ≤ 1 (a scene asking for more is an error
at its Material). Sampling mixes two techniques in proportion to their energy: cosine-weighted
directions (density cos θ/π) and the sheen's own, density (6/π)(1 − cos θ)² cos θ, drawn by
inverting its CDF F(c) = 6c² − 8c³ + 3c⁴ in c = cos θ.

    python3 examples/python/sheen_kernel.py [--small] [--out DIR]
"""
import argparse
import math
import pathlib

import numpy as np

import phasor
import phasor.testing


def sheen_cos(u):
    """c in [0, 1] with F(c) = 6c² − 8c³ + 3c⁴ = u (bisection; F is increasing)."""
    lo, hi = 0.0, 1.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if mid * mid * (6 - 8 * mid + 3 * mid * mid) < u:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


class SheenLambert(phasor.Material):
    """A Lambertian reflector with a sheen towards grazing angles: f = (ρ/π)(1 + s·(1 − cos θi)²(1 − cos θo)²)."""

    parameters = {
        "reflectance": phasor.param("number", 0.5, min=0, max=1, doc="ρ, the Lambertian part's albedo"),
        "sheen": phasor.param("number", 1.0, min=0, doc="s, the sheen's strength; ρ(1 + s/6) must not exceed 1"),
    }
    presets = [{"reflectance": 0.5, "sheen": 1.0}, {"reflectance": 0.8, "sheen": 1.5}]

    def __init__(self, params):
        super().__init__(params)
        self.rho, self.s = params["reflectance"], params["sheen"]
        if self.rho * (1 + self.s / 6) > 1:
            raise ValueError(f"reflectance·(1 + sheen/6) = {self.rho * (1 + self.s / 6):.4g} > 1 "
                             f"would reflect more than arrives at grazing incidence; lower one of them")

    def _mix(self, ci):
        """The probability of the sheen technique: its share of the albedo."""
        e = self.s * (1 - ci) ** 2 / 6
        return e / (1 + e)

    def eval(self, wi, wo, wl):
        if wi[2] * wo[2] <= 0:
            return 0.0
        ci, co = abs(wi[2]), abs(wo[2])
        return self.rho / math.pi * (1 + self.s * (1 - ci) ** 2 * (1 - co) ** 2)

    def pdf(self, wi, wo, wl):
        if wi[2] * wo[2] <= 0:
            return 0.0
        q, c = self._mix(abs(wi[2])), abs(wo[2])
        return (1 - q) * c / math.pi + q * 6 / math.pi * (1 - c) ** 2 * c

    def sample(self, wi, wl, u0, u):
        if wi[2] == 0:
            return None
        if u0 < self._mix(abs(wi[2])):
            c = sheen_cos(u[0])
        else:
            c = math.sqrt(u[0])  # cosine-weighted: cos θ = √u
        if c <= 0:
            return None
        s = math.sqrt(max(0.0, 1 - c * c))
        phi = 2 * math.pi * u[1]
        wo = (s * math.cos(phi), s * math.sin(phi), c if wi[2] > 0 else -c)
        pdf = self.pdf(wi, wo, wl)
        return phasor.ScatterSample(wo, self.eval(wi, wo, wl) * c / pdf, pdf)


SCENE = """wscene 2
# A sheen sphere and a plain Lambertian one on a matte floor, under one ceiling panel.
Define res = 64
Material "sheen" "velvet" { reflectance = 0.6  sheen = 2.2 }
Material "diffuse" "matte" { reflectance = 0.6 }
Material "diffuse" "floor" { reflectance = 0.4 }
Shape "sphere" "left" { center = [-1.1 0 0] m  radius = 1 m  material = @velvet }
Shape "sphere" "right" { center = [1.1 0 0] m  radius = 1 m  material = @matte }
Shape "rectangle" "ground" { to_world = [scale(6), translate([0 0 -1] m)]  material = @floor }
Shape "rectangle" "panel" { to_world = [scale(2), rotate(180 deg, [1 0 0]), translate([0 0 4] m)] }
Light "area" { shape = @panel  radiance = 3 W/m^2/sr }
Detector "perspective" "cam" { to_world = lookat([0 -6 1.5] m, [0 0 0] m, [0 0 1])  fov = 35 deg  resolution = [$res $res] }
"""


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--small", action="store_true", help="a quick contract check and a tiny render (the test's size)")
    ap.add_argument("--out", default="out/examples", help="directory for the image")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    phasor.register_material("sheen", SheenLambert)
    quick = dict(wavelengths=["550nm"], sample_scale=0.05) if args.small else {}
    report = phasor.testing.check_kernel("sheen", **quick)  # raises KernelContractError if a check fails
    print(report)

    scene = phasor.load_string(SCENE, defines={"res": 24 if args.small else 160}, name="sheen.wscene")
    image = scene.render("grt", spp=16 if args.small else 256, progress=not args.small)
    image.write(out / "sheen_kernel.exr")
    image.write(out / "sheen_kernel.png")
    # The sheen sphere (left half) is brighter at its rim than the Lambertian one (right half).
    i = image["intensity"].astype(np.float64)
    return {"report": report, "image": image, "left": float(i[:, : i.shape[1] // 2].mean()),
            "right": float(i[:, i.shape[1] // 2:].mean())}


if __name__ == "__main__":
    main()
