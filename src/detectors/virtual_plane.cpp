// SPDX-License-Identifier: Apache-2.0
// `virtual_plane`: a measurement plane (sensor) of given extent and resolution whose pixels
// report irradiance — the power per unit area crossing the plane from its front side — divided by
// `reference_irradiance` (E_ref, default 1 W/m²; theory §0 D2, D4: set it to the source's
// irradiance and the EXR `intensity` is flux / incident irradiance). The plane is the local z = 0 square of `extent` centred at the origin, front
// normal +z, placed by `to_world`; image x runs along local +x, image y along local −y. One-row
// sensors (N×1) are allowed; `pitch` sets resolution = round(extent/pitch) per axis.
//
// Pixels (D2): every GR starts at its waist on the plane with ρ = 0 and β_D = √2·σ_pix
// (σ_pix = `sigma`, default pitch/√12). "gaussian" pixels centre the GR on the pixel (sensitivity
// N(x; x_p, σ_pix²I)); "box" pixels place it uniformly in the pixel (sensitivity 1_box ⊛ N(0, σ_pix²),
// normalised to an average). The GR's own transverse footprint is isotropic (D1), so its cut of the
// plane is wider by 1/cosθ along the tilt (per-axis footprints are future work).
//
// Directions (D4, D4b): 𝒟 = 1 per unit sensor-plane transverse wavevector d²κ = k²cosθ dω. The GR's
// direction is sampled uniformly in the direction cosines (κ/k) over the acceptance cone of
// half-angle `acceptance` about the normal — or, with `aim = @shape`, over the box spanned by that
// shape's bounding box (an aperture plate: its openings' bounding box) seen from the pixel, widened
// by 5β (as an angle) and 6σ_θ at the longest carried wavelength — stratified
// across the pixel's samples (a rotated lattice when spp is a square). Without `aim` the scene
// aims at the one aperture plate in front of the sensor when every light lies beyond it
// (auto_aim, Scene::Build; the full cone there gives zeros and spikes, as almost every sampled
// direction misses the openings); `auto_aim = false` keeps the full cone. In radiance units the weight
// is the sampled region's area in direction cosines, so the pixel mean is ∫L cosθ dω = irradiance.
// Closed-form sources (plane wave, point, distant, Gaussian beam) are integrated over the directions
// analytically (D4a): E·cosθ_s·(1 − e^{−β²k²})·[fraction of the GR's directions inside the region],
// exact to ~1e-9 where sampling would need ~1e10 samples.
#include <cmath>

#include "core/render/aperture.h"
#include "core/render/detector.h"
#include "core/render/material.h"
#include "core/render/registry.h"

