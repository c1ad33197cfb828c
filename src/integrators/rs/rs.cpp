// SPDX-License-Identifier: Apache-2.0
// `rs`: the forward Rayleigh–Sommerfeld reference (theory §6.2, §9; docs/rs.md). Coherent,
// monochromatic sources — any light with a field (Light::Coherent, core/render/coherent_source.h)
// and a line spectrum: `plane_wave` at any incidence, `point`, `gaussian_beam` (its exact paraxial
// TEM₀₀ field, with the waist anywhere) — shine on ONE planar aperture plate — the scene's only shape, whose
// material has openings (Material::Openings, e.g. `aperture`) — and the scalar field behind it is
// computed in double precision on the `virtual_plane` sensor:
//   Kirchhoff boundary values U₀ = t·U_inc on the openings (the plate is infinite and opaque
//   elsewhere), RS of the first kind
//     U(r) = (1/2π) ∫∫ U₀(r') (z/R)(1/R − ik) e^{ikR}/R dA'                              (3-D)
//     U(x, z) = (ikz/2) ∫ U₀(x') H₁⁽¹⁾(kR)/R dx'                                          (2-D)
//   and ∇U from the analytic derivative of the same kernels. Amplitude convention: |U_inc|² =
//   irradiance normal to the direction of travel. Pixels report FLUX through the sensor plane per
//   unit area, F = −Im(U*·∂U/∂n_s)/k (n_s = front normal; S = Im(U*∇U)/k), integrated against
//   the pixel sensitivity of theory §0 D2 (Gaussian N(0, σ²I) or box ⊛ Gaussian) and divided by
//   the sensor's reference irradiance. Several lights add incoherently (intensities add).
//   In the double-slit set-up F differs from |U|² by 2.8e-5 of peak (measured in rs_test.cpp).
//
// Every check of the scene runs at load (Validate: the declarations of Support, then Plan), so
// `phasor check` refuses what Render would.
// The integrator's files (docs/rs.md §1): this one checks the scene and drives the rest —
//  * rs/propagator.{h,cpp}: the field U and ∇U at a point, by Gauss–Legendre panels over the
//    openings (3-D, or 2-D with Hankel functions);
//  * rs/sensor_quadrature.{h,cpp}: the grid of field points on the sensor and the pixel sums;
//  * rs/slit_end_error.{h,cpp}: the error of treating finite slits as infinite, which picks the
//    mode.
// `accuracy` (default 1e-4 of peak) sets the quadrature tolerances (QuadratureRule::ForAccuracy).
// 2-D mode (`mode = "2d"`, or `auto` when every opening is a rectangle with one common v range,
// the light is a plane wave with no component along v, a sensor axis is parallel to the slits,
// and SlitEndError predicts at most `auto_2d_tolerance`): the field is constant along the slits,
// so that grid axis collapses to one node.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>

#include <tbb/global_control.h>

#include "core/render/coherent_source.h"
#include "core/render/integrator.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/render/scene.h"
#include "core/render/work.h"
#include "integrators/rs/propagator.h"
#include "integrators/rs/sensor_quadrature.h"
#include "integrators/rs/slit_end_error.h"

