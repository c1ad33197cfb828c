// SPDX-License-Identifier: Apache-2.0
// phasor — checks and choices that need the whole built scene: a sensor plane against the
// aperture plates (placement error, pixels too narrow for their distance from a plate (theory
// §2.6), automatic `aim`, theory §0 D4b); after a render whose image is black, the likely cause;
// and the wording of the integrators' work estimates.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/render/aperture.h"
#include "core/render/integrator.h"
#include "core/render/narrow_pixels.h"
#include "core/render/integrator_support.h"
#include "core/render/scene.h"

namespace phasor {

namespace {

/// An aperture plate: a planar shape whose kernel has openings (the `aperture` material).
struct Plate {
    std::shared_ptr<Shape> shape;
    Vec3 origin, n;  // a point of the plate's plane and its unit normal (local +z)
};

std::vector<Plate> Plates(const std::vector<std::shared_ptr<Shape>> &shapes) {
    std::vector<Plate> out;
    for (const auto &s : shapes)
        if (s->material && OpeningsOf(*s->material) && s->IsPlanar()) {
            const Transform &m = s->objectToWorld;
            const Vec3 n = Cross(m.Vector(Vec3(1, 0, 0)), m.Vector(Vec3(0, 1, 0)));
            if (LengthSquared(n) > 0) out.push_back(Plate{s, m.Point(Vec3(0, 0, 0)), Normalize(n)});
        }
    return out;
}

std::string Metres(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.4g m", v);
    return buf;
}
std::string Nm(double lambda) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.5g nm", lambda * 1e9);
    return buf;
}

/// A light's position as seen from p: a point at distance `dist` along `wi` (dist = Infinity for
/// lights at infinity). False if the light says nothing about where it is.
bool LightDirection(const Light &light, const Vec3 &p, Vec3 *wi, double *dist) {
    SampledWavelengths wl;
    wl.lambda[0] = 550e-9;
    wl.pdf[0] = 1;
    wl.delta = true;
    if (auto ls = light.SampleLi(LightSampleContext{p, Vec3(0, 0, 0)}, Vec2(0.5, 0.5), wl);
        ls && LengthSquared(ls->wi) > 0) {
        *wi = ls->wi;
        *dist = ls->dist;
        return true;
    }
    const LightCoherence c = light.Coherence(p);
    if (!(LengthSquared(c.wi) > 0)) return false;
    *wi = Normalize(c.wi);
    *dist = Infinity;
    return true;
}

/// Pixels narrow enough to be measured by their exact state at an aperture plate (theory §2.6)
/// need the plate at least narrow_pixels::MinPlateDistance away; closer, the state's expansion in
/// the pixel's extent fails and the generalized-ray integrators are not exact: warn with the
/// distance and the fixes (only for wavelengths the lights emit, where kβ < 63).
void WarnNarrowPixelsNearPlates(const Scene &scene, Diagnostics &diag, const std::vector<Plate> &plates) {
    const Detector &det = scene.GetDetector();
    const SensorPlaneGeometry *g = det.SensorPlane();
    const double beta2 = 2 * g->sigma * g->sigma, kMax = narrow_pixels::NonParaxialBelowKBeta / std::sqrt(beta2);
    // The largest wavenumber any light emits below kMax (the expansion's error grows with k).
    double k = 0;
    for (const Light *l : scene.Lights()) {
        const Spectrum &s = l->EmissionSpectrum();
        const auto [lo, hi] = s.LineWavelength() ? std::pair{*s.LineWavelength(), *s.LineWavelength()} : s.Support();
        const double kLo = 2 * Pi / hi, kHi = lo > 0 ? 2 * Pi / lo : Infinity;
        if (kLo < kMax) k = std::max(k, std::min(kHi, kMax));
    }
    if (!(k > 0)) return;
    const double need = narrow_pixels::MinPlateDistance(k, beta2);
    for (const Plate &pl : plates) {
        if (!(Dot(pl.origin - g->origin, g->frame.n) > 0)) continue;  // behind the sensor
        double h = Infinity;
        for (int c = 0; c < 4; ++c) {
            const Vec3 corner = g->origin + g->frame.s * (((c & 1) ? 0.5 : -0.5) * g->width) +
                                g->frame.t * (((c & 2) ? 0.5 : -0.5) * g->height);
            h = std::min(h, std::abs(Dot(corner - pl.origin, pl.n)));
        }
        if (h >= need) continue;
        char msg[512];
        std::snprintf(msg, sizeof msg,
                      "sensor '%s' has pixels of sigma = %.3g um (k*beta = %.3g at %.5g nm) %.3g um from the aperture "
                      "plate '%s': grt and sample_solve measure pixels this narrow by their exact state, whose "
                      "expansion in the pixel's extent holds from %.3g um on (docs/narrow_pixels.md); closer, "
                      "their values are not exact. Use --integrator rs, or move the sensor at least %.3g um from "
                      "the plate",
                      det.name.c_str(), g->sigma * 1e6, k * std::sqrt(beta2), 2 * Pi / k * 1e9, h * 1e6,
                      pl.shape->name.c_str(), need * 1e6, need * 1e6);
        diag.Warning(scene.Where(&det), msg,
                     {Diagnostic{Severity::Note, scene.Where(pl.shape.get()), "the plate is defined here", {}}});
    }
}

}  // namespace

