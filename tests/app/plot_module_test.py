# SPDX-License-Identifier: Apache-2.0
"""Tests of python/phasor_plot.py (the matplotlib plots of phasor): each command draws its data
where the axes put it (checked in the rendered canvas at data coordinates), writes the format
asked for, and reports bad input and failed writes as one line with exit status 1; without
matplotlib/numpy the module exits with status 3.

    python3 plot_module_test.py PATH/TO/phasor_plot.py
"""

import importlib.util
import math
import os
import subprocess
import sys
import tempfile
import unittest

MODULE = None  # the module under test, loaded in main


def load(path):
    spec = importlib.util.spec_from_file_location("phasor_plot", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def rgb_at(fig, ax, x, y):
    """The colour (0..255) of the rendered figure at data point (x, y) of `ax`."""
    import numpy as np

    fig.canvas.draw()
    buf = np.asarray(fig.canvas.buffer_rgba())
    px, py = ax.transData.transform((x, y))
    h = buf.shape[0]
    return buf[int(round(h - py)), int(round(px)), :3].astype(int)


def close(a, b, tol=3):
    return all(abs(int(u) - int(v)) <= tol for u, v in zip(a, b))


def hex_rgb(h):
    return [int(h[i:i + 2], 16) for i in (1, 3, 5)]


class PlotModuleTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.path = lambda name: os.path.join(self.dir.name, name)

    def tearDown(self):
        self.dir.cleanup()

    def write(self, name, text):
        with open(self.path(name), "w", encoding="utf-8") as f:
            f.write(text)
        return self.path(name)

    def run_main(self, argv):
        """main(argv) with its stderr captured: (status, stderr text)."""
        import contextlib
        import io

        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            status = MODULE.main(argv)
        return status, err.getvalue()

    # ---- profile ----------------------------------------------------------------------------

    def profile_csv(self):
        rows = ["x_m,grt,rs,abs_diff"]
        for i in range(48):  # 25 µm pixels over ±600 µm
            x = -587.5e-6 + 25e-6 * i
            a = 1 + math.cos(x * 2e4)
            rows.append(f"{x},{a},{a + 0.1},0.1")
        return self.write("p.csv", "\n".join(rows) + "\n")

    def test_profile_draws_each_series_at_its_data(self):
        args = MODULE.parse_args(["profile", "--data", self.profile_csv(), "--out", self.path("p.png"),
                                  "--diff-scale", "2", "--title", "t"])
        fig = MODULE.figure_profile(args)
        ax = fig.axes[0]
        self.assertEqual(ax.get_xlabel(), "x (µm)")  # metres shown in a fitting unit
        self.assertEqual([round(v) for v in fig.get_size_inches() * fig.dpi], [1000, 600])
        # At pixel 24 (x = 12.5 µm): grt (blue, solid) at a, rs (green, dashed) at a + 0.1 covers it,
        # |grt − rs| × 2 = 0.2 is black.
        x = (-587.5e-6 + 25e-6 * 24)
        a = 1 + math.cos(x * 2e4)
        xs = x * 1e6
        self.assertTrue(close(rgb_at(fig, ax, xs, a), hex_rgb(MODULE.PALETTE[0]), 40), rgb_at(fig, ax, xs, a))
        self.assertTrue(close(rgb_at(fig, ax, xs, 0.2), [0, 0, 0], 60), rgb_at(fig, ax, xs, 0.2))
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        self.assertEqual(labels, ["grt", "rs", "|grt - rs| × 2", "one pixel (25 µm)"])
        lo, hi = ax.get_xlim()  # from the first pixel's left edge to the last one's right edge
        self.assertAlmostEqual(lo, -600, places=6)
        self.assertAlmostEqual(hi, 600, places=6)

    def test_profile_png_svg_and_pdf(self):
        data = self.profile_csv()
        for name, magic in (("p.png", b"\x89PNG"), ("p.svg", b"<?xml"), ("p.pdf", b"%PDF")):
            status, err = self.run_main(["profile", "--data", data, "--out", self.path(name)])
            self.assertEqual(status, 0, err)
            with open(self.path(name), "rb") as f:
                self.assertEqual(f.read(len(magic)), magic, name)
        # An explicit --format wins over the name (phasor writes to a temporary name).
        status, err = self.run_main(["profile", "--data", data, "--out", self.path(".p.png.tmp-1"), "--format", "png"])
        self.assertEqual(status, 0, err)
        with open(self.path(".p.png.tmp-1"), "rb") as f:
            self.assertEqual(f.read(4), b"\x89PNG")

    def test_bad_input_and_failed_writes_are_one_line_and_status_1(self):
        bad = self.write("bad.csv", "x_m,a\n0,1\n1,oops\n")
        status, err = self.run_main(["profile", "--data", bad, "--out", self.path("x.png")])
        self.assertEqual(status, 1)
        self.assertRegex(err, r"^error: .*bad\.csv:3: 'oops' is not a number\n$")
        status, err = self.run_main(["profile", "--data", self.write("k.csv", "z,a\n0,1\n"), "--out", self.path("x.png")])
        self.assertEqual((status, err.count("\n")), (1, 1))
        self.assertIn("the first column must be x_m, x_px or y_px", err)
        status, err = self.run_main(["profile", "--data", self.path("none.csv"), "--out", self.path("x.png")])
        self.assertEqual(status, 1)
        self.assertIn("cannot read", err)
        # A write that fails: the system's reason.
        status, err = self.run_main(["profile", "--data", self.profile_csv(), "--out", self.path("no/dir/x.png")])
        self.assertEqual(status, 1)
        self.assertEqual(err, "error: No such file or directory\n")
        self.assertFalse(os.path.exists(self.path("x.png")))

    # ---- disc map (phasor probe) ------------------------------------------------------------

    def disc_csv(self, n=41):
        rows = ["u,v,value"]
        for j in range(n):
            for i in range(n):
                u, v = -1 + 2 * i / (n - 1), -1 + 2 * j / (n - 1)
                rows.append(f"{u},{v},{1e-3 + math.exp(-((u - 0.5) ** 2 + (v + 0.25) ** 2) / 0.01)}")
        return self.write("d.csv", "\n".join(rows) + "\n")

    def test_disc_map_puts_values_over_the_projected_hemisphere(self):
        import matplotlib

        points = self.write("pts.csv", "u,v,label\n0.6,-0.1,R0\n-0.3,0.4,T+1\n")
        args = MODULE.parse_args(["disc-map", "--data", self.disc_csv(), "--points", points, "--out",
                                  self.path("d.png"), "--value-label", "Eval cos"])
        fig = MODULE.figure_disc_map(args)
        ax = fig.axes[0]
        viridis = matplotlib.colormaps["viridis"]
        top = [round(255 * c) for c in viridis(1.0)[:3]]
        bottom = [round(255 * c) for c in viridis(0.0)[:3]]
        # The peak (0 dB) at (0.5, −0.25) (a cell centre); far from it 1e-3 of the peak is −30 dB
        # (t = 0.25 of the 40 dB range); outside the unit disc nothing (white).
        self.assertTrue(close(rgb_at(fig, ax, 0.5, -0.25), top, 8), rgb_at(fig, ax, 0.5, -0.25))
        far = [round(255 * c) for c in viridis(0.25)[:3]]
        self.assertTrue(close(rgb_at(fig, ax, -0.6, -0.2), far, 8), rgb_at(fig, ax, -0.6, -0.2))
        self.assertTrue(close(rgb_at(fig, ax, 0.95, 0.95), [255, 255, 255], 2), rgb_at(fig, ax, 0.95, 0.95))
        self.assertFalse(close(top, bottom, 8))
        texts = [t.get_text() for t in ax.texts]
        self.assertIn("R0", texts)
        self.assertIn("T+1", texts)
        self.assertIn("Eval cos (dB, 0 dB = 1.001)", fig.axes[1].get_ylabel())
        # log and linear scales draw too
        for scale in ("log", "linear"):
            status, err = self.run_main(["disc-map", "--data", self.disc_csv(), "--out", self.path(scale + ".png"),
                                         "--scale", scale])
            self.assertEqual(status, 0, err)

    def test_two_discs_on_one_scale_with_rings_and_a_cross(self):
        import matplotlib

        rows = ["disc,u,v,value"]
        n = 21
        for disc, peak in (("reflection", 1.0), ("transmission", 0.01)):
            for j in range(n):
                for i in range(n):
                    u, v = -1 + 2 * i / (n - 1), -1 + 2 * j / (n - 1)
                    rows.append(f"{disc},{u},{v},{peak}")
        points = self.write("p.csv", "disc,u,v,label,marker,size\nreflection,-0.5,0,0.04,o,9\n"
                                     "transmission,0.3,0.3,0.96,o,12\nreflection,0.5,0,,x,10\n")
        args = MODULE.parse_args(["disc-map", "--data", self.write("d2.csv", "\n".join(rows) + "\n"), "--points",
                                  points, "--out", self.path("d2.png")])
        fig = MODULE.figure_disc_map(args)
        left, right = fig.axes[:2]
        self.assertEqual((left.get_title(), right.get_title()), ("reflection", "transmission"))
        self.assertEqual([round(v) for v in fig.get_size_inches() * fig.dpi], [80 + 840 + 130, 520])
        viridis = matplotlib.colormaps["viridis"]
        # One scale: the reflection disc at 0 dB, the transmission disc 20 dB below (t = 0.5).
        top = [round(255 * c) for c in viridis(1.0)[:3]]
        mid = [round(255 * c) for c in viridis(0.5)[:3]]
        self.assertTrue(close(rgb_at(fig, left, 0.1, -0.6), top, 8), rgb_at(fig, left, 0.1, -0.6))
        self.assertTrue(close(rgb_at(fig, right, -0.1, -0.6), mid, 8), rgb_at(fig, right, -0.1, -0.6))
        # The ring's red edge at its radius on the left disc, the label beside it; the cross white
        # at its centre.
        self.assertIn("0.04", [t.get_text() for t in left.texts])
        self.assertIn("0.96", [t.get_text() for t in right.texts])
        self.assertTrue(close(rgb_at(fig, left, 0.5, 0), [255, 255, 255], 30), rgb_at(fig, left, 0.5, 0))
        # A marker on a disc that is not in the data is an error.
        bad = self.write("bad.csv", "disc,u,v,label\nsomewhere,0,0,a\n")
        status, err = self.run_main(["disc-map", "--data", self.path("d2.csv"), "--points", bad, "--out",
                                     self.path("x.png")])
        self.assertEqual(status, 1)
        self.assertIn("no disc 'somewhere'", err)

    def test_labels_of_coincident_markers_do_not_overlap(self):
        # Three lobes leaving in one direction (a mix of kernels) and one elsewhere: every label is
        # drawn, and no two labels' boxes intersect on the canvas.
        rows = ["u,v,value"] + [f"{-1 + 2 * i / 10},{-1 + 2 * j / 10},1" for j in range(11) for i in range(11)]
        points = self.write("c.csv", "u,v,label\n0.2,0.1,a: 0.5\n0.2,0.1,b: 0.25\n0.2001,0.1,b: 0.125\n"
                                     "-0.6,-0.5,0.04\n")
        args = MODULE.parse_args(["disc-map", "--data", self.write("c_data.csv", "\n".join(rows) + "\n"),
                                  "--points", points, "--out", self.path("c.png")])
        fig = MODULE.figure_disc_map(args)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        texts = [t for t in fig.axes[0].texts if t.get_text() in ("a: 0.5", "b: 0.25", "b: 0.125", "0.04")]
        self.assertEqual(len(texts), 4)
        boxes = [t.get_window_extent(renderer) for t in texts]
        for i in range(len(boxes)):
            for j in range(i + 1, len(boxes)):
                self.assertFalse(boxes[i].overlaps(boxes[j]),
                                 f"labels '{texts[i].get_text()}' and '{texts[j].get_text()}' overlap")

    def test_a_map_that_is_zero_everywhere_is_neutral_grey(self):
        rows = ["u,v,value"] + [f"{-1 + 2 * i / 10},{-1 + 2 * j / 10},0" for j in range(11) for i in range(11)]
        args = MODULE.parse_args(["disc-map", "--data", self.write("z.csv", "\n".join(rows) + "\n"), "--out",
                                  self.path("z.png"), "--value-label", "Eval cos"])
        fig = MODULE.figure_disc_map(args)
        self.assertTrue(close(rgb_at(fig, fig.axes[0], 0.1, 0.1), [230, 230, 230], 3), rgb_at(fig, fig.axes[0], 0.1, 0.1))
        self.assertEqual(len(fig.axes), 1)  # no colour bar: there is no scale
        self.assertIn("Eval cos: zero everywhere", [t.get_text() for t in fig.texts])

    def test_disc_map_needs_a_regular_grid(self):
        data = self.write("g.csv", "u,v,value\n0,0,1\n0.5,0,1\n0,0.5,1\n")
        status, err = self.run_main(["disc-map", "--data", data, "--out", self.path("g.png")])
        self.assertEqual(status, 1)
        self.assertIn("do not form a regular grid", err)

    # ---- convergence ------------------------------------------------------------------------

    def test_convergence_draws_each_run_against_spp_and_time(self):
        rows = ["run,spp,seconds,rmse,rel_mse,max_error"]
        for run, c, speed in (("grt", 0.1, 0.01), ("ray", 0.2, 0.005)):
            for k in range(6):
                n = 2 ** k
                rows.append(f"{run},{n},{speed * n},{c / math.sqrt(n)},{c * c / n},{3 * c / math.sqrt(n)}")
        args = MODULE.parse_args(["convergence", "--data", self.write("c.csv", "\n".join(rows) + "\n"), "--out",
                                  self.path("c.png")])
        fig = MODULE.figure_convergence(args)
        by_spp, by_time = fig.axes[:2]
        self.assertEqual((by_spp.get_xscale(), by_spp.get_yscale()), ("log", "log"))
        lines = {l.get_label(): l for l in by_spp.lines}
        self.assertEqual(sorted(lines), ["grt", "ray", "∝ 1/√spp"])
        self.assertEqual(list(lines["ray"].get_xdata()), [1, 2, 4, 8, 16, 32])
        self.assertAlmostEqual(lines["ray"].get_ydata()[-1], 0.2 / math.sqrt(32))
        t = {l.get_label(): l for l in by_time.lines}
        self.assertAlmostEqual(t["grt"].get_xdata()[-1], 0.32)


class MissingLibraryTest(unittest.TestCase):
    def test_without_matplotlib_the_status_is_3(self):
        # -S: no site packages, so neither numpy nor matplotlib can be imported.
        r = subprocess.run([sys.executable, "-S", "-B", MODULE.__file__, "profile", "--data", "x", "--out", "y"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 3, r.stderr)
        self.assertRegex(r.stderr, r"^error: (numpy|matplotlib) is not installed for ")


if __name__ == "__main__":
    MODULE = load(sys.argv.pop(1))
    unittest.main(verbosity=1)
