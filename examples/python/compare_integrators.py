#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Comparing integrators from Python: phasor.compare on a Cornell box with a glass sphere, drawn
with matplotlib — each integrator's image, its error against the reference, and the error against
samples per pixel (the convergence curves `phasor compare` plots).

The generalized-ray tracer `grt` and the classical `ray` solve the same light transport here
(diffuse walls, a smooth dielectric; no wave effect a camera could see), so both converge to the
same image; the reference is a longer `ray` render. The table is Comparison.table (a list of
dicts, or Comparison.dataframe() with pandas); write_report() would write the program's page.

    python3 examples/python/compare_integrators.py [--small] [--out DIR]
"""
import argparse
import pathlib
import sys

import numpy as np

import phasor

SCENE = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "validation" / "grt_cornell.wscene"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--small", action="store_true", help="24x24 pixels, 16 spp (the test's size)")
    ap.add_argument("--out", default="out/examples", help="directory for the figure")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    res, spp = (24, 16) if args.small else (96, 256)
    scene = phasor.load(SCENE, defines={"res": res})
    c = phasor.compare(scene, ["grt", "ray"], spp=spp, reference_integrator="ray", reference_spp=16 * spp,
                       seed=1, progress=not args.small)
    print(f"reference: {c.reference['description']}")
    for row in c.table:
        if row["role"] == "compared":
            print(f"{row['integrator']:>5}: {row['spp']} spp in {row['seconds']:.2f} s, "
                  f"relative MSE {row['rel_mse']:.3g}, RMSE {row['rmse']:.3g}")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure", file=sys.stderr)
        return {"comparison": c}
    names = [r["integrator"] for r in c.table if r["role"] == "compared"]
    ref = next(r["integrator"] for r in c.table if r["role"] == "reference")
    reference = c.images[ref]["intensity"].astype(np.float64)
    fig, axes = plt.subplots(1, len(names) + 2, figsize=(3.2 * (len(names) + 2), 3.2))
    for ax, name in zip(axes, names):
        ax.imshow(c.images[name].to_srgb())
        ax.set_title(name, fontsize=9)
        ax.axis("off")
    diff = c.images[names[0]]["intensity"] - c.images[names[-1]]["intensity"]
    lim = float(np.max(np.abs(diff))) or 1.0
    im = axes[-2].imshow(diff, cmap="RdBu_r", vmin=-lim, vmax=lim)
    axes[-2].set_title(f"{names[0]} − {names[-1]} (intensity)", fontsize=9)
    axes[-2].axis("off")
    fig.colorbar(im, ax=axes[-2], fraction=0.046)
    for name in names:
        points = [p for p in c.convergence if p["integrator"] == name]
        axes[-1].loglog([p["spp"] for p in points], [p["rel_mse"] for p in points], "o-", ms=3, label=name)
    axes[-1].set_xlabel("samples per pixel")
    axes[-1].set_ylabel(f"relative MSE vs {ref}")
    axes[-1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "compare_integrators.png", dpi=110)
    plt.close(fig)
    return {"comparison": c, "reference": reference}


if __name__ == "__main__":
    main()
