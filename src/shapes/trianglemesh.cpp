// SPDX-License-Identifier: Apache-2.0
// `trianglemesh`: a mesh written inline in the scene: positions (a length list, 3 per vertex),
// indices (3 per triangle, counter-clockwise seen from outside), optional per-vertex normals and
// uvs; mapped by `to_world` (normals by its inverse transpose).
#include "shapes/shape_common.h"

namespace phasor {

class TriangleMeshShape final : public MeshShape {
  public:
    using MeshShape::MeshShape;

    static const Schema &GetSchema() {
        static const Schema s{
            "shape",
            "trianglemesh",
            "Triangle mesh given inline (positions, indices, optional normals and uvs).",
            {P::NumberList("positions", "vertex positions x y z …", Dim::Length()).Required(),
             P::IntegerList("indices", "vertex indices, 3 per triangle (counter-clockwise from outside)")
                 .Required(),
             P::NumberList("normals", "per-vertex normals x y z … (optional)"),
             P::NumberList("uvs", "per-vertex texture coordinates u v … (optional)"),
             shape_common::ToWorldParam(), shape_common::MaterialParam()}};
        return s;
    }
    static std::unique_ptr<Shape> Create(const ParamDict &d, BuildContext &ctx) {
        TriangleMesh m;
        std::vector<double> p = d.GetNumbers("positions");
        if (p.empty() || p.size() % 3 != 0)
            throw Error(d.Loc("positions"),
                        "'positions' needs 3 numbers per vertex; got " + std::to_string(p.size()));
        std::size_t nv = p.size() / 3;
        for (std::size_t i = 0; i < nv; ++i)
            m.positions.push_back(Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]));
        std::vector<int> idx = d.GetInts("indices");
        if (idx.empty() || idx.size() % 3 != 0)
            throw Error(d.Loc("indices"),
                        "'indices' needs 3 entries per triangle; got " + std::to_string(idx.size()));
        for (int i : idx) {
            if (i < 0 || std::size_t(i) >= nv)
                throw Error(d.Loc("indices"), "index " + std::to_string(i) + " is out of range (" +
                                                  std::to_string(nv) + " vertices)");
            m.indices.push_back(uint32_t(i));
        }
        if (d.Has("normals")) {
            std::vector<double> n = d.GetNumbers("normals");
            if (n.size() != p.size())
                throw Error(d.Loc("normals"), "'normals' needs 3 numbers per vertex (" +
                                                  std::to_string(p.size()) + "); got " +
                                                  std::to_string(n.size()));
            for (std::size_t i = 0; i < nv; ++i) {
                Vec3 v(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
                if (!(Length(v) > 0))
                    throw Error(d.Loc("normals"), "normal " + std::to_string(i) + " is zero");
                m.normals.push_back(Normalize(v));
            }
        }
        if (d.Has("uvs")) {
            std::vector<double> uv = d.GetNumbers("uvs");
            if (uv.size() != 2 * nv)
                throw Error(d.Loc("uvs"), "'uvs' needs 2 numbers per vertex (" + std::to_string(2 * nv) +
                                              "); got " + std::to_string(uv.size()));
            for (std::size_t i = 0; i < nv; ++i) m.uvs.push_back(Vec2(uv[2 * i], uv[2 * i + 1]));
        }
        const Transform toWorld = ctx.GetTransform(d, "to_world");
        m.Transform(toWorld);
        // The mesh is a function of the lists given and to_world.
        auto key = [&] {
            GeometryKey k("trianglemesh");
            k.Numbers("positions", p).Numbers("indices", std::vector<double>(idx.begin(), idx.end()));
            for (const char *list : {"normals", "uvs"})
                if (d.Has(list)) k.Numbers(list, d.GetNumbers(list));
            return k.Matrix("to_world", toWorld);
        };
        auto shape = shape_common::CachedMeshShape<TriangleMeshShape>(d, "positions", key, [&] { return std::move(m); });
        return shape_common::Finish(std::move(shape), d, ctx);
    }
    static std::vector<ParamDict> TestPresets() {
        auto list = [](std::vector<double> v, Dim dim) {
            std::vector<Value> items;
            for (double x : v) items.push_back(Value::Number(x, dim));
            return Value::List(std::move(items));
        };
        std::vector<Value> idx;
        for (int i : {0, 1, 2, 0, 2, 3}) idx.push_back(Value::Integer(i));
        return {ParamDict()
                    .Set("positions", list({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, Dim::Length()))
                    .Set("indices", Value::List(idx))
                    .Set("uvs", list({0, 0, 1, 0, 1, 1, 0, 1}, Dim::None()))};
    }
    std::string ToString() const override { return "trianglemesh " + MeshShape::ToString(); }
};

PHASOR_EXPORT_PLUGIN(Shape, TriangleMeshShape)

}  // namespace phasor
