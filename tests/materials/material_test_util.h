// SPDX-License-Identifier: Apache-2.0
// Shared helpers for the material tests: building a kernel through the registry (the same
// look-up → validate → create → report-unused protocol a scene uses), fixture objects presets may
// refer to, wavelengths and directions.
#pragma once

#include <memory>
#include <string>

#include "core/diagnostics.h"
#include "core/render/material.h"
#include "core/render/registry.h"

namespace phasor::test {

/// Name given to the object under test inside its little scene.
inline constexpr const char *UnderTestName = "under_test";

/// Fixture objects every preset may reference (TestPresets() are plain ParamDicts, so a kernel
/// that needs another object names one of these):
///   @contract_checker  texture  checkerboard(color0 = 0.1, color1 = 0.9, scale = 4)
///   @contract_half     texture  constant(value = 0.5)
///   @contract_gold     material conductor(ior = "Au")
///   @contract_glass    material dielectric(ior = 1.5)
///   @contract_film     material thin_film(ior = "Cu2O", thickness = 150 nm)  (a coating)
///   @contract_stack    material multilayer(layers = [layer("MgF2", 100 nm), layer(2.1, 65 nm)])  (a coating)
///   @contract_thickness texture gradient(value0 = 80 nm, value1 = 250 nm) along u (a length)
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
    add("Material", "thin_film", "contract_film",
        ParamDict().Set("ior", Value::String("Cu2O")).Set("thickness", Value::Number(150e-9, Dim::Length())));
    auto layer = [](Value ior, double d) {
        return Value::Call("layer", {std::move(ior), Value::Number(d, Dim::Length())}, {"ior", "thickness"});
    };
    add("Material", "multilayer", "contract_stack",
        ParamDict().Set("layers", Value::List({layer(Value::String("MgF2"), 100e-9), layer(Value::Number(2.1), 65e-9)})));
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
}

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

}  // namespace phasor::test