namespace phasor {

class VirtualPlane final : public Detector {
  public:
    struct Config {
        Transform toWorld;
        double width, height, sigma, acceptance;
        double referenceIrradiance = 1;  // E_ref [W/m²]: pixels report flux / E_ref (D4)
        bool gaussianPixel;
        std::shared_ptr<Shape> aim;
        bool autoAim = true;  // Scene::Build may choose `aim` (AimTarget)
    };
    VirtualPlane(int nx, int ny, SensorResponse r, Config c) : Detector(nx, ny, r), c_(std::move(c)) {
        origin_ = c_.toWorld.Point(Vec3(0, 0, 0));
        Vec3 ex = Normalize(c_.toWorld.Vector(Vec3(1, 0, 0))), ey = c_.toWorld.Vector(Vec3(0, 1, 0));
        ey = Normalize(ey - Dot(ey, ex) * ex);
        frame_.s = ex;
        frame_.t = ey;
        frame_.n = Cross(ex, ey);
        pitchX_ = c_.width / nx;
        pitchY_ = c_.height / ny;
        sinAcc_ = std::sin(c_.acceptance);
        beta2_ = 2 * c_.sigma * c_.sigma;
        geom_.origin = origin_;
        geom_.frame = frame_;
        geom_.width = c_.width;
        geom_.height = c_.height;
        geom_.pitchX = pitchX_;
        geom_.pitchY = pitchY_;
        geom_.sigma = c_.sigma;
        geom_.nx = nx;
        geom_.ny = ny;
        geom_.gaussianPixel = c_.gaussianPixel;
        geom_.referenceIrradiance = c_.referenceIrradiance;
        if (c_.aim) aimCorners_ = AimCorners(*c_.aim);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "detector",
            "virtual_plane",
            "Measurement plane whose pixels report irradiance (sensor for wave optics).",
            {P::Transform("to_world",
                          "placement of the plane (local z = 0, front normal +z; default: identity)"),
             P::NumberList("extent", "width and height of the plane", Dim::Length())
                 .Default(
                     Value::List({Value::Number(1e-3, Dim::Length()), Value::Number(1e-3, Dim::Length())}))
                 .Size(2)
                 .Min(0, true),
             P::IntegerList("resolution", "pixels along x and y (give this or 'pitch')").Size(2).Min(1),
             P::Length("pitch", "pixel pitch; resolution = round(extent/pitch) per axis").Min(0, true),
             P::String("pixel",
                       "pixel sensitivity: gaussian (GR centred on the pixel) or box (box ⊛ Gaussian)")
                 .Default(Value::String("gaussian"))
                 .Choices({"gaussian", "box"}),
             P::Length(
                 "sigma",
                 "spatial resolution sigma_pix of a pixel (beta = sqrt(2) sigma); default pitch/sqrt(12)")
                 .Min(0, true),
             P::Angle("acceptance", "half-angle of the acceptance cone about the normal")
                 .Default(Value::Number(Pi / 2, Dim::Angle()))
                 .Min(0, true)
                 .Max(Pi / 2),
             P::Ref("aim", "shape",
                    "sample only directions towards this shape's bounding box, or towards the openings "
                    "of an aperture plate (D4b); default: see auto_aim"),
             P::Bool("auto_aim",
                     "without 'aim': aim at the one aperture plate in front of the sensor when every light "
                     "lies beyond it (else sample the whole acceptance cone, with a warning)")
                 .Default(Value::Bool(true)),
             P::Number("reference_irradiance",
                       "pixels report flux per unit area divided by this (E_ref, theory D4; set it to the "
                       "source's irradiance for flux / incident irradiance)",
                       Dim::Irradiance())
                 .Default(Value::Number(1, Dim::Irradiance()))
                 // [1e-30, 1e30] W/m², like the lights' strengths (MaxLightStrength, light.h):
                 // 1e-30 W/m² is less than one visible photon per m² per millennium, and pixels
                 // are E/E_ref, so a smaller E_ref would only overflow.
                 .Min(1e-30)
                 .Max(1e30),
             ResponseParam("radiometric"), PolarizationParams()[0], PolarizationParams()[1]}};
        return s;
    }
    static std::unique_ptr<Detector> Create(const ParamDict &d, BuildContext &ctx) {
        std::vector<double> ext = d.GetNumbers("extent");
        int nx = 0, ny = 0;
        if (d.Has("resolution") && d.Has("pitch"))
            throw Error(d.Loc("pitch"), "give either 'resolution' or 'pitch', not both");
        if (!d.Has("resolution") && !d.Has("pitch"))
            throw Error(d.EntityLoc(), "virtual_plane needs 'resolution' (pixels along x and y) or 'pitch' "
                                       "(resolution = round(extent/pitch)); it has neither");
        if (d.Has("pitch")) {
            const double p = d.GetNumber("pitch");
            // A pitch equal to the extent is a one-pixel axis (a one-row sensor); a larger one is
            // a mistake that would silently give one pixel of the wrong size.
            for (int a = 0; a < 2; ++a)
                if (p > ext[a] * (1 + 1e-9))
                    throw Error(d.Loc("pitch"), "'pitch' (" + Value::Number(p, Dim::Length()).ToString() +
                                                    ") is larger than the extent along " + (a ? "y" : "x") + " (" +
                                                    Value::Number(ext[a], Dim::Length()).ToString() +
                                                    "); give a pitch <= the extent, or a larger 'extent'");
            const double fx = std::round(ext[0] / p), fy = std::round(ext[1] / p);
            if (fx > 65536 || fy > 65536)
                throw Error(d.Loc("pitch"), "'pitch' gives more than 65536 pixels along an axis");
            nx = std::max(1, int(fx));
            ny = std::max(1, int(fy));
        } else if (d.Has("resolution")) {
            std::vector<int> res = d.GetInts("resolution");
            nx = res[0];
            ny = res[1];
        }
        if (nx > 65536 || ny > 65536 || (long long)nx * ny > (1LL << 28))
            throw Error(d.Loc(d.Has("pitch") ? "pitch" : "resolution"), "resolution is too large");
        Config c;
        c.toWorld = ctx.GetTransform(d, "to_world");
        c.width = ext[0];
        c.height = ext[1];
        c.sigma =
            d.Has("sigma") ? d.GetNumber("sigma") : std::min(ext[0] / nx, ext[1] / ny) / std::sqrt(12.0);
        c.acceptance = d.GetNumber("acceptance");
        c.gaussianPixel = d.GetString("pixel") == "gaussian";
        if (d.Has("aim")) c.aim = ctx.GetRef<Shape>(d, "aim");
        c.autoAim = d.GetBool("auto_aim");
        c.referenceIrradiance = d.GetNumber("reference_irradiance");
        auto plane = std::make_unique<VirtualPlane>(nx, ny, ResponseFromParams(d), std::move(c));
        plane->SetPolarization(PolarizationFromParams(d));
        return plane;
    }

