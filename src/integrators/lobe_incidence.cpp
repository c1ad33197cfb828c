// SPDX-License-Identifier: Apache-2.0
// phasor — D4a through listed near-delta lobes (lobe_incidence.h).
#include "integrators/lobe_incidence.h"

#include <algorithm>
#include <cmath>

#include "core/render/light.h"
#include "core/render/lobe_average.h"
#include "core/render/material.h"

namespace phasor {

namespace {

// Newton's method on r(u) (lobe_incidence.h): converged when |r| < ResidualTol [rad], far below
// any GR's angular spread (≥ 1e-7 rad for a metre-sized pixel); central differences of step
// StepH [rad] (truncation ~StepH²·r''' and round-off ~1e-16/StepH, both ≲ 1e-10 relative).
constexpr double ResidualTol = 1e-11;
constexpr double StepH = 1e-5;
constexpr int MaxIterations = 30;
constexpr double MaxStep = 0.25;  // [rad] per Newton step
constexpr int MaxHalvings = 40;    // of a step that leaves the shape (0.25 rad / 2⁴⁰ ≈ 2e-13 rad)

/// The state at one detector direction: the hit, the lobe's exit direction and the source.
struct LobeState {
    SurfaceInteraction si;
    NearDeltaLobe lobe;   // the lobe as listed at this hit (weight a_j(λ_i), indices, directions)
    Vec3 dir;             // the detector direction that reaches it
    GrIncidence inc;      // the light at p (towards the source: inc.wi)
    Vec3 wo;              // the lobe's exit direction at wavelength `i` (world)
};

/// What is solved: one light through one lobe (by id) of one shape, at carried wavelength `i`
/// (for a lobe whose direction does not depend on λ, i = 0 serves every wavelength).
struct LobeTarget {
    const Scene &scene;
    const Shape *shape;
    const Light *light;
    int id;
    int i;
    Vec3 o;                     // the detector sample's origin
    const SpectralGenRay &g;    // its GR (footprint at the detector)
    const SampledWavelengths &wl;
    ScratchBuffer &scratch;     // each trial kernel is prepared here and dropped after Evaluate

    /// The GR as it meets the surface at si along dir: the detector's footprint, placed at the hit
    /// (a source that varies in space, a Gaussian beam, is seen through the pixel's own footprint).
    SpectralGenRay AtHit(const SurfaceInteraction &si, const Vec3 &dir) const {
        SpectralGenRay gp = g;
        gp.o = si.p;
        gp.d = dir;
        return gp;
    }
    /// The kernel query of that GR (its pointers refer to si and gp).
    ScatterQuery Query(const SurfaceInteraction &si, const SpectralGenRay &gp) const {
        ScatterQuery q;
        q.wi = si.shading.ToLocal(-gp.d);
        q.wl = &wl;
        q.rayOptics = false;
        q.tex = TextureEvalContext(si, std::sqrt(g.beta2[0]));
        q.gr = &gp;
        q.si = &si;
        return q;
    }

    /// The state along direction `dir` from o; false if the ray does not reach the shape first, the
    /// lobe is not listed there, or no light arrives at p.
    bool Evaluate(const Vec3 &dir, LobeState *st, PathStats &stats) const {
        ++stats.rays;
        auto si = scene.Intersect(Ray{o, dir});
        if (!si || si->shape != shape || !si->material) return false;
        const SpectralGenRay gp = AtHit(*si, dir);
        const ScatterQuery q = Query(*si, gp);
        const ScratchBuffer::Mark mark = scratch.Save();
        const NearDeltaLobe *lobe = si->material->Prepare(q, scratch).FindLobe(id);
        std::optional<GrIncidence> inc;
        if (lobe && lobe->Weight()[i] > 0) inc = light->IncidenceOnGR(gp, wl);
        if (inc) {
            st->si = *si;
            st->lobe = lobe->Detached();  // kept past the Rewind below
            st->dir = dir;
            st->inc = *inc;
            st->wo = si->shading.ToWorld(lobe->wo[i]);
        }
        scratch.Rewind(mark);
        return inc.has_value();
    }

    /// r = ω_j − s in the plane ⊥ `perp.n` (a frame fixed during one Newton step).
    static Vec2 Residual(const LobeState &st, const Frame &perp) {
        const Vec3 d = st.wo - st.inc.wi;
        return Vec2(Dot(d, perp.s), Dot(d, perp.t));
    }

