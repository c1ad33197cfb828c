// SPDX-License-Identifier: Apache-2.0
// `perspective`: a pinhole camera. Pixels report radiance (theory §0 D4).
// Camera frame from `to_world` (e.g. lookat): +z is the viewing direction, +y is up; image x
// grows to the right, image y downwards. `fov` spans the shorter image side.
//
// Generalized rays (theory §0 D2, §1.4): ρ = 0 at the pinhole and β = 1/(√2·k·σ_θ), σ_θ = the
// pixel angle/√12 (equal second moment with the pixel's box), so the GR's angular spread is the
// pixel's. `pixel` chooses the sensitivity: "box" jitters the mean ray uniformly over the pixel (the
// classical camera; with a GR the sensitivity is box ⊛ N(0, σ_θ²), about a pixel of blur), while
// "gaussian" centres the GR on the pixel (𝒟 = δ at the centre, sensitivity N(0, σ_θ²) — deterministic
// for closed-form measurements, and a pixel-centre ray for the `ray` integrator). The pixel angle is
// the one at the image centre.
#include <cmath>

#include "core/render/detector.h"
#include "core/render/registry.h"

namespace phasor {

class PerspectiveCamera final : public Detector {
  public:
    PerspectiveCamera(int w, int h, SensorResponse r, Transform toWorld, double fov, bool gaussianPixel)
        : Detector(w, h, r), toWorld_(toWorld), gaussianPixel_(gaussianPixel) {
        // Half-extent of the image plane at unit distance along the shorter side.
        double half = std::tan(0.5 * fov);
        scale_ = 2 * half / std::min(w, h);
        sigmaTheta_ = scale_ / std::sqrt(12.0);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "detector",
            "perspective",
            "Pinhole camera; pixels report radiance.",
            CameraParams()};
        return s;
    }
    static std::unique_ptr<Detector> Create(const ParamDict &d, BuildContext &ctx) {
        auto [w, h] = CameraResolution(d);
        auto cam = std::make_unique<PerspectiveCamera>(w, h, CameraResponse(d, ctx), ctx.GetTransform(d, "to_world"),
                                                       d.GetNumber("fov"), d.GetString("pixel") == "gaussian");
        cam->SetPolarization(PolarizationFromParams(d));
        return cam;
    }

    Ray RayThrough(Vec2 pFilm) const {
        if (gaussianPixel_) pFilm = Vec2(std::floor(pFilm.x) + 0.5, std::floor(pFilm.y) + 0.5);
        // Screen offsets: right and up on the image plane at unit distance. With a right-handed
        // lookat frame (x = up × forward), screen-right is −x.
        double sx = (pFilm.x - 0.5 * Width()) * scale_;
        double sy = (0.5 * Height() - pFilm.y) * scale_;
        Vec3 dCam(-sx, sy, 1);
        Vec3 d = Normalize(toWorld_.Vector(dCam));
        return Ray{toWorld_.Point(Vec3(0, 0, 0)), d};
    }
    std::optional<DetectorSample> Generate(const Vec2 &pFilm, const Vec2 &) const override {
        return DetectorSample{RayThrough(pFilm), 1.0};
    }

    bool SupportsGR() const override { return true; }
    /// Image right: camera −x (screen-right, RayThrough).
    Vec3 PolarizationX(const DetectorGrSample &) const override { return Normalize(toWorld_.Vector(Vec3(-1, 0, 0))); }
    std::optional<DetectorGrSample> GenerateGR(int x, int y, const PixelSampleIndex &, Sampler &sampler,
                                               const SampledWavelengths &wl) const override {
        const Vec2 u = sampler.GetPixel2D();
        DetectorGrSample s;
        s.ray = RayThrough(Vec2(x, y) + u);
        s.weight = 1;
        // Theory §0 D2: β = 1/(√2 k σ_θ), ρ = 0 at the pinhole (per wavelength; in vacuum).
        for (int i = 0; i < wl.Count(); ++i) {
            const double k = 2 * Pi / wl.lambda[i];
            s.beta2[i] = 1 / (2 * k * k * sigmaTheta_ * sigmaTheta_);
            s.rho[i] = 0;
        }
        return s;
    }

    std::string ToString() const override {
        return "perspective { resolution = [" + std::to_string(Width()) + " " + std::to_string(Height()) +
               "], pixel = " + (gaussianPixel_ ? "gaussian" : "box") + " }";
    }

  private:
    Transform toWorld_;
    double scale_, sigmaTheta_;
    bool gaussianPixel_;
};

PHASOR_EXPORT_PLUGIN(Detector, PerspectiveCamera)

}  // namespace phasor
