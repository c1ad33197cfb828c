// SPDX-License-Identifier: Apache-2.0
// Shared helpers for the material tests and the kernel benchmarks (bench/kernel_bench.cpp):
// building a kernel through the registry (the same look-up → validate → create → report-unused
// protocol a scene uses), fixture objects presets may refer to, wavelengths and directions, and the
// incident generalized ray of footprint-aware kernels.
#pragma once

#include <memory>
#include <string>

#include "core/diagnostics.h"
#include "core/render/genray.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/geometry/shape.h"

namespace phasor::test {

/// Name given to the object under test inside its little scene.
inline constexpr const char *UnderTestName = "under_test";

/// Fixture objects every preset may reference (TestPresets() are plain ParamDicts, so a kernel
/// that needs another object names one of these):
///   @contract_checker  texture  checkerboard(color0 = 0.1, color1 = 0.9, scale = 4)
///   @contract_half     texture  constant(value = 0.5)
///   @contract_ramp     texture  gradient(value0 = 0.1, value1 = 0.9) along u over [0, 1]: dimensionless
///   @contract_gold     material conductor(ior = "Au")
///   @contract_glass    material dielectric(ior = 1.5)
///   @contract_aluminium material conductor(ior = "Al")
///   @contract_matte    material diffuse(reflectance = 0.6)
///   @contract_bk7      material dielectric(ior = "BK7")   (dispersive)
///   @contract_pitch    texture  gradient(value0 = 1.2 um, value1 = 2.4 um, axis = "u")   (a length)
///   @contract_groove_angle texture gradient(value0 = 0 deg, value1 = 120 deg, axis = "v") (an angle)
///   @contract_film     material thin_film(ior = "Cu2O", thickness = 150 nm)  (a coating)
///   @contract_stack    material multilayer(layers = [layer("MgF2", 100 nm), layer(2.1, 65 nm)])  (a coating)
///   @contract_thickness texture gradient(value0 = 80 nm, value1 = 250 nm) along u (a length)
///   @contract_grating  material grating(substrate = @contract_gold, period = 1.6 um, height = 0.1 um,
///                      max_order = 5)   (energy per incident direction, listed orders)
///   @contract_rough    material harvey_shack(substrate = @contract_gold, sigma_h = 20 nm,
///                      alpha_r = 0.1)   (energy per incident direction, a glint and a halo)
///   @contract_grating_mix material mix(a = @contract_grating, b = @contract_rough, weight = 0.3)
///                      (for a mixture of mixtures)
inline void AddFixtures(SceneDesc &desc) {
    auto add = [&](const char *keyword, const char *type, const char *name, const ParamDict &params) {
        SceneEntity e;
        e.keyword = keyword;
        e.type = type;
        e.name = name;
        e.params = params;
        desc.entities.push_back(e);
    };
    add("Material", "conductor", "contract_gold", ParamDict().Set("ior", Value::String("Au")));
    add("Material", "dielectric", "contract_glass", ParamDict().Set("ior", Value::Number(1.5)));
    add("Material", "conductor", "contract_aluminium", ParamDict().Set("ior", Value::String("Al")));
    add("Material", "diffuse", "contract_matte", ParamDict().Set("reflectance", Value::Number(0.6)));
    add("Material", "dielectric", "contract_bk7", ParamDict().Set("ior", Value::String("BK7")));
    add("Texture", "gradient", "contract_pitch",
        ParamDict()
            .Set("value0", Value::Number(1.2e-6, Dim::Length()))
            .Set("value1", Value::Number(2.4e-6, Dim::Length()))
            .Set("axis", Value::String("u")));
    add("Texture", "gradient", "contract_groove_angle",
        ParamDict()
            .Set("value0", Value::Number(0, Dim::Angle()))
            .Set("value1", Value::Number(120 * 3.141592653589793 / 180, Dim::Angle()))
            .Set("axis", Value::String("v")));
    add("Material", "thin_film", "contract_film",
        ParamDict().Set("ior", Value::String("Cu2O")).Set("thickness", Value::Number(150e-9, Dim::Length())));
    auto layer = [](Value ior, double d) {
        return Value::Call("layer", {std::move(ior), Value::Number(d, Dim::Length())}, {"ior", "thickness"});
    };
    add("Material", "multilayer", "contract_stack",
        ParamDict().Set("layers", Value::List({layer(Value::String("MgF2"), 100e-9), layer(Value::Number(2.1), 65e-9)})));
    add("Material", "grating", "contract_grating",
        ParamDict()
            .Set("substrate", Value::Ref("contract_gold"))
            .Set("period", Value::Number(1.6e-6, Dim::Length()))
            .Set("height", Value::Number(0.1e-6, Dim::Length()))
            .Set("max_order", Value::Integer(5)));
    add("Material", "harvey_shack", "contract_rough",
        ParamDict()
            .Set("substrate", Value::Ref("contract_gold"))
            .Set("sigma_h", Value::Number(20e-9, Dim::Length()))
            .Set("alpha_r", Value::Number(0.1)));
    add("Material", "mix", "contract_grating_mix",
        ParamDict()
            .Set("a", Value::Ref("contract_grating"))
            .Set("b", Value::Ref("contract_rough"))
            .Set("weight", Value::Number(0.3)));
    add("Texture", "gradient", "contract_thickness",
        ParamDict()
            .Set("value0", Value::Number(80e-9, Dim::Length()))
            .Set("value1", Value::Number(250e-9, Dim::Length())));
    SceneEntity checker;
    checker.keyword = "Texture";
    checker.type = "checkerboard";
    checker.name = "contract_checker";
    checker.params.Set("color0", Value::Number(0.1))
        .Set("color1", Value::Number(0.9))
        .Set("scale", Value::Number(4));
    desc.entities.push_back(checker);
    SceneEntity half;
    half.keyword = "Texture";
    half.type = "constant";
    half.name = "contract_half";
    half.params.Set("value", Value::Number(0.5));
    desc.entities.push_back(half);
    add("Texture", "gradient", "contract_ramp", ParamDict().Set("value0", Value::Number(0.1)).Set("value1", Value::Number(0.9)));
}

/// A scene of a few entities (plus the fixtures, when asked), built at once; keeps the diagnostics.
struct MiniScene {
    SceneDesc desc;
    Diagnostics diag;
    /// Adds the fixtures of AddFixtures.
    MiniScene &WithFixtures() {
        AddFixtures(desc);
        return *this;
    }
    MiniScene &Add(const std::string &keyword, const std::string &type, const std::string &name, ParamDict p) {
        SceneEntity e;
        e.keyword = keyword;
        e.type = type;
        e.name = name;
        e.params = std::move(p);
        desc.entities.push_back(std::move(e));
        return *this;
    }
    /// Builds everything; returns the object named `name` (nullptr if it failed).
    template <typename T>
    std::shared_ptr<T> Build(const std::string &name) {
        BuildContext ctx(desc, diag);
        ctx.BuildAll();
        for (const auto &o : ctx.All<T>())
            if (const SceneEntity *e = ctx.EntityOf(o.get()); e && e->name == name) return o;
        return nullptr;
    }
    /// The first error's message ("" if none).
    std::string FirstError() const {
        for (const Diagnostic &d : diag.All())
            if (d.severity == Severity::Error) return d.message;
        return "";
    }
    /// The latest error's message ("" if none).
    std::string LastError() const {
        for (auto it = diag.All().rbegin(); it != diag.All().rend(); ++it)
            if (it->severity == Severity::Error) return it->message;
        return "";
    }
};

/// Builds one object of family T (keyword "Material", "Texture", …) from `params` in a scene that
/// also holds the fixtures. Returns nullptr if building failed; `diag` receives every diagnostic.
template <typename T>
std::shared_ptr<T> BuildObject(const std::string &keyword, const std::string &type, const ParamDict &params,
                               Diagnostics &diag) {
    SceneDesc desc;
    AddFixtures(desc);
    SceneEntity e;
    e.keyword = keyword;
    e.type = type;
    e.name = UnderTestName;
    e.params = params;
    desc.entities.push_back(e);
    BuildContext ctx(desc, diag);
    ctx.BuildAll();
    for (const auto &o : ctx.All<T>()) {
        const SceneEntity *src = ctx.EntityOf(o.get());
        if (src && src->name == UnderTestName) return o;
    }
    return nullptr;
}

inline std::shared_ptr<Material> BuildMaterial(const std::string &type, const ParamDict &params,
                                               Diagnostics &diag) {
    return BuildObject<Material>("Material", type, params, diag);
}

/// A kernel prepared for one query in a scratch buffer of its own, for tests that ask one query a
/// few questions: Prep(m, q)->Eval(wo), Prep(m, q)->ListNearDelta(), … (the listing and the answers
/// live as long as the Prep).
class Prep {
  public:
    Prep(const Material &m, const ScatterQuery &q)
        : scratch_(std::make_unique<ScratchBuffer>(1024)), k_(&m.Prepare(q, *scratch_)) {}
    const PreparedKernel *operator->() const { return k_; }
    const PreparedKernel &operator*() const { return *k_; }

