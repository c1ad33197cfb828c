// SPDX-License-Identifier: Apache-2.0
// `subdivision`: a Catmull–Clark subdivision surface (OpenSubdiv): the polygon cage from an OBJ
// `file` (or the built-in `cage = "cube"`, [−1, 1]³) refined `levels` times uniformly, quads
// split into triangles, shading normals from the limit surface, uvs from the cage's `vt`
// (face-varying, seams kept; without them each triangle has the default parameterisation);
// mapped by `to_world`.
// Triangle count: 2 · 4^levels per cage quad (a cube at level 8: 786 432).
#include "core/geometry/mesh_io.h"
#include "shapes/shape_common.h"

namespace phasor {

class SubdivisionShape final : public MeshShape {
  public:
    using MeshShape::MeshShape;

    static const Schema &GetSchema() {
        static const Schema s{
            "shape",
            "subdivision",
            "Catmull–Clark subdivision surface of an OBJ cage (OpenSubdiv).",
            {P::File("file", "the cage as an .obj file (polygons are kept, not triangulated; its vt, at every corner or none, become face-varying uvs)"),
             P::String("cage", "a built-in cage instead of `file`").Choices({"cube"}),
             P::Integer("levels", "uniform refinement levels").Default(Value::Integer(3)).Min(0).Max(8),
             shape_common::ToWorldParam(), shape_common::MaterialParam()}};
        return s;
    }
    static std::unique_ptr<Shape> Create(const ParamDict &d, BuildContext &ctx) {
        if (d.Has("file") == d.Has("cage"))
            throw Error(d.EntityLoc(),
                        "subdivision: give exactly one of 'file' (an OBJ cage) or 'cage = \"cube\"'");
        int levels = d.GetInt("levels");
        Transform toWorld = ctx.GetTransform(d, "to_world");
        const bool fromFile = d.Has("file");
        const std::string param = fromFile ? "file" : "cage";
        const std::string path = fromFile ? ctx.ResolveFile(d, "file").string() : "";
        if (!fromFile) d.GetString("cage");  // "cube" (the only choice)
        // The mesh is a function of the cage (the file's content), the levels and to_world.
        auto key = [&] {
            GeometryKey k("subdivision");
            if (fromFile) k.File("file", path);
            else k.Text("cage", "cube");
            return k.Integer("levels", levels).Matrix("to_world", toWorld);
        };
        auto shape = shape_common::CachedMeshShape<SubdivisionShape>(d, param, key, [&] {
            TriangleMesh m = SubdivideCatmullClark(fromFile ? LoadObjPolygons(path) : CubeCage(), levels);
            m.Transform(toWorld);
            return m;
        });
        return shape_common::Finish(std::move(shape), d, ctx);
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict().Set("cage", Value::String("cube")).Set("levels", Value::Integer(2))};
    }
    std::string ToString() const override { return "subdivision " + MeshShape::ToString(); }
};

PHASOR_EXPORT_PLUGIN(Shape, SubdivisionShape)

}  // namespace phasor
