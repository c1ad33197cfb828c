// SPDX-License-Identifier: Apache-2.0
// Helpers for the smooth-stack kernel tests (thin_film, multilayer, coated conductor and
// dielectric): build a kernel from parameters, and read its listed reflectance / transmittance
// and lobe responses at one wavelength and incidence.
#pragma once

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "material_test_util.h"
#include "materials/smooth_kernel.h"

namespace phasor::test {

/// Builds `type` from `params` (with the fixtures of material_test_util.h and, if given, extra
/// named materials); fails the test on any diagnostic.
inline std::shared_ptr<Material> Kernel(const std::string &type, const ParamDict &params) {
    Diagnostics diag;
    auto m = BuildMaterial(type, params, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(m && diag.All().empty()) << type << ":\n" << os.str();
    return m;
}

/// The plane-wave optics of a smooth kernel (conductor, dielectric, thin_film, multilayer); fails the
/// test for another kernel.
inline const SmoothSurface &SurfaceOf(const Material &m) {
    const auto *k = dynamic_cast<const SmoothKernel *>(&m);
    EXPECT_TRUE(k) << m.ToString() << " is not a smooth kernel";
    static const SmoothSurface none(nullptr, 0, nullptr);
    return k ? k->Surface() : none;
}
/// The layers of a coating definition (thin_film, multilayer), or nullptr.
inline const Coating *LayersOf(const Material &m) {
    const auto *k = dynamic_cast<const CoatingKernel *>(&m);
    return k ? k->Layers().get() : nullptr;
}

inline Value Nm(double v) { return Value::Number(v * 1e-9, Dim::Length()); }
inline Value LayerCall(Value ior, double nm) { return Value::Call("layer", {std::move(ior), Nm(nm)}, {"ior", "thickness"}); }

/// What a kernel lists for one wave: R (lobe 0's weight) and T in energy (lobe 1's weight times
/// (η_t/η_i)², undoing the radiance factor), 0 for an unlisted lobe.
struct Listed {
    double R = 0, T = 0;
    int count = 0;
};

/// A query at vacuum wavelength lambda [m] (one line), incidence cosθ (negative: from below) and
/// azimuth phi, in the coherent regime (a generalized ray) unless rayOptics.
struct OneWave {
    SampledWavelengths wl;
    ScatterQuery q;
    OneWave(double lambda, double cosTheta, double phi = 0.3, bool rayOptics = false) {
        wl = LineWavelength(lambda);
        q.wi = DirectionFromCosTheta(cosTheta, phi);
        q.wl = &wl;
        q.rayOptics = rayOptics;
    }
    OneWave(const OneWave &o) : wl(o.wl), q(o.q) { q.wl = &wl; }
};

inline Listed List(const Material &m, const OneWave &w) {
    const Prep k(m, w.q);
    Listed out;
    out.count = int(k->ListNearDelta().size());
    for (const NearDeltaLobe &l : k->ListNearDelta()) {
        if (l.id == 0) out.R = l.Weight()[0];
        if (l.id == 1) out.T = l.Weight()[0] * Sqr(l.Eta(0));
    }
    return out;
}

/// EvalLobe of lobe `id` towards its listed hero direction (nullopt if it is not listed).
inline std::optional<LobeResponse> Response(const Material &m, const OneWave &w, int id) {
    const Prep k(m, w.q);
    const NearDeltaLobe *l = k->FindLobe(id);
    return l ? k->EvalLobe(id, l->wo[0]) : std::nullopt;
}

}  // namespace phasor::test
