// SPDX-License-Identifier: Apache-2.0
// `obj`: a Wavefront OBJ file (v, vt, vn, f; polygons fan-triangulated), mapped by `to_world`.
#include "core/geometry/mesh_io.h"
#include "shapes/shape_common.h"

namespace phasor {

class ObjShape final : public MeshShape {
  public:
    using MeshShape::MeshShape;

    static const Schema &GetSchema() {
        static const Schema s{"shape",
                              "obj",
                              "Triangle mesh from a Wavefront OBJ file.",
                              {P::File("file", "the .obj file").Required(), shape_common::ToWorldParam(),
                               shape_common::MaterialParam()}};
        return s;
    }
    static std::unique_ptr<Shape> Create(const ParamDict &d, BuildContext &ctx) {
        std::string path = ctx.ResolveFile(d, "file").string();
        Transform toWorld = ctx.GetTransform(d, "to_world");
        auto key = [&] { return GeometryKey("obj").File("file", path).Matrix("to_world", toWorld); };
        auto shape = shape_common::CachedMeshShape<ObjShape>(d, "file", key, [&] {
            TriangleMesh m = LoadObj(path);
            m.Transform(toWorld);
            return m;
        });
        return shape_common::Finish(std::move(shape), d, ctx);
    }
    std::string ToString() const override { return "obj " + MeshShape::ToString(); }
};

PHASOR_EXPORT_PLUGIN(Shape, ObjShape)

}  // namespace phasor
