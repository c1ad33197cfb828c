// SPDX-License-Identifier: Apache-2.0
#include "core/render/scene.h"

#include <algorithm>

namespace phasor {

// The `Render` block is not a plug-in but is validated and documented the same way.
const Schema &RenderSchema() {
    static const Schema s{
        "render", "Render",
        "What to render: detector, integrator, samples, output (optional; the command line overrides).",
        {P::Ref("detector", "detector", "the detector to render (required if the scene has several)"),
         P::Ref("integrator", "integrator",
                "the integrator (default: the only one in the scene, else `ray`; --integrator overrides)"),
         P::Integer("spp", "samples per pixel (--spp overrides)").Default(Value::Integer(16)).Min(1),
         P::Integer("seed", "random seed (--seed overrides)").Default(Value::Integer(0)).Min(0),
         P::String("sampler",
                   "the sample generator: a plug-in of the sampler family (`phasor list sampler`) or the name of "
                   "a Sampler block; default: the scene's only Sampler block, else `sobol` (--sampler overrides)"),
         P::String("output",
                   "output EXR path, relative to the working directory as pbrt's film filename is (a .png is "
                   "written beside it; -o overrides); default: out/<scene file name>.exr")}};
    return s;
}

namespace {

// The object Render names by `param`, else the only one of its family. Counting the family's
// objects means something only in a scene read without errors (`whole`).
template <typename T>
std::shared_ptr<T> PickOne(BuildContext &ctx, const ParamDict *render, const std::string &param,
                           const std::string &what, Diagnostics &diag, const FileLoc &sceneLoc, bool whole) {
    if (render && render->Has(param)) {
        try {
            return ctx.GetRef<T>(*render, param);
        } catch (const Error &e) {
            diag.Report(e);
            return nullptr;
        }
    }
    if (!whole) return nullptr;
    auto all = ctx.All<T>();
    if (all.size() == 1) return all[0];
    if (all.size() > 1) {
        std::vector<Diagnostic> notes;
        for (auto &o : all)
            if (const SceneEntity *e = ctx.EntityOf(o.get()))
                notes.push_back(Diagnostic{Severity::Note, e->loc, what + " defined here", {}});
        diag.Error(render ? render->EntityLoc() : sceneLoc,
                   "the scene has " + std::to_string(all.size()) + " " + what + "s; choose one with Render { " +
                       param + " = @name }",
                   std::move(notes));
    }
    return nullptr;
}

}  // namespace

Scene::~Scene() = default;

std::unique_ptr<Scene> Scene::Build(const SceneDesc &descIn, Diagnostics &diag,
                                    const std::string &integratorOverride) {
    std::unique_ptr<Scene> scene(new Scene());
    scene->ownedDesc_ = std::make_unique<SceneDesc>(descIn);
    const SceneDesc &desc = *scene->ownedDesc_;
    FileLoc sceneLoc{desc.sourceFile, 0, 0, 1};
    scene->ctx_ = std::make_unique<BuildContext>(desc, diag);
    BuildContext &ctx = *scene->ctx_;
    ctx.BuildAll();  // (objects are named by their entity's DisplayName)

    // Render block.
    const SceneEntity *renderEntity = ctx.RenderEntity();
    const ParamDict *render = renderEntity ? &renderEntity->params : nullptr;
    int renderCount = 0;
    for (const SceneEntity &e : desc.entities)
        if (e.keyword == "Render" && ++renderCount == 2) diag.Error(e.loc, "only one Render block is allowed");
    const bool renderValid = render && render->Validate(RenderSchema(), diag);
    RenderOptions &options = scene->settings_.options;
    if (renderValid) {
        options.spp = render->GetInt("spp");
        options.seed = (uint64_t)render->GetNumber("seed");
        if (render->Has("output")) scene->settings_.output = render->GetString("output");
        scene->settings_.loc = render->EntityLoc();
    }
    // The sampler: Render.sampler (a Sampler block's name or a plug-in), else the only Sampler
    // block, else the family's default plug-in (`sobol`, which declares itself so).
    const auto samplers = ctx.All<Sampler>();
    if (renderValid && render->Has("sampler")) {
        options.sampler = render->GetString("sampler");
        if (!scene->NewSampler(options.sampler, 0)) {
            const std::string s = Suggest(options.sampler, scene->SamplerNames());
            diag.Error(render->Loc("sampler"), "unknown sampler '" + options.sampler + "'" +
                                                   (s.empty() ? "" : "; did you mean '" + s + "'?"));
        }
    } else if (samplers.size() == 1) {
        options.sampler = ctx.EntityOf(samplers[0].get())->name;
    } else if (samplers.size() > 1) {
        diag.Error(render ? render->EntityLoc() : sceneLoc, "the scene has " + std::to_string(samplers.size()) +
                                                                " samplers; choose one with Render { sampler = \"name\" }");
    } else if (const auto *entry = Registry<Sampler>::Default()) {
        options.sampler = entry->name;
    }

    const bool whole = !desc.incomplete;
    scene->detector_ = PickOne<Detector>(ctx, render, "detector", "detector", diag, sceneLoc, whole);
    if (!scene->detector_ && ctx.All<Detector>().empty() && !diag.HasErrors())
        diag.Error(render ? render->EntityLoc() : sceneLoc, "the scene has no detector (add e.g. Detector \"perspective\")");

    // Integrator: the CLI override (by @name or by type), else Render.integrator, else the only one,
    // else the family's default plug-in (`ray`, which declares itself so).
    if (!integratorOverride.empty()) {
        if (render && render->Has("integrator")) render->GetValue("integrator");  // overridden, not unused
        for (auto &i : ctx.All<Integrator>()) {
            const SceneEntity *e = ctx.EntityOf(i.get());
            if (e && (e->name == integratorOverride || (e->type == integratorOverride && !scene->integrator_)))
                scene->integrator_ = i;
        }
        // An Integrator of that name whose build failed has its own error already.
        const bool failedEntity = std::any_of(desc.entities.begin(), desc.entities.end(), [&](const SceneEntity &e) {
            return e.keyword == "Integrator" && e.name == integratorOverride;
        });
        if (!scene->integrator_ && !failedEntity) {
            auto *entry = Registry<Integrator>::Find(integratorOverride);
            if (!entry) {
                std::string s = Suggest(integratorOverride, Registry<Integrator>::Names());
                diag.Error(FileLoc{"<command line>", 0, 0, 1},
                           "unknown integrator '" + integratorOverride + "'" +
                               (s.empty() ? "" : "; did you mean '" + s + "'?"));
            } else {
                ParamDict d;
                d.Validate(entry->schema(), diag);
                try {
                    scene->integrator_ = std::shared_ptr<Integrator>(entry->create(d, ctx));
                    scene->integrator_->name = integratorOverride;
                } catch (const Error &e) {
                    diag.Report(e);
                }
            }
        }
    } else {
        if ((render && render->Has("integrator")) || ctx.All<Integrator>().size() > 1)
            scene->integrator_ = PickOne<Integrator>(ctx, render, "integrator", "integrator", diag, sceneLoc, whole);
        else if (ctx.All<Integrator>().size() == 1)
            scene->integrator_ = ctx.All<Integrator>()[0];
        else if (auto *entry = Registry<Integrator>::Default()) {
            ParamDict d;
            d.Validate(entry->schema(), diag);
            scene->integrator_ = std::shared_ptr<Integrator>(entry->create(d, ctx));
            scene->integrator_->name = entry->name;
        }
    }
    if (renderValid) render->ReportUnused(diag, "Render");  // (after an error, nothing was read)
    if (!whole || diag.HasErrors() || !scene->detector_ || !scene->integrator_) return nullptr;

    // Geometry and lights.
    scene->shapes_ = ctx.All<Shape>();
    std::vector<const Shape *> shapes;
    for (auto &s : scene->shapes_) {
        shapes.push_back(s.get());
        if (!s->material) continue;
        try {
            s->material->CheckShape(*s);
        } catch (const Error &e) {
            const SceneEntity *ent = ctx.EntityOf(s.get());
            if (e.Loc().Known() || !ent) diag.Report(e);
            else diag.Report(Error(ent->loc, e.Message()));
        }
    }
    if (diag.HasErrors()) return nullptr;
    for (const Shape *s : shapes) scene->straightThrough_ = scene->straightThrough_ || (s->material && s->material->MayPassStraight());
    try {
        scene->accel_ = std::make_unique<Accel>(shapes);
    } catch (const Error &e) {
        diag.Report(e);
        return nullptr;
    }
    std::vector<std::pair<const Spectrum *, double>> emitters;
    for (auto &l : ctx.All<Light>()) {
        l->Preprocess(scene->accel_->Bounds());
        scene->lights_.push_back(l.get());
        if (l->IsInfinite()) scene->infiniteLights_.push_back(l.get());
        (l->IsDelta() ? scene->deltaLights_ : scene->hittableEmitters_).push_back(l.get());
        if (l->MeasuredInClosedForm()) scene->closedFormLights_.push_back(l.get());
        if (l->Type() == LightType::Area) scene->areaLights_.push_back(l.get());
        emitters.emplace_back(&l->EmissionSpectrum(), l->PowerScale());
    }
    if (scene->lights_.empty()) diag.Warning(sceneLoc, "the scene has no light; the image will be black");
    scene->uniformLights_ = std::make_unique<LightSampler>(scene->lights_, LightSelection::Uniform);
    scene->powerLights_ = std::make_unique<LightSampler>(scene->lights_, LightSelection::Power);
    scene->exhaustiveLights_ = std::make_unique<LightSampler>(scene->lights_, LightSelection::Exhaustive);
    scene->CheckSensorPlane(diag);
    scene->wavelengths_ = std::make_unique<WavelengthSampler>(emitters, scene->detector_->Response());
    if (diag.HasErrors()) return nullptr;
    // What the integrator cannot render, at load (`check` refuses what `render` would).
    scene->integrator_->Validate(*scene, diag);
    if (diag.HasErrors()) return nullptr;
    return scene;
}

std::unique_ptr<Sampler> Scene::NewSampler(const std::string &name, uint64_t seed) const {
    if (ctx_)
        for (const auto &s : ctx_->All<Sampler>())
            if (const SceneEntity *e = ctx_->EntityOf(s.get()); e && e->name == name) {
                std::unique_ptr<Sampler> copy = s->Clone();
                copy->SetSeed(seed);
                return copy;
            }
    return MakeSampler(name, seed);
}

std::vector<std::string> Scene::SamplerNames() const {
    std::vector<std::string> names = Registry<Sampler>::Names();
    if (ctx_)
        for (const auto &s : ctx_->All<Sampler>())
            if (const SceneEntity *e = ctx_->EntityOf(s.get()); e && !e->name.empty()) names.push_back(e->name);
    return names;
}

FileLoc Scene::Where(const void *object) const {
    const SceneEntity *e = ctx_ ? ctx_->EntityOf(object) : nullptr;
    return e ? e->loc : FileLoc{};
}

Ray Scene::ShadowRay(const SurfaceInteraction &from, const Vec3 &to, bool toDirection, double *tMax) const {
    if (toDirection) {
        *tMax = Infinity;
        return Ray{from.SpawnOrigin(to), to};
    }
    const Vec3 o = from.SpawnOrigin(to - from.p), od = to - o;
    const double dist = Length(od);
    if (!(dist > 0)) {
        *tMax = 0;
        return Ray{o, Normalize(to - from.p)};
    }
    // Stop just short of the target so the light's own surface does not occlude it.
    *tMax = dist * (1 - ShadowEpsilon);
    return Ray{o, od / dist};
}

}  // namespace phasor