void Scene::CheckSensorPlane(Diagnostics &diag) {
    Detector &det = *detector_;
    const SensorPlaneGeometry *g = det.SensorPlane();
    if (!g) return;
    const FileLoc detLoc = Where(&det);
    const std::vector<Plate> plates = Plates(shapes_);

    // A sensor in (or through) a plate's plane: GRs leave it tangentially to the plate; `rs`
    // refuses the same placement.
    for (const Plate &pl : plates) {
        double hMin = Infinity, hMax = -Infinity;
        for (int c = 0; c < 4; ++c) {
            const Vec3 corner = g->origin + g->frame.s * (((c & 1) ? 0.5 : -0.5) * g->width) +
                                g->frame.t * (((c & 2) ? 0.5 : -0.5) * g->height);
            const double h = Dot(corner - pl.origin, pl.n);
            hMin = std::min(hMin, h);
            hMax = std::max(hMax, h);
        }
        const double scale = std::max({g->width, g->height, Length(g->origin - pl.origin)});
        if (std::max(std::abs(hMin), std::abs(hMax)) <= 1e-9 * scale)
            diag.Error(detLoc, "sensor '" + det.name + "' lies in the plane of the aperture plate '" + pl.shape->name +
                                   "', where no diffracted light crosses it; move it in front of the plate (e.g. "
                                   "to_world = translate([0 m 0 m -10 mm]) for a plate at z = 0 facing +z)",
                       {Diagnostic{Severity::Note, Where(pl.shape.get()), "the plate is defined here", {}}});
        else if (hMin < 0 && hMax > 0)
            diag.Error(detLoc, "sensor '" + det.name + "' crosses the plane of the aperture plate '" + pl.shape->name +
                                   "' (its corners are " + Metres(hMin) + " and " + Metres(hMax) +
                                   " from it); place the whole sensor on one side of the plate",
                       {Diagnostic{Severity::Note, Where(pl.shape.get()), "the plate is defined here", {}}});
    }
    if (diag.HasErrors()) return;
    WarnNarrowPixelsNearPlates(*this, diag, plates);
    if (!det.MayAutoAim()) return;

    // Automatic aim (D4b): the one footprint-aware shape entirely in front of the sensor, when
    // every light lies beyond its plane (all light then reaches the sensor through it). Sampling
    // the whole acceptance cone instead puts almost every direction on the opaque plate: zeros
    // with rare spikes.
    std::vector<std::shared_ptr<Shape>> inFront;
    for (const auto &s : shapes_) {
        if (!s->material || !s->material->IsFootprintAware()) continue;
        bool front = true;
        for (const Vec3 &c : AimCorners(*s)) front = front && Dot(c - g->origin, g->frame.n) > 0;
        if (front) inFront.push_back(s);
    }
    if (inFront.empty()) return;
    std::string why;
    if (inFront.size() > 1) {
        why = std::to_string(inFront.size()) + " footprint-aware shapes are in front of it";
    } else {
        const Shape &target = *inFront[0];
        const Plate *pl = nullptr;
        for (const Plate &p : plates)
            if (p.shape.get() == &target) pl = &p;
        const double sensorSide = pl ? Dot(g->origin - pl->origin, pl->n) : 0;
        for (const Light *light : lights_) {
            Vec3 wi;
            double dist = Infinity;
            bool beyond = pl && LightDirection(*light, g->origin, &wi, &dist);
            if (beyond) {
                const double lightSide = std::isfinite(dist) ? Dot(g->origin + wi * dist - pl->origin, pl->n)
                                                             : Dot(wi, pl->n);  // only its sign matters
                beyond = lightSide * sensorSide < 0;
            }
            if (!beyond) {
                why = "light '" + light->name + "' is not beyond '" + target.name + "'";
                break;
            }
        }
        if (why.empty()) {
            det.AimAt(inFront[0]);
            return;
        }
    }
    std::string names;
    for (const auto &s : inFront) names += (names.empty() ? "@" : ", @") + s->name;
    diag.Warning(detLoc, "sensor '" + det.name + "' has no 'aim' and samples its whole acceptance cone (" + why +
                             "); light through an aperture then gives zeros and rare spikes: add aim = " +
                             "@" + inFront[0]->name + " (footprint-aware shapes in front: " + names +
                             "), or auto_aim = false to keep the cone without this warning");
}


