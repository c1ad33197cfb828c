#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""What a kernel written in Python costs per call (docs/python.md, "Kernels in Python").

Times, in one run, Sample calls made by phasor's C++ code (through `phasor.probe`, which calls the
kernel's Sample once per Monte-Carlo sample) for
  * the C++ `diffuse` kernel,
  * a Python Lambertian (the same formulas as `diffuse`),
  * a Python kernel whose sample() does nothing but return a constant sample (the adapter's own
    cost: taking the GIL, building the argument tuples, converting the result),
and the Python Lambertian's sample() called directly from Python (its body's cost), plus a grt
render of the same scene with either kernel on every thread. Medians of 5 repetitions; the
numbers are ratios within one run (the machine may be shared).

    PYTHONPATH=build/python python3 bench/python_kernel_cost.py
"""
import math
import os
import statistics
import sys
import time

import phasor

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "python"))
from test_kernels import SCENE, Lambert  # noqa: E402  (the tests' Python copy of `diffuse`)


class Null(phasor.Material):
    """A kernel whose sample() returns one constant direction: the adapter's cost alone."""

    def sample(self, wi, wl, u0, u):
        return ((0.0, 0.0, 1.0), 0.5, 1 / math.pi)

    def eval(self, wi, wo, wl):
        return 0.5 / math.pi

    def pdf(self, wi, wo, wl):
        return 1 / math.pi


def median_seconds(f, repeat=5):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    phasor.register_material("py_lambert", Lambert)
    phasor.register_material("py_null", Null)
    lib = 'wscene 2\nMaterial "diffuse" "cpp" { reflectance = 0.5 }\nMaterial "py_lambert" "py" { albedo = 0.5 }\n' \
          'Material "py_null" "null" {}\n'
    path = os.path.join(os.environ.get("TMPDIR", "/tmp"), "phasor_kernel_cost.wscene")
    with open(path, "w") as f:
        f.write(lib)
    n = 200_000
    per_call = {}
    for name in ("cpp", "py", "null"):
        per_call[name] = median_seconds(lambda: phasor.probe(path, name, "30deg", "550nm", samples=n)) / n
    k = Lambert({"albedo": 0.5})
    wi, wl = (0.5, 0.0, math.sqrt(0.75)), (550e-9,)

    def direct_calls():
        for _ in range(n):
            k.sample(wi, wl, 0.3, (0.2, 0.7))
    direct = median_seconds(direct_calls) / n

    print("| per Sample call (probe, one thread) | µs |")
    print("|---|---|")
    print(f"| C++ `diffuse` | {per_call['cpp'] * 1e6:.2f} |")
    print(f"| Python Lambertian through phasor | {per_call['py'] * 1e6:.2f} |")
    print(f"| Python kernel returning a constant (the adapter alone) | {per_call['null'] * 1e6:.2f} |")
    print(f"| the Python Lambertian's sample() called from Python | {direct * 1e6:.2f} |")

    scenes = {kind: phasor.load_string(SCENE, defines={"kernel": kind}) for kind in ("cpp", "py")}
    render = {kind: median_seconds(lambda: s.render("grt", spp=256, progress=False), 3) for kind, s in scenes.items()}
    print(f"\ngrt render, {os.cpu_count()} threads: Python kernel / C++ kernel = "
          f"{render['py'] / render['cpp']:.1f}x ({render['py']:.3f} s vs {render['cpp']:.3f} s)")


if __name__ == "__main__":
    main()
