// SPDX-License-Identifier: Apache-2.0
// `sphere`: an analytic sphere, intersected in double precision (Embree user geometry) and
// sampled uniformly by area. `to_world` must be a similarity (rotation, uniform scale,
// translation): it moves the centre, scales the radius and orients the (u, v) = (φ/2π, θ/π)
// parameterisation (local +z is the pole).
#include "core/geometry/analytic.h"
#include "shapes/shape_common.h"

namespace phasor {

class SphereShape final : public AnalyticSphere {
  public:
    explicit SphereShape(const AnalyticSphere &s) : AnalyticSphere(s) {}

    // Starts with the scene type, as the mesh shapes' do (messages take the first word).
    std::string ToString() const override { return "sphere " + AnalyticSphere::ToString(); }

    static const Schema &GetSchema() {
        static const Schema s{"shape",
                              "sphere",
                              "Analytic sphere (double-precision intersection, uniform area sampling).",
                              {P::Vector("center", "centre in object space", Dim::Length())
                                   .Default(Value::Vector(Vec3(), Dim::Length())),
                               P::Length("radius", "radius in object space")
                                   .Default(Value::Number(1, Dim::Length()))
                                   .Min(0, true),
                               shape_common::ToWorldParam(), shape_common::MaterialParam()}};
        return s;
    }
    static std::unique_ptr<Shape> Create(const ParamDict &d, BuildContext &ctx) {
        Transform toWorld = ctx.GetTransform(d, "to_world");
        auto shape = shape_common::AtParam(d, "to_world", [&] {
            return std::make_unique<SphereShape>(
                AnalyticSphere::FromTransform(d.GetVector("center"), d.GetNumber("radius"), toWorld));
        });
        return shape_common::Finish(std::move(shape), d, ctx);
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict(), ParamDict()
                                 .Set("radius", Value::Number(0.25, Dim::Length()))
                                 .Set("center", Value::Vector(Vec3(0.1, -0.2, 3), Dim::Length()))};
    }
};

PHASOR_EXPORT_PLUGIN(Shape, SphereShape)

}  // namespace phasor