namespace phasor {

// ---- The integrator ---------------------------------------------------------------------------------

class RsIntegrator final : public Integrator {
  public:
    enum class Mode { Auto, TwoD, ThreeD };
    RsIntegrator(Mode mode, double auto2dTolerance, double accuracy)
        : mode_(mode), auto2dTolerance_(auto2dTolerance), accuracy_(accuracy) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "integrator",
            "rs",
            "Forward Rayleigh-Sommerfeld reference: coherent plane waves / point sources through one "
            "aperture plate onto a virtual_plane (double precision, pixel-integrated flux).",
            {P::String("mode",
                       "2d: slits infinite along the plate's y axis; 3d: full surface integral; auto: 2d "
                       "where it applies (slits, a plane wave without a y component, a sensor axis along "
                       "the slits) and the slit ends' predicted effect is within auto_2d_tolerance")
                 .Default(Value::String("auto"))
                 .Choices({"auto", "2d", "3d"}),
             P::Number("auto_2d_tolerance",
                       "largest predicted error (relative to the local intensity) of ignoring the slit ends "
                       "that `auto` accepts for the 2-D mode")
                 .Default(Value::Number(2e-4))
                 .Min(0),
             P::Number("accuracy",
                       "target accuracy of the quadratures: largest pixel error relative to the row's peak "
                       "(sets the Gauss-Legendre node rule and the sensor grid; docs/rs.md)")
                 .Default(Value::Number(1e-4))
                 .Min(1e-12)
                 .Max(0.1)}};
        return s;
    }
    static std::unique_ptr<Integrator> Create(const ParamDict &d, BuildContext &) {
        const std::string m = d.GetString("mode");
        const Mode mode = m == "2d" ? Mode::TwoD : (m == "3d" ? Mode::ThreeD : Mode::Auto);
        return std::make_unique<RsIntegrator>(mode, d.GetNumber("auto_2d_tolerance"), d.GetNumber("accuracy"));
    }
    /// The integrator contract cases `rs` supports (tests/integrators/integrator_contract_test.cpp):
    /// only coherent sources through one aperture plate onto a virtual_plane (docs/rs.md §1), so
    /// no furnace, area light, camera, Cornell box or plate-free sensor. Not a point source through
    /// an open plate either: open to 1e-3 for a spherical wave it is hundreds of Fresnel zones wide,
    /// a 3-D integral of ~5e9 kernel evaluations (minutes); the 2-D mode takes plane waves only.
    static std::vector<std::string> ContractCases() { return {"plane_wave_open_plate"}; }

    /// Coherent lights with a field, a sensor plane, one aperture plate (integrator_support.h).
    IntegratorSupport Support() const override {
        IntegratorSupport s;
        s.lights = {LightReach::Field, LightReach::Field, LightReach::Refused, LightReach::Refused};
        s.detector = DetectorNeed::SensorPlane;
        s.kernels = {KernelReach::Refused, KernelReach::Refused, KernelReach::OpeningsOnly};
        return s;
    }

    /// The declarations (ValidateSupport), then the set-up Render makes: one planar plate, the
    /// sensor in front of it, every light on its far side, the mode, the field grid.
    void Validate(const Scene &scene, Diagnostics &diag) const override {
        const std::size_t before = diag.ErrorCount();
        ValidateSupport(*this, scene, diag);
        if (diag.ErrorCount() > before) return;
        try {
            Plan(scene);
        } catch (const Error &e) {
            diag.Report(e);
        }
    }

    RenderStats Render(const Scene &scene, Film &film, const RenderOptions &opt) const override {
        const auto start = std::chrono::steady_clock::now();
        std::unique_ptr<tbb::global_control> threads;
        if (opt.threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            opt.threads);
        const RsPlan plan = Plan(scene);
        const SensorPlaneGeometry *sensor = plan.sensor;
        const std::vector<Job> &jobs = plan.jobs;
        const int totalUnits = plan.totalUnits;

        // Work estimate before the long part: a few field evaluations timed (≤ ~0.5 s per light)
        // times the grid's nodes, on all threads.
        if (opt.warn) {
            double seconds = 0, nodes = 0, perNode = 0;
            for (const Job &job : jobs) {
                const rs::SensorGrid &gr = job.grid;
                const auto t0 = std::chrono::steady_clock::now();
                double elapsed = 0, sink = 0;
                int n = 0;
                for (; n < 8 && (n == 0 || elapsed < 0.5); ++n) {
                    const double x = gr.xs[(n * gr.xs.size()) / 8], y = gr.ys[(n * gr.ys.size()) / 8];
                    sink += job.prop->Flux(sensor->origin + sensor->frame.s * x + sensor->frame.t * y, sensor->frame.n);
                    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                }
                (void)sink;
                nodes += double(gr.Nodes());
                perNode = std::max(perNode, elapsed / n);
                seconds += elapsed / n * double(gr.Nodes());
            }
            const int threads =
                opt.threads > 0 ? opt.threads : int(std::max(1u, std::thread::hardware_concurrency()));
            char what[160];
            std::snprintf(what, sizeof what, "%.3g field nodes on the sensor grid at %.3g ms each on %d threads",
                          nodes, perNode * 1e3, threads);
            const std::string msg =
                WorkWarning(seconds / threads, what,
                            "the sensor grid and the quadrature over the openings follow the wavelength; a "
                            "longer wavelength (the light's spectrum, e.g. the scene's `lambda`), a smaller sensor "
                            "'extent', shorter openings or mode = \"2d\" for long slits reduce it");
            if (!msg.empty()) opt.warn(msg);
        }

        // ---- Field and pixel integrals, one light at a time (intensities add) ------------------
        RenderStats stats;
        const int nx = sensor->nx, ny = sensor->ny;
        std::size_t fieldPoints = 0;
        std::string modes;
        for (const Job &job : jobs) {
            fieldPoints += job.grid.Nodes();
            const std::string m = job.prop->TwoD() ? "2d" : "3d";
            if (modes.find(m) == std::string::npos) modes += (modes.empty() ? "" : ",") + m;
        }
        std::vector<Vec3> channels(std::size_t(nx) * ny);
        std::vector<double> intensity(std::size_t(nx) * ny, 0.0);
        int unitsDone = 0;
        const double eRef = sensor->referenceIrradiance > 0 ? sensor->referenceIrradiance : 1.0;
        for (const Job &job : jobs) {
            const int base = unitsDone;
            auto onBatch = [&](int done) {
                unitsDone = base + done;
                if (opt.progress) opt.progress(unitsDone, totalUnits);
                return true;
            };
            std::vector<double> flux =
                rs::IntegrateSensor(*sensor, *job.prop, job.grid, rs::Quantity::Flux, onBatch, opt.cancel, opt.work);
            // A helper process (MPI) computes its share of every light's field; the pixels are summed
            // on the coordinating one.
            const bool helper = opt.work && !opt.work->Coordinates();
            if (helper && !(opt.cancel && opt.cancel->load())) continue;
            if (flux.empty()) {
                // Every pixel needs the field over its whole window, so a partial field gives no
                // honest pixel: nothing is written (docs/rs.md "Cancellation").
                stats.cancelled = true;
                stats.hasImage = false;
                stats.work = "stopped after " + std::to_string(unitsDone) + " of " + std::to_string(totalUnits) +
                             " steps of its field integral";
                stats.seconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                return stats;
            }
            const SensorResponse::Weights w = film.Response().At(job.lambda);
            for (std::size_t p = 0; p < flux.size(); ++p) {
                const double v = flux[p] / eRef;
                channels[p] += w.channels * v;
                intensity[p] += w.intensity * v;
            }
        }
        if (opt.work && !opt.work->Coordinates()) {
            stats.hasImage = false;
            return stats;
        }
        // Round-off can leave tiny negative sums in dark pixels: those are clamped to 0. A pixel
        // more negative than round-off, or one the film cannot hold (NaN, beyond float), is an
        // invalid sample (counted, written as 0).
        double peak = 0;
        for (double v : intensity) peak = std::max(peak, v);
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const std::size_t p = std::size_t(j) * nx + i;
                Vec3 c = channels[p];
                double v = intensity[p];
                if (v < -1e-9 * peak) {
                    film.AddInvalidSample(i, j);
                    continue;
                }
                c = Vec3(std::max(c.x, 0.0), std::max(c.y, 0.0), std::max(c.z, 0.0));
                film.AddReduced(i, j, c, std::max(v, 0.0));
            }
        // rs evaluates the field deterministically on a grid and integrates it over each pixel: it
        // takes no samples, so it reports its own work, never an spp.
        stats.work = "solved " + std::to_string(std::size_t(nx) * ny) + " pixels (" + std::to_string(nx) + "x" +
                     std::to_string(ny) + ", " + modes + ") from " + std::to_string(fieldPoints) +
                     " field points";
        stats.metadata["phasor:rs_field_points"] = std::to_string(fieldPoints);
        stats.metadata["phasor:rs_mode"] = modes;
        stats.invalidSamples = film.InvalidSampleCount();
        stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return stats;
    }

    /// One light's field on the sensor: its propagator and the grid of field points.
    struct Job {
        const Light *light;
        double lambda;
        std::unique_ptr<rs::Propagator> prop;
        rs::SensorGrid grid;
    };
    struct RsPlan {
        const SensorPlaneGeometry *sensor = nullptr;
        std::vector<Job> jobs;
        int totalUnits = 0;
    };

    /// Everything Render needs before the field integral, checked: throws a phasor::Error located at
    /// the object at fault (Validate reports it at load). Assumes the declarations hold (a sensor
    /// plane, coherent lights with line spectra).
    RsPlan Plan(const Scene &scene) const {
        RsPlan plan;
        const Detector &det = scene.GetDetector();
        const SensorPlaneGeometry *sensor = det.SensorPlane();
        plan.sensor = sensor;
        if (scene.Lights().empty())
            throw Error(scene.Where(this), "integrator 'rs' needs at least one coherent light; the scene has none");
        const auto &shapes = scene.Shapes();
        if (shapes.empty())
            throw Error(
                scene.Where(this),
                "integrator 'rs' needs exactly one shape, a planar aperture plate (material with openings, "
                "e.g. 'aperture') between the source and the sensor; the scene has none");
        if (shapes.size() > 1) {
            std::string names;
            for (std::size_t i = 0; i < shapes.size() && i < 6; ++i)
                names += (i ? ", '" : "'") + shapes[i]->name + "'";
            throw Error(
                scene.Where(shapes[1].get()),
                "integrator 'rs' handles exactly one planar aperture plate between source and sensor; the "
                "scene has " +
                std::to_string(shapes.size()) + " shapes (" + names + (shapes.size() > 6 ? ", …" : "") + ")");
        }
        const Shape &shape = *shapes[0];
        const ApertureMask *mask = shape.material ? OpeningsOf(*shape.material) : nullptr;
        if (!mask)
            throw Error(scene.Where(&shape), "integrator 'rs' needs an aperture plate: shape '" + shape.name +
                        "' has no material with openings (use the 'aperture' material)");
        if (!shape.IsPlanar())
            throw Error(scene.Where(&shape), "integrator 'rs': the aperture plate '" + shape.name + "' is not planar");
        PlateFrame plate;
        try {
            plate = PlateFrame::FromTransform(shape.objectToWorld);
        } catch (const Error &e) {
            throw Error(scene.Where(&shape), "aperture plate '" + shape.name + "': " + e.Message());
        }

        // Sensor side: the whole evaluation window must lie strictly on one side, ≥ 1 λ away.
        const double extX = 6 * sensor->sigma + 0.5 * sensor->pitchX,
                     extY = 6 * sensor->sigma + 0.5 * sensor->pitchY;
        const Vec2 c00 = sensor->PixelCenter(0, 0), c11 = sensor->PixelCenter(sensor->nx - 1, sensor->ny - 1);
        double hMin = Infinity, hMax = -Infinity;
        for (int c = 0; c < 4; ++c) {
            const double x = (c & 1) ? c11.x + extX : c00.x - extX, y = (c & 2) ? c00.y + extY : c11.y - extY;
            const double h =
                Dot(sensor->origin + sensor->frame.s * x + sensor->frame.t * y - plate.origin, plate.n);
            hMin = std::min(hMin, h);
            hMax = std::max(hMax, h);
        }
        if (!(hMin > 0) && !(hMax < 0))
            throw Error(scene.Where(&det), "sensor '" + det.name + "' is not in front of the aperture plate '" + shape.name +
                        "': it reaches the plate's plane");
        const bool flip = hMax < 0;
        const Vec3 towardsSensor = flip ? -plate.n : plate.n;
        if (!(Dot(sensor->frame.n, towardsSensor) < 0))
            throw Error(scene.Where(&det), "sensor '" + det.name + "' is not in front of the aperture plate '" + shape.name +
                        "': its front side (+z) faces away from the plate");

        for (const Light *light : scene.Lights()) {
            const CoherentSource &source = *light->Coherent();
            const double lambda = *light->EmissionSpectrum().LineWavelength();
            const double minHeight = std::min(std::abs(hMin), std::abs(hMax));
            if (minHeight < lambda)
                throw Error(scene.Where(&det), "sensor '" + det.name +
                            "' is closer than one wavelength to the aperture plate '" + shape.name +
                            "' (Kirchhoff boundary values need a distant sensor)");
            const double towards = Dot(source.Travel(plate.origin, lambda), towardsSensor);
            if (std::abs(towards) < 1e-6)
                throw Error(scene.Where(light), "light '" + light->name + "' travels parallel to the aperture plate '" +
                                                    shape.name + "' (rs propagates from the source through the plate)");
            if (!(towards > 0))
                throw Error(scene.Where(light), "light '" + light->name + "' and sensor '" + det.name +
                            "' are on the same side of the aperture plate '" + shape.name +
                            "' (rs propagates from the source through the plate to the sensor)");
            const bool twoD = Choose2d(scene, *mask, plate, source, lambda, *sensor, light->name);
            Job job{light, lambda, nullptr, {}};
            try {
                job.prop = std::make_unique<rs::Propagator>(plate, *mask, source, lambda, flip, twoD,
                                                            rs::QuadratureRule::ForAccuracy(accuracy_));
            } catch (const Error &e) {
                throw Error(scene.Where(light), "light '" + light->name + "' on the aperture plate '" + shape.name +
                                                    "': " + e.Message());
            }
            try {
                job.grid = rs::MakeGrid(*sensor, *job.prop);
            } catch (const Error &e) {
                throw Error(scene.Where(&det), "sensor '" + det.name + "': " + e.Message());
            }
            plan.totalUnits += rs::ProgressUnits(job.grid);
            plan.jobs.push_back(std::move(job));
        }
        return plan;
    }

    bool Deterministic() const override { return true; }
    bool WaveOptical() const override { return true; }

    std::string ToString() const override {
        const char *m = mode_ == Mode::TwoD ? "2d" : (mode_ == Mode::ThreeD ? "3d" : "auto");
        return std::string("rs { mode = ") + m + ", auto_2d_tolerance = " + std::to_string(auto2dTolerance_) +
               ", accuracy = " + std::to_string(accuracy_) + " }";
    }

  private:
    /// Whether the 2-D mode applies (this file's header); throws for `mode = "2d"` when it cannot.
    bool Choose2d(const Scene &scene, const ApertureMask &mask, const PlateFrame &plate, const CoherentSource &source,
                  double lambda, const SensorPlaneGeometry &sensor, const std::string &lightName) const {
        if (mode_ == Mode::ThreeD) return false;
        const bool forced = mode_ == Mode::TwoD;
        auto fail = [&](const std::string &why) {
            if (forced) throw Error(scene.Where(this), "integrator 'rs' with mode = \"2d\": " + why);
            return false;
        };
        double v0 = 0, v1 = 0;
        if (!mask.IsSlitsAlongV(0, &v0, &v1))
            return fail(
                "the openings must be rectangles that share one range along the plate's y axis (slits)");
        const std::optional<Vec3> dir = source.PlaneWaveDirection();
        if (!dir || std::abs(Dot(Normalize(*dir), plate.e2)) > 1e-9)
            return fail("light '" + lightName + "' must be a plane wave with no component along the slits");
        const bool alongT = std::abs(Dot(sensor.frame.t, plate.e2)) >= 1 - 1e-9;
        const bool alongS = std::abs(Dot(sensor.frame.s, plate.e2)) >= 1 - 1e-9;
        if (!alongT && !alongS)
            return fail("a sensor axis must be parallel to the slits (the plate's y axis)");
        if (forced) return true;
        // auto: the slit ends' predicted effect on every pixel (docs/rs.md "2-D mode selection").
        Bounds2 slits = mask.Bounds();
        slits.lo.y = v0;
        slits.hi.y = v1;
        return rs::SlitEndError(plate, slits, sensor, 2 * Pi / lambda) <= auto2dTolerance_;
    }

    Mode mode_;
    double auto2dTolerance_, accuracy_;
};

PHASOR_EXPORT_PLUGIN(Integrator, RsIntegrator)

}  // namespace phasor
