// SPDX-License-Identifier: Apache-2.0
// phasor — the integrators' support declarations at work (integrator_support.h): the scene checks
// every integrator's Validate starts with, the unreachable-light diagnosis, and the generated table.
#include "core/render/integrator_support.h"

#include <algorithm>
#include <sstream>

#include "core/render/coherent_source.h"
#include "core/render/integrator.h"
#include "core/render/material.h"
#include "core/render/scene.h"

namespace phasor {

namespace {

/// "a delta position light", "an area light".
std::string ALight(LightType t) {
    const std::string d = Describe(t);
    return (d[0] == 'a' ? "an " : "a ") + d + " light";
}

/// The light types an integrator renders, for messages: "delta position, delta direction".
std::string RenderedTypes(const IntegratorSupport &s) {
    std::string out;
    for (int t = 0; t < NumLightTypes; ++t)
        if (s.lights[t] != LightReach::Refused) out += (out.empty() ? "" : ", ") + std::string(Describe(LightType(t)));
    return out;
}

/// True if every kernel capability but footprint-awareness is refused and footprint-aware kernels
/// need openings: the integrator renders aperture plates only (rs).
bool PlatesOnly(const IntegratorSupport &s) {
    return s.kernels[0] == KernelReach::Refused && s.kernels[1] == KernelReach::Refused &&
           s.kernels[2] == KernelReach::OpeningsOnly;
}

/// The capabilities a kernel shows over a few queries in one regime (ScatterQuery::rayOptics):
/// normal and oblique incidence from both sides, at a 3×3 grid of surface parameters (a `mix`
/// whose weight is a texture may differ across the surface).
unsigned ProbedCaps(const Material &m, bool rayOptics) {
    static const SpectralGenRay gr;  // a generalized-ray query reads no geometry from it here
    SampledWavelengths wl;
    wl.lambda[0] = 550e-9;
    wl.pdf[0] = 1;
    wl.delta = true;
    unsigned caps = 0;
    for (const Vec3 &wi : {Vec3(0, 0, 1), Normalize(Vec3(0.6, 0.2, 0.77)), Vec3(0, 0, -1),
                           Normalize(Vec3(-0.5, 0.3, -0.81))})
        for (int i = 0; i < 9; ++i) {
            ScatterQuery q;
            q.wi = wi;
            q.wl = &wl;
            q.rayOptics = rayOptics;
            q.gr = rayOptics ? nullptr : &gr;
            q.tex = TextureEvalContext::AtUV(Vec2(0.1 + 0.4 * (i % 3), 0.1 + 0.4 * (i / 3)));
            ScratchBuffer scratch;
            caps |= m.Prepare(q, scratch).Capabilities();
        }
    return caps;
}

const char *const CapNames[3] = {"continuous lobes", "near-delta lobes", "footprint-aware (aperture)"};

}  // namespace

void ValidateSupport(const Integrator &integrator, const Scene &scene, Diagnostics &diag) {
    const IntegratorSupport s = integrator.Support();
    const std::string who = "integrator '" + integrator.name + "'";
    const Detector &det = scene.GetDetector();
    const FileLoc detLoc = scene.Where(&det);

    // The detector.
    if (s.detector == DetectorNeed::SensorPlane && !det.SensorPlane())
        diag.Error(detLoc, who + " needs a virtual_plane detector (a sensor plane); detector '" + det.name +
                               "' is not one");
    if (s.detector == DetectorNeed::GeneralizedRays && !det.SupportsGR())
        diag.Error(detLoc, who + " needs a detector that generates generalized rays (perspective, thin_lens, "
                                 "virtual_plane); detector '" + det.name + "' does not");
    if (const DetectorPolarization &pol = det.Polarization(); pol.Any() && !s.polarization) {
        const std::string what = pol.polarizer ? "a polarizer" : "Stokes output";
        diag.Error(pol.polarizer ? pol.polarizerLoc : pol.stokesLoc,
                   "detector '" + det.name + "' asks for " + what + ", but " + who +
                       " carries no polarisation (it renders unpolarised intensity); use integrator "
                       "\"sample_solve\" (e.g. --integrator sample_solve) or remove the parameter");
    }

    // The lights.
    for (const Light *light : scene.Lights()) {
        const LightType type = light->Type();
        const LightReach reach = s.Reach(type);
        const FileLoc loc = scene.Where(light);
        const bool fields = std::find(s.lights.begin(), s.lights.end(), LightReach::Field) != s.lights.end();
        if ((reach == LightReach::Refused && fields) || (reach == LightReach::Field && !light->Coherent())) {
            diag.Error(loc, "light '" + light->name + "' has no coherent field (" + ALight(type) + "): " + who +
                                " propagates the fields of coherent lights (plane_wave, point, gaussian_beam and any "
                                "light that implements Light::Coherent)");
        } else if (reach == LightReach::Refused) {
            diag.Error(loc, who + " cannot render light '" + light->name + "', " + ALight(type) + " (it renders " +
                                RenderedTypes(s) + " lights; docs/plugins.md, \"What each integrator renders\")");
        } else if (reach == LightReach::Field && !light->EmissionSpectrum().LineWavelength()) {
            diag.Error(loc, "light '" + light->name + "' is not monochromatic: " + who +
                                    " propagates the field of one wavelength; give it a line spectrum (e.g. "
                                    "spectrum = line(633 nm))");
        }
    }

    // The kernels.
    const bool platesOnly = PlatesOnly(s);
    const bool rayOptics = s.kernels[1] == KernelReach::RayOpticsLimit;
    for (const auto &shape : scene.Shapes()) {
        const Material *m = shape->material;
        const FileLoc loc = scene.Where(shape.get());
        if (platesOnly && !(m && OpeningsOf(*m))) {
            diag.Error(loc, who + " needs an aperture plate: shape '" + shape->name +
                                "' has no material with openings (use the 'aperture' material; " + who +
                                " propagates through one plate and no other shape)");
            continue;
        }
        if (!m) continue;
        const unsigned caps = m->IsFootprintAware() ? unsigned(CapFootprintAware) : ProbedCaps(*m, rayOptics);
        for (int c = 0; c < 3; ++c)
            if ((caps & KernelCapOrder[c]) && s.kernels[c] == KernelReach::Refused)
                diag.Error(loc, who + " cannot render shape '" + shape->name + "': its material has " + CapNames[c]);
    }

    // Lights it cannot reach in this scene (a warning: the image is what the integrator computes).
    if (const std::string why = UnreachableDeltaLights(integrator, scene); !why.empty())
        diag.Warning(scene.Where(&integrator).Known() ? scene.Where(&integrator) : detLoc, why);
}

std::string UnreachableDeltaLights(const Integrator &integrator, const Scene &scene) {
    const IntegratorSupport s = integrator.Support();
    std::string names;
    int n = 0;
    for (const Light *l : scene.Lights())
        if (s.Reach(l->Type()) == LightReach::SampledOnly) {
            names += (n++ ? ", '" : "'") + l->name + "'";
        }
    if (n == 0) return "";
    const bool rayOptics = s.kernels[1] == KernelReach::RayOpticsLimit;
    for (const auto &shape : scene.Shapes())
        if (shape->material && (ProbedCaps(*shape->material, rayOptics) & CapContinuous)) return "";
    return "integrator '" + integrator.name + "' cannot reach light" + (n > 1 ? "s " : " ") + names +
           ": it meets a delta light only by next-event estimation at a surface with a continuous lobe, and no "
           "shape here has one (mirrors, gratings and apertures are deltas in ray optics, and the detector never "
           "sees a delta light directly); " +
           (n > 1 ? "their" : "its") +
           " light is missing from the image: use integrator \"grt\" (--integrator grt), which measures delta "
           "lights in closed form at the detector and through every specular lobe";
}

// ---- The generated table ------------------------------------------------------------------------

namespace {

/// Every registered light, detector and integrator, built once from its default parameters (a
/// required shape reference names a fixture rectangle, a detector gets a resolution): the table
/// shows what each plug-in is. A plug-in that does not build so is listed as such.
struct Samples {
    std::unique_ptr<SceneDesc> desc;
    std::unique_ptr<Diagnostics> diag;
    std::unique_ptr<BuildContext> ctx;
    std::vector<std::pair<std::string, std::shared_ptr<Light>>> lights;
    std::vector<std::pair<std::string, std::shared_ptr<Detector>>> detectors;
    std::vector<std::pair<std::string, std::shared_ptr<Integrator>>> integrators;
};

template <typename T>
void AddEntities(SceneDesc &desc, const char *keyword) {
    for (const auto &e : Registry<T>::Entries()) {
        SceneEntity ent;
        ent.keyword = keyword;
        ent.type = e.name;
        ent.name = std::string("sample_") + e.name;
        for (const ParamSpec &p : e.schema().params) {
            if (p.required && p.kind == ParamKind::Ref && p.refFamily == "shape")
                ent.params.Set(p.name, Value::Ref("sample_panel"));
            if (p.name == "resolution" && !p.defaultValue && p.kind == ParamKind::IntegerList)
                ent.params.Set(p.name, Value::List({Value::Integer(2), Value::Integer(2)}));
        }
        desc.entities.push_back(std::move(ent));
    }
}

const Samples &PluginSamples() {
    static const Samples s = [] {
        Samples out;
        out.desc = std::make_unique<SceneDesc>();
        SceneEntity panel;
        panel.keyword = "Shape";
        panel.type = "rectangle";
        panel.name = "sample_panel";
        out.desc->entities.push_back(panel);
        AddEntities<Light>(*out.desc, "Light");
        AddEntities<Detector>(*out.desc, "Detector");
        AddEntities<Integrator>(*out.desc, "Integrator");
        out.diag = std::make_unique<Diagnostics>();
        out.ctx = std::make_unique<BuildContext>(*out.desc, *out.diag);
        out.ctx->BuildAll();
        for (const auto &l : out.ctx->All<Light>())
            if (const SceneEntity *e = out.ctx->EntityOf(l.get())) out.lights.emplace_back(e->type, l);
        for (const auto &d : out.ctx->All<Detector>())
            if (const SceneEntity *e = out.ctx->EntityOf(d.get())) out.detectors.emplace_back(e->type, d);
        for (const auto &i : out.ctx->All<Integrator>())
            if (const SceneEntity *e = out.ctx->EntityOf(i.get())) out.integrators.emplace_back(e->type, i);
        return out;
    }();
    return s;
}

std::string LightCell(const IntegratorSupport &s, const Light &light) {
    switch (s.Reach(light.Type())) {
        case LightReach::Refused: return "—";
        case LightReach::HitAndSampled: return "hit + NEE (MIS)";
        case LightReach::SampledOnly: return "NEE at continuous lobes only ¹";
        case LightReach::ClosedForm:
            return light.Type() == LightType::Distant ? "closed form ² + hit + NEE" : "closed form ² + NEE";
        case LightReach::Field:
            return light.Coherent() ? "field (line spectrum) ³" : "— (no coherent field)";
    }
    return "?";
}

std::string DetectorCell(const IntegratorSupport &s, const Detector &d) {
    switch (s.detector) {
        case DetectorNeed::Rays: return "✓";
        case DetectorNeed::GeneralizedRays: return d.SupportsGR() ? "✓ (generalized rays)" : "—";
        case DetectorNeed::SensorPlane: return d.SensorPlane() ? "✓ (the field on the plane)" : "— (not a sensor plane)";
    }
    return "?";
}

const char *KernelCell(KernelReach r) {
    switch (r) {
        case KernelReach::Refused: return "—";
        case KernelReach::RayOpticsLimit: return "ray-optics limit ⁴";
        case KernelReach::Full: return "✓";
        case KernelReach::OpeningsOnly: return "openings of one plate";
    }
    return "?";
}

}  // namespace

std::string SupportMarkdown() {
    const Samples &samples = PluginSamples();
    std::ostringstream os;
    auto header = [&](const char *first) {
        os << "| " << first << " |";
        for (const auto &[name, i] : samples.integrators) os << " `" << name << "` |";
        os << "\n|---|";
        for (std::size_t k = 0; k < samples.integrators.size(); ++k) os << "---|";
        os << "\n";
    };
    os << "Each integrator declares what it renders (`Integrator::Support`, "
          "core/render/integrator_support.h); the scene checks at load (`phasor check`, `render`, `compare`) "
          "refuse what it cannot render, at the object's location, and warn about lights it cannot reach in "
          "that scene. These tables are printed from the same declarations.\n\n";
    // A registered plug-in that did not build with its default parameters (never for the built-in
    // ones: tests/integrators/validate_test.cpp).
    auto unbuilt = [&](const char *name) {
        os << "| `" << name << "` (not built with its default parameters) |";
        for (std::size_t k = 0; k < samples.integrators.size(); ++k) os << " ? |";
        os << "\n";
    };
    os << "### Lights (type with default parameters)\n\n";
    header("light");
    for (const auto &e : Registry<Light>::Entries()) {
        const auto it = std::find_if(samples.lights.begin(), samples.lights.end(),
                                     [&](const auto &l) { return l.first == e.name; });
        if (it == samples.lights.end()) {
            unbuilt(e.name);
            continue;
        }
        const Light &light = *it->second;
        os << "| `" << e.name << "` (" << Describe(light.Type()) << ") |";
        for (const auto &[iname, i] : samples.integrators) os << " " << LightCell(i->Support(), light) << " |";
        os << "\n";
    }
    os << "\n`distant` with `angular_radius = 0` (or `omega = 0`) is a delta direction.\n"
          "¹ A classical path meets a delta light only by next-event estimation at a vertex with a continuous "
          "lobe: never at the detector nor through a mirror, grating or aperture (deltas in ray optics). "
          "A scene where no kernel has a continuous lobe gets a warning at load naming the lights it cannot "
          "reach.\n"
          "² Measured in closed form (Eq. 24) by the detector's generalized rays and through every near-delta "
          "lobe (theory §0 D4a, D14).\n"
          "³ The light's field (`Light::Coherent`) at its line wavelength; a continuous spectrum is refused.\n\n";
    os << "### Detectors\n\n";
    header("detector");
    for (const auto &e : Registry<Detector>::Entries()) {
        const auto it = std::find_if(samples.detectors.begin(), samples.detectors.end(),
                                     [&](const auto &d) { return d.first == e.name; });
        if (it == samples.detectors.end()) {
            unbuilt(e.name);
            continue;
        }
        os << "| `" << e.name << "` |";
        for (const auto &[iname, i] : samples.integrators) os << " " << DetectorCell(i->Support(), *it->second) << " |";
        os << "\n";
    }
    os << "\n### Kernel capabilities (`Material::Capabilities`)\n\n";
    header("capability");
    for (int c = 0; c < 3; ++c) {
        os << "| " << CapNames[c] << " |";
        for (const auto &[iname, i] : samples.integrators) os << " " << KernelCell(i->Support().kernels[c]) << " |";
        os << "\n";
    }
    os << "| polarisation (`polarizer`, `stokes`) |";
    for (const auto &[iname, i] : samples.integrators) os << " " << (i->Support().polarization ? "✓" : "—") << " |";
    os << "\n\n⁴ Near-delta lobes are true deltas (a grating keeps its zeroth orders), an aperture casts its "
          "geometric shadow.\n";
    return os.str();
}

}  // namespace phasor