  private:
    std::unique_ptr<ScratchBuffer> scratch_;
    const PreparedKernel *k_;
};

/// Hero `lambda` [m] plus three companions spaced by 85 nm and wrapped into 380–720 nm (the
/// hero-wavelength layout of theory §4.10).
inline SampledWavelengths TestWavelengths(double lambda) {
    SampledWavelengths wl;
    const double lo = 380e-9, span = 340e-9;
    for (int i = 0; i < NumWavelengths; ++i) {
        wl.lambda[i] = i == 0 ? lambda : lo + std::fmod(lambda - lo + i * 85e-9, span);
        wl.pdf[i] = 1 / span;
    }
    return wl;
}

/// A single discrete line at `lambda` [m].
inline SampledWavelengths LineWavelength(double lambda) {
    SampledWavelengths wl;
    wl.lambda[0] = lambda;
    wl.pdf[0] = 1;
    wl.delta = true;
    return wl;
}

/// Unit direction from cosθ and φ (local frame, z = normal).
inline Vec3 DirectionFromCosTheta(double cosTheta, double phi) {
    const double s = SafeSqrt(1 - cosTheta * cosTheta);
    return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

/// Uniform direction on the sphere from two uniform numbers.
inline Vec3 UniformSphere(double u1, double u2) { return DirectionFromCosTheta(1 - 2 * u1, 2 * Pi * u2); }

/// The plate a footprint-aware kernel is queried on: the plane z = 0 with identity to_world, so
/// local, world and plate coordinates coincide.
class ContractPlate final : public Shape {
  public:
    ContractPlate() { name = "contract_plate"; }
    SurfaceInteraction Interaction(const Ray &, double, unsigned, double, double) const override {
        return {};
    }
    Bounds3 Bounds() const override { return {}; }
    double Area() const override { return 0; }
    ShapeSample Sample(const Vec2 &) const override { return {}; }
    std::string ToString() const override { return "rectangle (contract plate)"; }
    bool IsPlanar() const override { return true; }
};

/// The incident GR of footprint-aware kernels: β [m] and ρ at the hit, the same for every
/// wavelength; the hit point near the plate's origin (the presets place openings there).
inline constexpr double ContractBeta = 0.5e-6, ContractRho = 0.5;
inline const Vec3 ContractHit(0.3e-6, -0.4e-6, 0);

/// Points q at a GR arriving along −wi at si.p (wave regime).
inline void AttachFootprint(ScatterQuery &q, SpectralGenRay &gr, SurfaceInteraction &si, const ContractPlate &plate) {
    si.n = Vec3(0, 0, 1);
    si.shading = Frame();
    si.shape = &plate;
    gr.o = si.p;
    gr.d = -q.wi;
    gr.count = q.wl->Count();
    for (int i = 0; i < gr.count; ++i) {
        gr.k[i] = 2 * Pi * q.etaOutside / q.wl->lambda[i];
        gr.beta2[i] = ContractBeta * ContractBeta;
        gr.rho[i] = ContractRho;
    }
    q.rayOptics = false;
    q.gr = &gr;
    q.si = &si;
}

}  // namespace phasor::test