    /// ∂r/∂u at dir by central differences, u = (a, b) ↦ normalize(dir + a·T.s + b·T.t) (unit
    /// speed at 0: solid-angle coordinates); one-sided where a neighbour leaves the shape (within
    /// StepH·distance of its edge). False if both neighbours of an axis miss.
    bool Jacobian(const Vec3 &dir, const LobeState &at, const Frame &T, const Frame &perp, double J[2][2],
                  PathStats &stats) const {
        const Vec2 r0 = Residual(at, perp);
        for (int c = 0; c < 2; ++c) {
            const Vec3 axis = c == 0 ? T.s : T.t;
            LobeState plus, minus;
            const bool p = Evaluate(Normalize(dir + axis * StepH), &plus, stats);
            const bool m = Evaluate(Normalize(dir - axis * StepH), &minus, stats);
            if (!p && !m) return false;
            const Vec2 hi = p ? Residual(plus, perp) : r0, lo = m ? Residual(minus, perp) : r0;
            const Vec2 d = (hi - lo) / ((p && m ? 2 : 1) * StepH);
            J[0][c] = d.x;
            J[1][c] = d.y;
        }
        return true;
    }

    /// Newton from `seed`: the solution's state and |det ∂r/∂u| there; false if none is found. A
    /// step that leaves the shape (or the lobe) is halved until it lands on it: near the shape's
    /// edge the first steps, taken with the Jacobian of a distant seed, may overshoot.
    bool Solve(const Vec3 &seed, LobeState *st, double *absDet, PathStats &stats) const {
        Vec3 dir = seed;
        LobeState cur;
        if (!Evaluate(dir, &cur, stats)) return false;
        for (int it = 0; it < MaxIterations; ++it) {
            const Frame perp = Frame::FromNormal(cur.inc.wi);
            const Frame T = Frame::FromNormal(dir);
            double J[2][2];
            if (!Jacobian(dir, cur, T, perp, J, stats)) return false;
            const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
            if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) return false;
            const Vec2 r = Residual(cur, perp);
            if (Length(r) < ResidualTol) {
                // r only sees the components ⊥ s, so ω = −s (a lobe pointing away from the source,
                // e.g. a refraction on the source's own side) would pass: no solution then.
                if (Dot(cur.wo, cur.inc.wi) <= 0) return false;
                *st = cur;
                *absDet = std::abs(det);
                return true;
            }
            // δ = −J⁻¹ r, limited so that a far seed approaches in bounded steps.
            Vec2 delta(-(J[1][1] * r.x - J[0][1] * r.y) / det, -(-J[1][0] * r.x + J[0][0] * r.y) / det);
            const double len = Length(delta);
            if (len > MaxStep) delta = delta * (MaxStep / len);
            for (int halvings = 0;; ++halvings) {
                const Vec3 next = Normalize(dir + T.s * delta.x + T.t * delta.y);
                if (Evaluate(next, &cur, stats)) {
                    dir = next;
                    break;
                }
                if (halvings == MaxHalvings) return false;
                delta = delta * 0.5;
            }
        }
        return false;
    }
};
/// Directions from o towards the shape to start Newton from: its bounds' centre, then a few
/// points spread over it (a plate with a hole in the middle).
std::vector<Vec3> Seeds(const Shape &shape, const Vec3 &o) {
    std::vector<Vec3> seeds;
    const Bounds3 b = shape.Bounds();
    auto add = [&](const Vec3 &p) {
        const Vec3 d = p - o;
        if (LengthSquared(d) > 0) seeds.push_back(Normalize(d));
    };
    add(b.Center());
    for (const Vec2 &u : {Vec2(0.5, 0.5), Vec2(0.2, 0.2), Vec2(0.8, 0.8), Vec2(0.2, 0.8), Vec2(0.8, 0.2)})
        add(shape.Sample(u).p);
    return seeds;
}

}  // namespace

LobeIncidence::LobeIncidence(const Scene &scene) {
    SampledWavelengths wl;
    wl.lambda[0] = 550e-9;  // Capabilities do not depend on λ for any kernel; one is needed for the query
    wl.pdf[0] = 1;
    ScratchBuffer scratch;
    for (const auto &shape : scene.Shapes()) {
        const Material *m = shape->material;
        if (!m || !shape->IsPlanar() || m->IsFootprintAware()) continue;
        ScatterQuery q;
        q.wi = Vec3(0, 0, 1);
        q.wl = &wl;
        q.rayOptics = false;
        scratch.Reset();
        if (m->Prepare(q, scratch).Capabilities() & CapNearDelta) shapes_.push_back(shape.get());
    }
}

bool LobeIncidence::Covers(const Shape *shape) const {
    return std::find(shapes_.begin(), shapes_.end(), shape) != shapes_.end();
}

