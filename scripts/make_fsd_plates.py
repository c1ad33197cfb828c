#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
# Writes the FSD test plates of scenes/validation/fsd_plates (docs/fsd.md; not scenes/assets, which
# tools/make_assets writes): flat, single-sided, zero-thickness
# triangle meshes in the plane z = 0 — a square [-64, 64]^2 with a hole, triangulated as a ring of
# quads between the hole's vertices and the square's points at the same angles. Unit: the hole's
# size (scale with to_world).
#   fsd_disc_hole.obj  a 256-gon of the area of the unit circle (radius 1)
#   fsd_star_hole.obj  a 5-pointed star, outer radius 1, inner radius 0.45 (the GR paper's Fig. S3)
# Usage: scripts/make_fsd_plates.py scenes/validation/fsd_plates
import math
import sys


def plate(outline, half=64.0):
    """A ring of quads from the hole's outline (counter-clockwise, star-shaped about the origin)
    to the square's points at the same angles."""
    verts, tris = [], []
    for (x, y) in outline:
        phi = math.atan2(y, x)
        c, s = math.cos(phi), math.sin(phi)
        t = half / max(abs(c), abs(s))
        verts += [(x, y), (t * c, t * s)]
    n = len(outline)
    for i in range(n):
        j = (i + 1) % n
        a, b, c, d = 2 * i, 2 * i + 1, 2 * j + 1, 2 * j
        tris += [(a, b, c), (a, c, d)]
    return verts, tris


def write(path, verts, tris, comment):
    with open(path, "w") as f:
        f.write("# " + comment + " (scripts/make_fsd_plates.py)\n")
        for x, y in verts:
            f.write("v %.12g %.12g 0\n" % (x, y))
        for a, b, c in tris:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def main(out):
    n = 256
    equal_area = math.sqrt(2 * math.pi / (n * math.sin(2 * math.pi / n)))
    disc = [(equal_area * math.cos(2 * math.pi * i / n), equal_area * math.sin(2 * math.pi * i / n)) for i in range(n)]
    write(out + "/fsd_disc_hole.obj", *plate(disc),
          "square plate [-64, 64]^2 with a 256-gon hole of the unit circle's area")

    # The star as a polygon (10 vertices: tips and notches) sampled along its straight edges.
    m = 8  # vertices per edge
    tips = []
    for i in range(10):
        phi = math.pi / 2 + math.pi * i / 5
        r = 1.0 if i % 2 == 0 else 0.45
        tips.append((r * math.cos(phi), r * math.sin(phi)))
    outline = []
    for i in range(10):
        (x0, y0), (x1, y1) = tips[i], tips[(i + 1) % 10]
        outline += [(x0 + (x1 - x0) * k / m, y0 + (y1 - y0) * k / m) for k in range(m)]
    verts, tris = plate(outline)
    write(out + "/fsd_star_hole.obj", verts, tris,
          "square plate [-64, 64]^2 with a 5-pointed star hole (outer radius 1, inner 0.45)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "scenes/validation/fsd_plates")
