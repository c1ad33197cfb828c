// SPDX-License-Identifier: Apache-2.0
// `rectangle`: the quad [−w/2, w/2] × [−h/2, h/2] in the object-space plane z = 0 (normal +z;
// by default w = h = 2 m, i.e. [−1, 1]²), mapped by `to_world`. Two triangles with uvs
// (0,0) … (1,1) from the −x−y corner.
#include "core/geometry/spherical_rectangle.h"
#include "shapes/shape_common.h"

namespace phasor {

class RectangleShape final : public MeshShape {
  public:
    using MeshShape::MeshShape;

    static const Schema &GetSchema() {
        static const Schema s{"shape",
                              "rectangle",
                              "Rectangle in the object-space plane z = 0, normal +z (two triangles).",
                              {P::Length("width", "extent along object-space x")
                                   .Default(Value::Number(2, Dim::Length()))
                                   .Min(0, true),
                               P::Length("height", "extent along object-space y")
                                   .Default(Value::Number(2, Dim::Length()))
                                   .Min(0, true),
                               shape_common::ToWorldParam(), shape_common::MaterialParam()}};
        return s;
    }
    static std::unique_ptr<Shape> Create(const ParamDict &d, BuildContext &ctx) {
        const double w = d.GetNumber("width"), h = d.GetNumber("height");
        const Transform toWorld = ctx.GetTransform(d, "to_world");
        auto key = [&] { return GeometryKey("rectangle").Number("width", w).Number("height", h).Matrix("to_world", toWorld); };
        auto shape = shape_common::CachedMeshShape<RectangleShape>(d, "to_world", key, [&] {
            const double hw = 0.5 * w, hh = 0.5 * h;
            TriangleMesh m;
            m.positions = {{-hw, -hh, 0}, {hw, -hh, 0}, {hw, hh, 0}, {-hw, hh, 0}};
            m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            m.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from +z
            m.Transform(toWorld);
            return m;
        });
        return shape_common::Finish(std::move(shape), d, ctx);
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict(), ParamDict()
                                 .Set("width", Value::Number(0.5, Dim::Length()))
                                 .Set("height", Value::Number(0.125, Dim::Length()))};
    }
    std::string ToString() const override { return "rectangle " + MeshShape::ToString(); }
    bool IsPlanar() const override { return true; }

    // Next-event estimation samples a rectangle by the solid angle it subtends (an area light's
    // density r²/(A·cos θ) swings by orders of magnitude over a large panel near the point lit).
    std::optional<ShapeSolidAngleSample> SampleSolidAngle(const Vec3 &ref, const Vec2 &u) const override {
        const std::optional<SphericalRectangle> r = SeenFrom(ref);
        if (!r) return std::nullopt;
        return ShapeSolidAngleSample{r->Sample(u), PointAt(0, 1.0 / 3, 1.0 / 3).ng, 1 / r->SolidAngle()};
    }
    double PdfSolidAngle(const Vec3 &ref) const override {
        const std::optional<SphericalRectangle> r = SeenFrom(ref);
        return r ? 1 / r->SolidAngle() : 0;
    }

  private:
    // The world-space quad: corner 0 (−x−y) and the edges to corners 1 (+x) and 3 (+y); a
    // `to_world` that shears it has no spherical rectangle (From declines).
    std::optional<SphericalRectangle> SeenFrom(const Vec3 &ref) const {
        const std::vector<Vec3> &v = Mesh()->positions;
        return SphericalRectangle::From(ref, v[0], v[1] - v[0], v[3] - v[0]);
    }
};

PHASOR_EXPORT_PLUGIN(Shape, RectangleShape)

}  // namespace phasor