    /// World position for continuous image coordinates pFilm (pixel units).
    Vec3 PlanePoint(Vec2 pFilm) const {
        if (c_.gaussianPixel) pFilm = Vec2(std::floor(pFilm.x) + 0.5, std::floor(pFilm.y) + 0.5);
        const double lx = -0.5 * c_.width + pFilm.x * pitchX_, ly = 0.5 * c_.height - pFilm.y * pitchY_;
        return origin_ + frame_.s * lx + frame_.t * ly;
    }

    /// The sampled region in direction cosines (u = (d·s, d·t)) for a GR at p: [lo, hi].
    /// maxLambda: the longest wavelength the GR carries (sets the 6σ_θ margin).
    void Region(const Vec3 &p, double maxLambda, Vec2 *lo, Vec2 *hi) const {
        *lo = Vec2(-sinAcc_, -sinAcc_);
        *hi = Vec2(sinAcc_, sinAcc_);
        if (!c_.aim) return;
        Vec2 alo(Infinity, Infinity), ahi(-Infinity, -Infinity);
        double minDist = Infinity;
        for (const Vec3 &corner : aimCorners_) {
            const Vec3 l = frame_.ToLocal(corner - p);
            const double dist = Length(l);
            if (!(l.z > 1e-9 * dist)) return;  // the box reaches behind the plane: keep the full cone
            const Vec2 u(l.x / dist, l.y / dist);
            alo = Vec2(std::min(alo.x, u.x), std::min(alo.y, u.y));
            ahi = Vec2(std::max(ahi.x, u.x), std::max(ahi.y, u.y));
            minDist = std::min(minDist, dist);
        }
        // Widen by 5β (seen from the nearest corner) and 6σ_θ at the longest wavelength carried
        // (σ_θ = 1/(2σ_pix k) grows with λ).
        const double margin = 5 * std::sqrt(beta2_) / minDist + 6 * AngularSigma(maxLambda);
        lo->x = std::max(lo->x, alo.x - margin);
        lo->y = std::max(lo->y, alo.y - margin);
        hi->x = std::min(hi->x, ahi.x + margin);
        hi->y = std::min(hi->y, ahi.y + margin);
    }
    double AngularSigma(double lambda) const { return 1 / (2 * c_.sigma * (2 * Pi / lambda)); }
    /// Classical rays carry no wavelength here: 2 µm covers the bands phasor samples in practice.
    static constexpr double ClassicalMaxLambda = 2e-6;

    /// Direction from a sample u ∈ [0,1)² over [lo, hi]; nullopt outside the cone.
    std::optional<Vec3> Direction(const Vec2 &u, const Vec2 &lo, const Vec2 &hi) const {
        const double ux = lo.x + u.x * (hi.x - lo.x), uy = lo.y + u.y * (hi.y - lo.y);
        const double r2 = ux * ux + uy * uy;
        if (!(r2 < sinAcc_ * sinAcc_) || !(r2 < 1)) return std::nullopt;
        return frame_.ToWorld(Vec3(ux, uy, std::sqrt(1 - r2)));
    }