std::string Scene::DarkImageCause() const {
    if (lights_.empty()) return "the scene has no light";
    const Detector &det = *detector_;

    // Lights whose spectra lie outside the detector's response (e.g. infrared under cie_xyz).
    const SensorResponse &resp = det.Response();
    std::string unseen;
    int nUnseen = 0;
    for (const Light *l : lights_) {
        const Spectrum &s = l->EmissionSpectrum();
        // The radiometric response is flat; CIE weights vanish outside 360–830 nm (1 nm steps).
        double seen = 0;
        if (auto line = s.LineWavelength()) seen = s.Eval(*line) * resp.Intensity(*line);
        else if (resp.GetKind() == SensorResponse::Kind::Radiometric) seen = s.MaxValue();
        else
            for (double lambda = CieLambdaMin; lambda <= CieLambdaMax && !(seen > 0); lambda += 1e-9)
                seen = s.Eval(lambda) * resp.Intensity(lambda);
        if (seen > 0) continue;
        ++nUnseen;
        if (unseen.empty()) {
            const auto [lo, hi] = s.Support();
            unseen = "light '" + l->name + "' emits " +
                     (s.LineWavelength() ? "at " + Nm(*s.LineWavelength()) : "only within " + Nm(lo) + " – " + Nm(hi));
        }
    }
    if (nUnseen == int(lights_.size()))
        return "no light emits where the detector responds (" + unseen + "; the " + resp.Name() +
               " response covers 360–830 nm): give the light a visible spectrum, or the detector response = "
               "\"radiometric\"";

    // Delta lights the integrator cannot reach (a classical path tracer: only by next-event
    // estimation at surfaces with a continuous lobe).
    if (std::string why = UnreachableDeltaLights(*integrator_, *this); !why.empty()) return why;
    // Aperture plates that transmit nothing.
    for (const Plate &pl : Plates(shapes_))
        if (!(OpeningsOf(*pl.shape->material)->OpenArea() > 0))
            return "the aperture plate '" + pl.shape->name +
                   "' has no open area (no openings, or every opening has transmission 0): open one";

    // A camera inside closed geometry: its rays first meet the inside of a surface.
    int inside = 0, total = 0;
    const Shape *where = nullptr;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            const Vec2 p((i + 0.5) / 16 * det.Width(), (j + 0.5) / 16 * det.Height());
            auto s = det.Generate(p, Vec2(0.5, 0.5));
            if (!s) continue;
            ++total;
            // Inside a closed surface, the ray and its reverse both meet the same surface from the
            // inside (a single plate seen from behind does not count).
            auto hit = accel_->IntersectSurface(s->ray, 0, Infinity);
            if (!hit || !(Dot(s->ray.d, hit->n) > 0) || hit->shape->IsPlanar()) continue;
            auto back = accel_->IntersectSurface(Ray{s->ray.o, -s->ray.d}, 0, Infinity);
            if (back && back->shape == hit->shape && Dot(-s->ray.d, back->n) > 0) {
                ++inside;
                where = hit->shape;
            }
        }
    if (total > 0 && 2 * inside >= total && where)
        return std::to_string(100 * inside / total) + "% of the detector's rays start inside shape '" + where->name +
               "' (they meet its inside first): move detector '" + det.name + "' out of it";

    // A sensor plane that every light reaches only from behind, with nothing in front of it that
    // could send the light back (a mirror, a grating or a screen in front makes the light's side
    // irrelevant; an aperture plate only lets it through).
    const SensorPlaneGeometry *g = det.SensorPlane();
    const bool redirectorInFront = g && std::any_of(shapes_.begin(), shapes_.end(), [&](const auto &s) {
        if (!s->material || s->material->IsFootprintAware()) return false;
        const Bounds3 b = s->Bounds();
        for (int c = 0; c < 8; ++c) {
            const Vec3 p((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
            if (Dot(p - g->origin, g->frame.n) > 0) return true;
        }
        return false;
    });
    if (g && !redirectorInFront) {
        std::string behind;
        int nBehind = 0;
        for (const Light *l : lights_) {
            Vec3 wi;
            double dist;
            if (LightDirection(*l, g->origin, &wi, &dist) && !(Dot(wi, g->frame.n) > 0)) {
                ++nBehind;
                if (behind.empty()) behind = l->name;
            }
        }
        if (nBehind == int(lights_.size()))
            return "no light reaches the front of sensor '" + det.name + "': light '" + behind +
                   "' arrives from behind its plane (the sensor counts light crossing it from its front side, +z "
                   "of its to_world); turn the light or the sensor (a plane wave through a plate must travel "
                   "from the far side of the plate towards the sensor)";
    }
    // Only delta lights, which the integrator reaches only at continuous lobes (`ray`): the
    // detector sees no surface they light.
    const IntegratorSupport support = integrator_->Support();
    if (std::all_of(lights_.begin(), lights_.end(),
                    [&](const Light *l) { return support.Reach(l->Type()) == LightReach::SampledOnly; })) {
        std::string names;
        for (const Light *l : lights_) names += (names.empty() ? "'" : ", '") + l->name + "'";
        return "integrator '" + integrator_->name + "' reaches the delta light" + (lights_.size() > 1 ? "s " : " ") +
               names +
               " only by next-event estimation at surfaces with a continuous lobe, and the detector sees none that "
               "they light (a delta light seen directly, or through a mirror, grating or aperture, is invisible to "
               "it): render with integrator \"grt\", which measures delta lights in closed form at the detector "
               "and through every specular lobe";
    }

    return "no light reached the detector; check that the lights face the scene, that nothing blocks them and "
           "that the detector sees lit surfaces";
}

std::string WorkWarning(double seconds, const std::string &what, const std::string &fix, const std::string &run) {
    if (!(seconds > LongRenderSeconds)) return "";
    char t[32];
    if (seconds < 3600) std::snprintf(t, sizeof t, "%.0f min", seconds / 60);
    else if (seconds < 86400 * 2) std::snprintf(t, sizeof t, "%.1f h", seconds / 3600);
    else std::snprintf(t, sizeof t, "%.3g days", seconds / 86400);
    return "this " + run + " would take about " + t + " (" + what + "), far beyond the usual: " + fix;
}

}  // namespace phasor
