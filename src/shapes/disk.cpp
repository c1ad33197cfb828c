// SPDX-License-Identifier: Apache-2.0
// `disk`: the analytic disk x² + y² ≤ radius² in the object-space plane z = 0 with normal +z,
// mapped by `to_world` (a non-uniform scale makes an ellipse). Double-precision intersection,
// uniform area sampling; (u, v) = (φ/2π, ρ/radius).
#include "core/geometry/analytic.h"
#include "shapes/shape_common.h"

namespace phasor {

class DiskShape final : public AnalyticDisk {
  public:
    using AnalyticDisk::AnalyticDisk;

    // Starts with the scene type, as the mesh shapes' do (messages take the first word).
    std::string ToString() const override { return "disk " + AnalyticDisk::ToString(); }

    static const Schema &GetSchema() {
        static const Schema s{"shape",
                              "disk",
                              "Analytic disk in the object-space plane z = 0, normal +z.",
                              {P::Length("radius", "radius in object space")
                                   .Default(Value::Number(1, Dim::Length()))
                                   .Min(0, true),
                               shape_common::ToWorldParam(), shape_common::MaterialParam()}};
        return s;
    }
    static std::unique_ptr<Shape> Create(const ParamDict &d, BuildContext &ctx) {
        Transform toWorld = ctx.GetTransform(d, "to_world");
        auto shape = shape_common::AtParam(
            d, "to_world", [&] { return std::make_unique<DiskShape>(d.GetNumber("radius"), toWorld); });
        return shape_common::Finish(std::move(shape), d, ctx);
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict(), ParamDict().Set("radius", Value::Number(0.05, Dim::Length()))};
    }
    bool IsPlanar() const override { return true; }
};

PHASOR_EXPORT_PLUGIN(Shape, DiskShape)

}  // namespace phasor
