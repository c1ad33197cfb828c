// SPDX-License-Identifier: Apache-2.0
// `gltf`: every triangle of a glTF 2.0 file (.gltf or .glb, loaded with tinygltf) in the world
// space of its default scene (node hierarchy applied), scaled by `units` (the length of one glTF
// unit; glTF's convention is metres) and then mapped by `to_world`. Materials in the file are
// ignored; the shape's `material` applies to the whole mesh.
#include "core/geometry/mesh_io.h"
#include "shapes/shape_common.h"

namespace phasor {

class GltfShape final : public MeshShape {
  public:
    using MeshShape::MeshShape;

    static const Schema &GetSchema() {
        static const Schema s{"shape",
                              "gltf",
                              "Triangle mesh from a glTF 2.0 file (.gltf or .glb), node transforms applied.",
                              {P::File("file", "the .gltf or .glb file").Required(),
                               P::Length("units", "length of one glTF unit")
                                   .Default(Value::Number(1, Dim::Length()))
                                   .Min(0, true),
                               shape_common::ToWorldParam(), shape_common::MaterialParam()}};
        return s;
    }
    static std::unique_ptr<Shape> Create(const ParamDict &d, BuildContext &ctx) {
        std::string path = ctx.ResolveFile(d, "file").string();
        double units = d.GetNumber("units");
        Transform toWorld = ctx.GetTransform(d, "to_world") * Transform::Scale(Vec3(units, units, units));
        std::string skipped;
        auto shape = shape_common::AtParam(d, "file", [&] {
            TriangleMesh m = LoadGltf(path, &skipped);
            m.Transform(toWorld);
            return std::make_unique<GltfShape>(std::move(m));
        });
        if (!skipped.empty())
            ctx.Diag().Warning(d.Loc("file"), path + ": skipped non-triangle primitives: " + skipped);
        return shape_common::Finish(std::move(shape), d, ctx);
    }
    std::string ToString() const override { return "gltf " + MeshShape::ToString(); }
};

PHASOR_EXPORT_PLUGIN(Shape, GltfShape)

}  // namespace phasor
