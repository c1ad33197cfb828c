#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Young's double slit: the fringe contrast C(d) against the slit spacing d, rendered and in closed form.

scenes/validation/double_slit.wscene (a plane wave through two slits of width b, a row of
Gaussian pixels of standard deviation σ at distance z) is swept over d with render_many; each d
is rendered with both slits (P) and with each alone (P1, P2), and the contrast of the interference
term over the row is

    C = √(Σ (P − P1 − P2)² / Σ P²).

Closed form: narrow slits (b²/λz ≪ 1) send cylindrical waves whose single-slit patterns are
I_j(x) ∝ sinc²(π b sinθ_j / λ)·cosθ_j / r_j, r_j the distance from slit j; they interfere as
P = I_1 + I_2 + 2√(I_1 I_2)·V·cos φ(x), φ = k(r_1 − r_2), and a Gaussian pixel averages the
fringes to the visibility V(x) = exp(−σ²φ′(x)²/2) with φ′ = k(sinθ_1 − sinθ_2) ≈ k d / z (theory
§6: the pixel's Gaussian response). With many fringes under the envelopes C ≈ V/√(2 + V²), so the
contrast falls from 1/√3 to 0 as d grows past λz/(πσ). Valid while σ is small against the
envelope (λz/b) and b²/λz ≪ 1 — here 8e-4. It agrees with the `rs` integrator's Rayleigh–Sommerfeld
integral to 1e-5 in C; grt agrees to about 2e-3 at 256 samples per pixel and 2e-4 at 1024 (its
Monte-Carlo noise).

    python3 examples/python/double_slit_contrast.py [--small] [--out DIR]
"""
import argparse
import math
import pathlib
import sys

import numpy as np

import phasor

SCENE = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "validation" / "double_slit.wscene"

# Lengths in metres: λ, plate-to-sensor distance, slit width, pixel σ, pitch, sensor width.
LAMBDA, Z, B, SIGMA, PITCH, WIDTH = 1e-6, 20e-3, 4e-6, 20e-6, 10e-6, 4e-3
DEFINES = {"lambda": LAMBDA, "z": Z, "b": B, "sigma_pix": SIGMA, "pitch": PITCH, "width": WIDTH, "length": 2e-3}


def closed_form_contrast(d):
    """C(d) of the closed form above, over the same pixel centres as the render."""
    n = int(round(WIDTH / PITCH))
    x = -WIDTH / 2 + (np.arange(n) + 0.5) * PITCH
    k = 2 * math.pi / LAMBDA
    terms = []
    for s in (-d / 2, d / 2):
        r = np.hypot(x - s, Z)
        sin_t = (x - s) / r
        terms.append((np.sinc(B * sin_t / LAMBDA) ** 2 * (Z / r) / r, r, sin_t))
    (i1, r1, s1), (i2, r2, s2) = terms
    visibility = np.exp(-0.5 * (SIGMA * k * (s1 - s2)) ** 2)
    cross = 2 * np.sqrt(i1 * i2) * visibility * np.cos(k * (r1 - r2))
    p = i1 + i2 + cross
    return math.sqrt(np.sum(cross ** 2) / np.sum(p ** 2))


def rendered_contrast(scene, d, spp):
    both, one, two = scene.render_many([{"d": d}, {"d": d, "slit2": False}, {"d": d, "slit1": False}],
                                       spp=spp, progress=False)
    p, p1, p2 = (img["intensity"][0].astype(np.float64) for img in (both, one, two))
    return math.sqrt(np.sum((p - p1 - p2) ** 2) / np.sum(p ** 2))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--small", action="store_true", help="five spacings at 256 spp (the test's size)")
    ap.add_argument("--out", default="out/examples", help="directory for the plot")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    spacings = np.array([50, 100, 200, 300, 400] if args.small else np.arange(25, 501, 25)) * 1e-6
    spp = 256 if args.small else 1024
    scene = phasor.load(SCENE, defines=DEFINES)
    rendered = np.array([rendered_contrast(scene, float(d), spp) for d in spacings])
    closed = np.array([closed_form_contrast(d) for d in spacings])
    worst = float(np.max(np.abs(rendered - closed)))
    for d, c, f in zip(spacings, rendered, closed):
        print(f"d = {d * 1e6:5.0f} um: C = {c:.4f} (grt, {spp} spp), closed form {f:.4f}")
    print(f"max |C_grt - C_closed| = {worst:.4f}")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot", file=sys.stderr)
    else:
        fig, ax = plt.subplots(figsize=(6, 3.5))
        fine = np.linspace(spacings[0], spacings[-1], 200)
        ax.plot(fine * 1e6, [closed_form_contrast(d) for d in fine], "k-", lw=1, label="closed form")
        ax.plot(spacings * 1e6, rendered, "o", ms=4, label=f"phasor (grt, {spp} spp)")
        ax.set_xlabel("slit spacing d [µm]")
        ax.set_ylabel("fringe contrast C")
        ax.set_title(f"λ = 1 µm, z = 20 mm, b = 4 µm, Gaussian pixels σ = 20 µm", fontsize=9)
        ax.legend()
        fig.tight_layout()
        fig.savefig(out / "double_slit_contrast.png", dpi=120)
        plt.close(fig)
    return {"d": spacings, "rendered": rendered, "closed_form": closed, "max_error": worst}


if __name__ == "__main__":
    main()
