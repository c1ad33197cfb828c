// SPDX-License-Identifier: Apache-2.0
// `thin_lens`: a camera with a thin lens of radius `aperture_radius` focused at `focus_distance`
// (depth of field). Pixels report radiance (theory §0 D4). Same frame and `fov` convention as
// `perspective`; rays start on the lens disc (camera z = 0) and pass through the pixel's point on
// the plane of focus (camera z = focus_distance).
//
// Generalized rays (theory §0 D2): the pixel's waist is imaged onto the plane of focus. The pixel's
// footprint there has the std σ_θ·d_f (σ_θ = pixel angle/√12, d_f = focus distance), so the GR has
// ρ = 0 and β_f = √2·σ_θ·d_f at the focus point; on the lens it is that waist propagated back
// (ABCD, theory §1.6), i.e. it converges towards the plane of focus. `pixel` = box | gaussian as for
// `perspective`.
#include <cmath>

#include "core/render/detector.h"
#include "core/render/registry.h"
#include "core/render/sampling.h"

namespace phasor {

class ThinLensCamera final : public Detector {
  public:
    ThinLensCamera(int w, int h, SensorResponse r, Transform toWorld, double fov, double radius, double focus,
                   bool gaussianPixel)
        : Detector(w, h, r),
          toWorld_(toWorld),
          radius_(radius),
          focus_(focus),
          gaussianPixel_(gaussianPixel) {
        scale_ = 2 * std::tan(0.5 * fov) / std::min(w, h);
        sigmaTheta_ = scale_ / std::sqrt(12.0);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "detector",
            "thin_lens",
            "Thin-lens camera with depth of field; pixels report radiance.",
            CameraParams({P::Length("aperture_radius", "radius of the lens")
                              .Default(Value::Number(0.01, Dim::Length()))
                              .Min(0),
                          P::Length("focus_distance", "distance of the plane of focus along the view axis")
                              .Default(Value::Number(1, Dim::Length()))
                              .Min(0, true)})};
        return s;
    }
    static std::unique_ptr<Detector> Create(const ParamDict &d, BuildContext &ctx) {
        auto [w, h] = CameraResolution(d);
        auto cam = std::make_unique<ThinLensCamera>(w, h, CameraResponse(d, ctx), ctx.GetTransform(d, "to_world"),
                                                    d.GetNumber("fov"), d.GetNumber("aperture_radius"),
                                                    d.GetNumber("focus_distance"), d.GetString("pixel") == "gaussian");
        cam->SetPolarization(PolarizationFromParams(d));
        cam->SetExposure(CameraExposure(d));
        return cam;
    }

    // Lens point and focus point in camera space for film position pFilm and lens sample uLens.
    std::pair<Vec3, Vec3> LensAndFocus(Vec2 pFilm, const Vec2 &uLens) const {
        if (gaussianPixel_) pFilm = Vec2(std::floor(pFilm.x) + 0.5, std::floor(pFilm.y) + 0.5);
        const double sx = (pFilm.x - 0.5 * Width()) * scale_, sy = (0.5 * Height() - pFilm.y) * scale_;
        const Vec3 focusPoint = Vec3(-sx, sy, 1) * focus_;
        const Vec2 l = ConcentricDisc(uLens) * radius_;
        return {Vec3(l.x, l.y, 0), focusPoint};
    }
    std::optional<DetectorSample> Generate(const Vec2 &pFilm, const Vec2 &uLens) const override {
        auto [lens, focus] = LensAndFocus(pFilm, uLens);
        const Vec3 o = toWorld_.Point(lens);
        return DetectorSample{Ray{o, Normalize(toWorld_.Point(focus) - o)}, 1.0};
    }

    bool SupportsGR() const override { return true; }
    /// Image right: camera −x (see perspective.cpp).
    Vec3 PolarizationX(const DetectorGrSample &) const override { return Normalize(toWorld_.Vector(Vec3(-1, 0, 0))); }
    std::optional<DetectorGrSample> GenerateGR(int x, int y, const PixelSampleIndex &, Sampler &sampler,
                                               const SampledWavelengths &wl) const override {
        const Vec2 uPixel = sampler.GetPixel2D();
        auto [lens, focus] = LensAndFocus(Vec2(x, y) + uPixel, sampler.Get2D());
        DetectorGrSample s;
        const Vec3 o = toWorld_.Point(lens), f = toWorld_.Point(focus);
        const double dist = Length(f - o);
        s.ray = Ray{o, (f - o) / dist};
        // Waist β_f = √2 σ_θ d_f at the focus point, carried back to the lens (theory §1.6).
        const double waist2 = 2 * Sqr(sigmaTheta_ * focus_);
        for (int i = 0; i < wl.Count(); ++i) {
            GenRay g{f, s.ray.d, 2 * Pi / wl.lambda[i], waist2, 0};
            g.Propagate(-dist);
            s.beta2[i] = g.beta2;
            s.rho[i] = g.rho;
        }
        return s;
    }

    std::string ToString() const override {
        return "thin_lens { resolution = [" + std::to_string(Width()) + " " + std::to_string(Height()) +
               "], aperture_radius = " + std::to_string(radius_) +
               " m, focus_distance = " + std::to_string(focus_) + " m }";
    }

  private:
    Transform toWorld_;
    double radius_, focus_, scale_, sigmaTheta_;
    bool gaussianPixel_;
};

PHASOR_EXPORT_PLUGIN(Detector, ThinLensCamera)

}  // namespace phasor
