// SPDX-License-Identifier: Apache-2.0
// phasor — free-space diffraction (FSD): where a generalized ray meets edges, and the shadow the
// geometry there casts on the GR's footprint (theory §4.8, docs/fsd.md §2–§3).
//
// A GR segment starts at g.o and runs along g.d. Its footprint radius ϱ(t) = window·β(t) (or a
// constant `radius`) grows along it (theory §1.6). FindEvent walks the segment with Embree ball
// queries (Accel::ForEachNear) that cover the cone of radius ϱ(t); the first opaque geometry whose
// distance to the mean ray is ≤ ϱ at its depth fixes the event: the point p on the mean ray at the
// depth where the geometry comes nearest to it (where the GR grazes or crosses it). The mask is
// then the union of the orthographic projections along d, onto the plane ⊥ d through p, of every
// opaque triangle (and analytic shape) within √5ϱ of p (the ball around the mask's box): shared edges whose two triangles project to
// opposite sides cancel (they are inside the shadow), so what bounds the mask are silhouette edges
// (one face towards the GR, one away) and open boundaries — found from the triangles gathered,
// without any preprocessing of the mesh. Analytic shapes enter as polygons: a disk's rim (an
// ellipse in projection) and a sphere's outline (a circle), with a sagitta below 10⁻³ ϱ.
#pragma once

#include <vector>

#include "core/geometry/polygon_union.h"
#include "core/render/genray.h"
#include "core/render/scene.h"

namespace phasor::fsd {

/// The integrator parameters of FSD (grt, sample_solve).
struct Settings {
    bool enabled = false;
    double window = 4;  // integration radius ϱ in units of the GR's β (D13)
    double radius = 0;  // > 0: a constant integration radius [m] instead of window·β (Fig. S3b)
};

/// The parameters `fsd`, `fsd_window`, `fsd_radius` and their values.
std::vector<ParamSpec> Params();
Settings SettingsFromParams(const ParamDict &d);

/// Which of the scene's shapes cast FSD shadows (by Accel shape index): every shape except those
/// whose kernel is footprint-aware (an `aperture` plate diffracts by itself) or transmits light
/// (a `dielectric` is not an opaque screen; its light stays classical). Built once per scene.
class Occluders {
  public:
    explicit Occluders(const Scene &scene);
    bool Contains(unsigned shapeIndex) const {
        return shapeIndex < occluder_.size() && occluder_[shapeIndex] != 0;
    }
    bool Any() const { return any_; }

  private:
    std::vector<char> occluder_;
    bool any_ = false;
};

/// β² at distance t along a GR with wavenumber k, β², ρ at t = 0 (theory §1.6).
inline double Beta2At(double k, double beta2, double rho, double t) {
    const double zb = t / k;
    return beta2 + zb * (2 * rho + zb * (1 + rho * rho) / beta2);
}

/// The integration radius ϱ [m] of the GR `g` (at its origin) at distance t: window·max_i β_i(t),
/// or the constant radius.
double IntegrationRadius(const SpectralGenRay &g, double t, const Settings &s);

/// An FSD event: the plane through p ⊥ d (axes frame.s, frame.t; frame.n = d, the traced
/// direction) and the shadow of the local geometry in it, in plane coordinates relative to p.
struct Event {
    Vec3 p;
    double t = 0;              // distance from the segment's origin [m]
    Frame frame;
    double halfWidth = 0;      // ϱ at the event: the mask covers [−2ϱ, 2ϱ] × [−ϱ, ϱ]
    double gatherRadius = 0;   // geometry within this distance of p is in the mask [m] (√5·ϱ)
    std::vector<OrientedSegment> edges;  // the shadow's outline (silhouettes, open boundaries)
    UnionDecomposition mask;             // covered (shadow) and open trapezoids of the box
    /// The hero's |ψ|² mass in each covered trapezoid and their sum (the fraction of the GR's
    /// power that meets the geometry; the box holds 1 − O(10⁻⁸)).
    std::vector<double> coveredMass;
    double coveredFraction = 0;
    double heroBeta2 = 0;                // β² of the hero at the event [m²]
    /// How far the gathered geometry reaches beyond p along d [m], in [0, gatherRadius]: a ray
    /// leaving the event starts there, past what the mask already accounts for (fsd_kernel.h).
    double beyond = 0;
};

enum class Search {
    None,     // no geometry in the footprint along the segment
    Event,    // an event: the geometry covers part of the footprint
    Blocked,  // the first geometry covers the whole footprint (a plain hit)
};

/// What a search cost (for statistics).
struct SearchCost {
    int ballQueries = 0;
    int primitives = 0;
};

/// Searches the segment of `g` (its origin, traced direction, per-wavelength footprints there)
/// from t = 0 to tEnd (the mean ray's hit, or Infinity) for the first event. `exclude` is the
/// shape the GR leaves (its own surface does not diffract it), or nullptr. Geometry whose share
/// of the footprint is below 10⁻⁵ is passed; a share above 1 − 10⁻⁵ is Blocked.
/// `source`: the distance of a source the GR measures along d (a point light); geometry beyond it
/// casts no shadow on the measurement (BuildMask's tEnd).
Search FindEvent(const Scene &scene, const Occluders &occ, const SpectralGenRay &g, double tEnd,
                 const Shape *exclude, const Settings &s, Event *ev, SearchCost *cost = nullptr,
                 double source = Infinity);

/// Builds the mask of an event at distance t along g (the gather and projection of FindEvent);
/// for tests and for the search itself.
/// Geometry beyond depth tEnd along g (a source the GR measures) is left out, as is geometry
/// behind the origin.
void BuildMask(const Scene &scene, const Occluders &occ, const SpectralGenRay &g, double t,
               const Shape *exclude, const Settings &s, Event *ev, SearchCost *cost = nullptr,
               double tEnd = Infinity);

/// |ψ|² mass of the hero GR (β², waist form e^{−|x|²/β²}/(πβ²)) over a trapezoid.
double GaussianMass(const Trapezoid &tr, double beta2);

}  // namespace phasor::fsd