    std::optional<DetectorSample> Generate(const Vec2 &pFilm, const Vec2 &uDir) const override {
        const Vec3 p = PlanePoint(pFilm);
        Vec2 lo, hi;
        Region(p, ClassicalMaxLambda, &lo, &hi);
        if (!(hi.x > lo.x && hi.y > lo.y)) return std::nullopt;
        auto d = Direction(uDir, lo, hi);
        if (!d) return std::nullopt;
        return DetectorSample{Ray{p, *d}, (hi.x - lo.x) * (hi.y - lo.y) / c_.referenceIrradiance};
    }

    bool SupportsGR() const override { return true; }
    /// Image x: the plane's local x axis (light arriving from the front sees y = image down).
    Vec3 PolarizationX(const DetectorGrSample &) const override { return frame_.s; }
    bool StratifiesAcrossSamples() const override { return true; }  // StratifiedPixelSample
    std::optional<DetectorGrSample> GenerateGR(int x, int y, const PixelSampleIndex &si, Sampler &sampler,
                                               const SampledWavelengths &wl) const override {
        const Vec2 uPixel = sampler.GetPixel2D();
        const Vec2 uDir = StratifiedPixelSample(x, y, si, sampler);
        DetectorGrSample s;
        s.ray.o = PlanePoint(Vec2(x, y) + uPixel);
        s.integratesIncidence = true;
        for (int i = 0; i < wl.Count(); ++i) {
            s.beta2[i] = beta2_;
            s.rho[i] = 0;
            s.maxLambda = std::max(s.maxLambda, wl.lambda[i]);
        }
        Vec2 lo, hi;
        Region(s.ray.o, s.maxLambda, &lo, &hi);
        auto d = hi.x > lo.x && hi.y > lo.y ? Direction(uDir, lo, hi) : std::nullopt;
        // Outside the cone the sample still carries the analytic part (D4a): weight 0, any direction.
        s.ray.d = d ? *d : frame_.n;
        s.weight = d ? (hi.x - lo.x) * (hi.y - lo.y) / c_.referenceIrradiance : 0;
        return s;
    }

    SampledSpectrum IntegrateIncidence(const DetectorGrSample &s, const GrIncidence &inc) const override {
        const double cosTheta = Dot(inc.wi, frame_.n);
        if (!(cosTheta > 0)) return SampledSpectrum(0.0);  // arrives from behind
        // Fraction of the GR's directions (a Gaussian about the source direction) that the sampled
        // region keeps: the cone (a disc in direction cosines) and, with `aim`, the box.
        const Vec2 us(Dot(inc.wi, frame_.s), Dot(inc.wi, frame_.t));
        const double sigma = std::sqrt(inc.angularVariance);
        double frac = c_.acceptance >= Pi / 2 ? 1.0 : DiscGaussianProbability(Length(us), sinAcc_, sigma);
        if (c_.aim) {
            Vec2 lo, hi;
            Region(s.ray.o, s.maxLambda, &lo, &hi);
            frac *= RectGaussianProbability(us, sigma, lo, hi);
        }
        return inc.irradiance * (cosTheta * frac / c_.referenceIrradiance);
    }

    const SensorPlaneGeometry *SensorPlane() const override { return &geom_; }
    const Shape *AimTarget() const override { return c_.aim.get(); }
    bool MayAutoAim() const override { return c_.autoAim && !c_.aim; }
    void AimAt(std::shared_ptr<Shape> shape) override {
        c_.aim = std::move(shape);
        aimCorners_ = c_.aim ? AimCorners(*c_.aim) : std::vector<Vec3>{};
    }

    std::string ToString() const override {
        return "virtual_plane { resolution = [" + std::to_string(Width()) + " " + std::to_string(Height()) +
               "], extent = [" + std::to_string(c_.width) + " " + std::to_string(c_.height) +
               "] m, sigma = " + std::to_string(c_.sigma) +
               " m, pixel = " + (c_.gaussianPixel ? "gaussian" : "box") + " }";
    }

  private:
    Config c_;
    Vec3 origin_;
    Frame frame_;
    double pitchX_, pitchY_, sinAcc_, beta2_;
    SensorPlaneGeometry geom_;
    std::vector<Vec3> aimCorners_;  // AimCorners(*c_.aim), empty without `aim`
};

PHASOR_EXPORT_PLUGIN(Detector, VirtualPlane)

}  // namespace phasor