SampledSpectrum LobeIncidence::Integrate(const Scene &scene, const DetectorGrSample &ds, const SpectralGenRay &g,
                                         const SampledWavelengths &wl, ScratchBuffer &scratch, PathStats &stats,
                                         const Report *report, const ModeOf *mode) const {
    SampledSpectrum sum(0.0);
    const Detector &detector = scene.GetDetector();
    for (const Shape *shape : shapes_) {
        const std::vector<Vec3> seeds = Seeds(*shape, ds.ray.o);
        for (const Light *sceneLight : scene.ClosedFormLights()) {
            const Light *light = sceneLight;
            // The lobes listed where the first seed that reaches the shape hits it; each is then
            // followed by its id (a planar kernel lists the same ids over the surface).
            const ScratchBuffer::Mark mark = scratch.Save();
            std::span<const NearDeltaLobe> seedLobes;
            Vec3 seed, seedHit, seedWi;
            bool found = false;
            for (const Vec3 &d : seeds) {
                ++stats.rays;
                auto si = scene.Intersect(Ray{ds.ray.o, d});
                if (!si || si->shape != shape) continue;
                SpectralGenRay gp = g;
                gp.o = si->p;
                gp.d = d;
                ScatterQuery q;
                q.wi = si->shading.ToLocal(-d);
                q.wl = &wl;
                q.rayOptics = false;
                q.tex = TextureEvalContext(*si, std::sqrt(g.beta2[0]));
                q.gr = &gp;
                q.si = &*si;
                seedLobes = si->material->Prepare(q, scratch).ListNearDelta();
                seedWi = q.wi;
                seed = d;
                seedHit = si->p;
                found = true;
                break;
            }
            if (!found) {
                scratch.Rewind(mark);
                continue;
            }
            // A replacement light (a coherent mode) is drawn once per light and shape, where the
            // seed ray meets the shape.
            if (mode) light = (*mode)(sceneLight, seedHit);
            for (const NearDeltaLobe &lobe : seedLobes) {
                // Light straight through the surface reaches the sensor as direct incidence, whose
                // shadow ray crosses it (Scene::Transmittance, theory §3.5).
                if (PassesStraight(*shape->material, lobe, seedWi, wl.Count())) continue;
                bool uniform = !(lobe.flags & ScatterDispersive);
                for (int i = 1; i < wl.Count(); ++i) uniform = uniform && lobe.wo[i] == lobe.wo[0];
                // One solve serves every wavelength of a lobe whose direction does not depend on λ;
                // a dispersive lobe is solved per carried wavelength, each along its own direction.
                for (int i = 0; i < (uniform ? 1 : wl.Count()); ++i) {
                    const LobeTarget target{scene, shape, light, lobe.id, i, ds.ray.o, g, wl, scratch};
                    LobeState st;
                    double absDet = 0;
                    if (!target.Solve(seed, &st, &absDet, stats)) continue;
                    const Vec3 s = st.inc.wi;
                    const bool far = std::isinf(st.inc.dist);
                    double tMax = 0;
                    const Ray shadow = scene.ShadowRay(st.si, far ? s : st.si.p + s * st.inc.dist, far, &tMax);
                    const SampledSpectrum crossed = scene.Transmittance(shadow, tMax, wl, false, scratch, stats.rays);
                    if (crossed.IsZero()) continue;
                    // (1): E_det = a_j·E_p/|det ∂r/∂u|, arriving at o from the hit — with a_j averaged
                    // over the light's angular profile, each plane wave weighted by the lobe's irradiance
                    // transfer relative to the central one's, which |det| holds (theory §0 D15).
                    const SpectralGenRay gp = target.AtHit(st.si, st.dir);
                    const LobeEnsemble ensemble = SourceEnsemble(st.si.shading, st.inc.wi, st.inc.profile);
                    const ScratchBuffer::Mark hitMark = scratch.Save();
                    const PreparedKernel &k = st.si.material->Prepare(target.Query(st.si, gp), scratch);
                    const SampledSpectrum a = AverageLobeWeight(*st.si.material, k, st.lobe, ensemble,
                                                                LobeTransfer::Irradiance, uniform ? -1 : i);
                    scratch.Rewind(hitMark);
                    GrIncidence inc;
                    inc.irradiance = SampledSpectrum(0.0);
                    for (int k = 0; k < wl.Count(); ++k)
                        if (uniform || k == i) inc.irradiance[k] = crossed[k] * a[k] * st.inc.irradiance[k] / absDet;
                    inc.wi = Normalize(st.si.p - ds.ray.o);
                    inc.dist = Length(st.si.p - ds.ray.o) + st.inc.dist;
                    inc.angularVariance = st.inc.angularVariance;
                    const SampledSpectrum v = detector.IntegrateIncidence(ds, inc);
                    sum += v;
                    if (report && !v.IsZero()) {
                        SpectralGenRay gp = g;  // as Evaluate placed it at p
                        gp.o = st.si.p;
                        gp.d = Normalize(st.si.p - ds.ray.o);
                        Contribution c;
                        c.value = v;
                        c.light = sceneLight;
                        c.ensemble = light == sceneLight;
                        c.si = &st.si;
                        c.gr = &gp;
                        c.lobe = lobe.id;
                        c.woLocal = st.si.shading.ToLocal(st.wo);
                        c.wavelength = uniform ? -1 : i;
                        c.travel = -s;
                        c.dist = st.inc.dist;
                        c.profile = st.inc.profile;
                        (*report)(c);
                    }
                }
            }
            scratch.Rewind(mark);  // the seed's kernel and what the reports prepared
        }
    }
    return sum;
}

}  // namespace phasor
