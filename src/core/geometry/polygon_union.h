// SPDX-License-Identifier: Apache-2.0
// phasor — the union of planar polygons cut into trapezoids (used by free-space diffraction,
// docs/fsd.md §3). Polygons are given by their boundary as oriented segments with the inside on
// the left (counter-clockwise outlines, clockwise holes); a point is covered when its winding
// number W — the number of outlines around it, counted with orientation — is ≥ 1, so overlapping
// polygons (the front and back faces of a box, two boxes one behind the other) count once and
// segments shared by two polygons on opposite sides cancel. A box is cut into horizontal slabs at
// every segment end point and crossing, and each slab into covered and open intervals whose
// limits are linear in v: trapezoids {v ∈ [v0, v1], u ∈ [a_lo + b_lo·v, a_hi + b_hi·v]}.
#pragma once

#include <span>
#include <vector>

#include "core/math.h"

namespace phasor {

/// One boundary segment from a to b; the covered side is on its left. `id` identifies the
/// source edge (≥ 0) for callers that track which edges bound the union; −1 for none.
struct OrientedSegment {
    Vec2 a, b;
    int id = -1;
};

/// {v ∈ [v0, v1], u ∈ [loA + loB·v, hiA + hiB·v]}. A limit that is a segment carries its index
/// in the input span (loSeg, hiSeg); a limit that is the box's side carries −1.
struct Trapezoid {
    double v0 = 0, v1 = 0;
    double loA = 0, loB = 0, hiA = 0, hiB = 0;
    int loSeg = -1, hiSeg = -1;
    double Lo(double v) const { return loA + loB * v; }
    double Hi(double v) const { return hiA + hiB * v; }
    double Area() const;
};

/// The box [−halfU, halfU] × [−halfV, halfV] split into the part the union covers and the rest.
struct UnionDecomposition {
    std::vector<Trapezoid> covered, open;
};

/// Decomposes the box as above. Segments outside the box still count (a polygon whose outline
/// lies left of the box covers it); horizontal segments are skipped (they bound no horizontal
/// interval). Cost: O(n²) crossing tests on bounding-box overlaps plus O(n log n) per slab.
/// Consecutive slabs whose intervals are bounded by the same segments are merged.
UnionDecomposition DecomposeUnion(std::span<const OrientedSegment> segments, double halfU, double halfV);

/// Winding number of the outlines at p (for tests): Σ over segments crossed by the ray from p
/// towards −u of ±1.
int WindingNumber(std::span<const OrientedSegment> segments, const Vec2 &p);

}  // namespace phasor
