// SPDX-License-Identifier: Apache-2.0
// phasor test support — building scene descriptions in C++ and rendering them in-process.
#pragma once

#include <memory>
#include <sstream>
#include <string>

#include "core/image/film.h"
#include "core/render/registry.h"
#include "core/render/scene.h"

namespace phasor::test {

inline Value Len(double metres) { return Value::Number(metres, Dim::Length()); }
inline Value Vec(double x, double y, double z, Dim d = Dim::None()) { return Value::Vector({x, y, z}, d); }
inline Value LenVec(double x, double y, double z) { return Vec(x, y, z, Dim::Length()); }
inline Value Num(double v) { return Value::Number(v); }
inline Value Int(long long v) { return Value::Integer(v); }
inline Value Str(std::string s) { return Value::String(std::move(s)); }
inline Value Ref(std::string s) { return Value::Ref(std::move(s)); }
inline Value Call(std::string f, std::vector<Value> args, std::vector<std::string> names = {}) {
    return Value::Call(std::move(f), std::move(args), std::move(names));
}

/// Fluent scene-description builder: b.Add("Shape", "sphere", "ball").Set("radius", Len(1)) …
class SceneBuilder {
  public:
    ParamDict &Add(std::string keyword, std::string type, std::string name = "") {
        SceneEntity e;
        e.keyword = std::move(keyword);
        e.type = std::move(type);
        e.name = std::move(name);
        desc_.entities.push_back(std::move(e));
        return desc_.entities.back().params;
    }
    ParamDict &Render() { return Add("Render", ""); }
    const SceneDesc &Desc() const { return desc_; }

    /// Builds the scene; fails the calling test (via the returned nullptr and `log`) on errors.
    std::unique_ptr<Scene> Build(std::string *log = nullptr) const {
        Diagnostics diag;
        auto scene = Scene::Build(desc_, diag);
        if (log) {
            std::ostringstream os;
            diag.Print(os);
            *log = os.str();
        }
        return scene;
    }

  private:
    SceneDesc desc_;
};

/// One plug-in of family T built through the registry as a scene builds it (look-up, schema,
/// Create, the unused-parameter report), named "under_test" in `desc` (which may hold objects its
/// parameters refer to). Throws phasor::Error with the diagnostics if it does not build.
template <typename T>
std::shared_ptr<T> BuildOne(const std::string &keyword, const std::string &type, const ParamDict &params,
                            SceneDesc desc = {}) {
    SceneEntity e;
    e.keyword = keyword;
    e.type = type;
    e.name = "under_test";
    e.params = params;
    desc.entities.push_back(std::move(e));
    Diagnostics diag;
    BuildContext ctx(desc, diag);
    ctx.BuildAll();
    for (const auto &o : ctx.All<T>())
        if (const SceneEntity *ent = ctx.EntityOf(o.get()); ent && ent->name == "under_test" && !diag.HasErrors())
            return o;
    std::ostringstream os;
    diag.Print(os);
    throw Error(keyword + " \"" + type + "\" did not build: " + os.str());
}

/// Renders with the scene's integrator and returns the resolved image. Its `variance` channel is
/// the i.i.d. variance of each pixel mean: for error estimates use support/replicas.h.
inline Image RenderImage(const Scene &scene, int spp, uint64_t seed = 1, const std::string &sampler = "sobol") {
    const Detector &d = scene.GetDetector();
    Film film(d.Width(), d.Height(), d.Response());
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed;
    opt.sampler = sampler;
    scene.GetIntegrator().Render(scene, film, opt);
    return film.Resolve();
}

}  // namespace phasor::test
