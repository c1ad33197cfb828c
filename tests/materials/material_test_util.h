// SPDX-License-Identifier: Apache-2.0
// Shared helpers for the material tests: building a kernel through the registry (the same
// look-up → validate → create → report-unused protocol a scene uses), fixture objects presets may
// refer to, wavelengths and directions.
#pragma once

#include <memory>
#include <string>
#include <vector>

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
///   @contract_bk7      material dielectric(ior = "BK7")   (dispersive)
///   @contract_pitch    texture  gradient(value0 = 1.2 um, value1 = 2.4 um, axis = "u")   (a length)
///   @contract_groove_angle texture gradient(value0 = 0 deg, value1 = 120 deg, axis = "v") (an angle)
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
/// also holds the fixtures and `extra` entities (objects the parameters may reference). Returns
/// nullptr if building failed; `diag` receives every diagnostic.
template <typename T>
std::shared_ptr<T> BuildObject(const std::string &keyword, const std::string &type, const ParamDict &params,
                               Diagnostics &diag, const std::vector<SceneEntity> &extra = {}) {
    SceneDesc desc;
    AddFixtures(desc);
    desc.entities.insert(desc.entities.end(), extra.begin(), extra.end());
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
                                               Diagnostics &diag, const std::vector<SceneEntity> &extra = {}) {
    return BuildObject<Material>("Material", type, params, diag, extra);
}

/// A named entity for BuildObject's `extra` (e.g. Entity("Material", "conductor", "metal", params)).
inline SceneEntity Entity(const std::string &keyword, const std::string &type, const std::string &name,
                          const ParamDict &params) {
    SceneEntity e;
    e.keyword = keyword;
    e.type = type;
    e.name = name;
    e.params = params;
    return e;
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
