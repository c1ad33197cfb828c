// SPDX-License-Identifier: Apache-2.0
// phasor — glTF 2.0 import through tinygltf (Debian's prebuilt library; no implementation macro
// here). Geometry only: triangles of every mesh instanced by the default scene's node tree, in
// world space. Accessors are bounds-checked here, so a corrupt file is an error, never a crash.
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>

#include "core/diagnostics.h"
#include "core/geometry/mesh_io.h"

namespace phasor {

namespace {

/// Images are not needed for geometry; skip decoding them entirely.
bool IgnoreImage(tinygltf::Image *, const int, std::string *, std::string *, int, int, const unsigned char *,
                 int, void *) {
    return true;
}

const char *ModeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        default: return "unknown";
    }
}

class GltfReader {
  public:
    GltfReader(const std::string &path, const tinygltf::Model &model) : path_(path), model_(model) {}

    [[noreturn]] void Fail(const std::string &reason) const { throw Error(path_ + ": " + reason); }

    /// Reads accessor `index` (type SCALAR, VEC2 or VEC3 for comps = 1, 2, 3) as `count × comps`
    /// doubles; integer components are converted as the glTF spec says (normalised or not).
    std::vector<double> Read(int index, int comps, const char *what, bool allowIntegers) const {
        if (index < 0 || index >= int(model_.accessors.size()))
            Fail(std::string(what) + ": accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor &acc = model_.accessors[index];
        int expectType = comps == 1   ? TINYGLTF_TYPE_SCALAR
                         : comps == 2 ? TINYGLTF_TYPE_VEC2
                                      : TINYGLTF_TYPE_VEC3;
        if (acc.type != expectType)
            Fail(std::string(what) + ": accessor " + std::to_string(index) + " has the wrong type");
        if (acc.sparse.isSparse) Fail(std::string(what) + ": sparse accessors are not supported");
        int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
        if (compSize <= 0)
            Fail(std::string(what) + ": unknown component type " + std::to_string(acc.componentType));
        if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !allowIntegers)
            Fail(std::string(what) + ": the component type must be FLOAT");
        std::vector<double> out(acc.count * comps, 0.0);
        if (acc.count == 0) return out;
        if (acc.bufferView < 0) return out;  // no buffer view: all zeros (glTF 2.0 §3.6.2.1)
        if (acc.bufferView >= int(model_.bufferViews.size()))
            Fail(std::string(what) + ": buffer view " + std::to_string(acc.bufferView) + " does not exist");
        const tinygltf::BufferView &view = model_.bufferViews[acc.bufferView];
        if (view.buffer < 0 || view.buffer >= int(model_.buffers.size()))
            Fail(std::string(what) + ": buffer " + std::to_string(view.buffer) + " does not exist");
        const std::vector<unsigned char> &data = model_.buffers[view.buffer].data;
        int stride = acc.ByteStride(view);
        if (stride <= 0) Fail(std::string(what) + ": invalid byte stride");
        std::size_t elemSize = std::size_t(compSize) * comps;
        // Overflow-safe bounds check of the last element against the view and the buffer.
        std::size_t viewEnd = view.byteOffset + view.byteLength;
        if (viewEnd < view.byteOffset || viewEnd > data.size())
            Fail(std::string(what) + ": buffer view " + std::to_string(acc.bufferView) +
                 " exceeds its buffer");
        std::size_t last = acc.byteOffset + std::size_t(stride) * (acc.count - 1) + elemSize;
        if (acc.count > (SIZE_MAX - elemSize - acc.byteOffset) / std::size_t(stride) ||
            last > view.byteLength)
            Fail(std::string(what) + ": accessor " + std::to_string(index) + " exceeds its buffer view");
        const unsigned char *base = data.data() + view.byteOffset + acc.byteOffset;
        for (std::size_t i = 0; i < acc.count; ++i) {
            const unsigned char *e = base + i * std::size_t(stride);
            for (int c = 0; c < comps; ++c) out[i * comps + c] = Component(e + c * compSize, acc);
        }
        return out;
    }

    std::string path_;
    const tinygltf::Model &model_;

  private:
    static double Component(const unsigned char *p, const tinygltf::Accessor &acc) {
        // Normalised integers map to [0, 1] or [−1, 1] (glTF 2.0 §3.11, "animation" table).
        bool n = acc.normalized;
        switch (acc.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                float v;
                std::memcpy(&v, p, 4);
                return v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
                uint8_t v = *p;
                return n ? v / 255.0 : v;
            }
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                int8_t v;
                std::memcpy(&v, p, 1);
                return n ? std::max(v / 127.0, -1.0) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t v;
                std::memcpy(&v, p, 2);
                return n ? v / 65535.0 : v;
            }
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                int16_t v;
                std::memcpy(&v, p, 2);
                return n ? std::max(v / 32767.0, -1.0) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
                uint32_t v;
                std::memcpy(&v, p, 4);
                return v;
            }
            case TINYGLTF_COMPONENT_TYPE_INT: {
                int32_t v;
                std::memcpy(&v, p, 4);
                return v;
            }
            case TINYGLTF_COMPONENT_TYPE_DOUBLE: {
                double v;
                std::memcpy(&v, p, 8);
                return v;
            }
            default: return 0;
        }
    }
};

/// The local transform of a node: its matrix (column-major), or T·R·S (glTF 2.0 §3.5.3).
/// Returns false for a singular transform (e.g. a zero scale that hides a subtree).
bool NodeTransform(const tinygltf::Node &node, Transform *out, const GltfReader &r) {
    Transform::Mat m{};
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) r.Fail("node '" + node.name + "': matrix must have 16 entries");
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) m[row][col] = node.matrix[col * 4 + row];
        if (m[3][0] != 0 || m[3][1] != 0 || m[3][2] != 0 || m[3][3] != 1)
            r.Fail("node '" + node.name + "': the matrix is not affine");
    } else {
        double t[3] = {0, 0, 0}, s[3] = {1, 1, 1}, q[4] = {0, 0, 0, 1};
        if (!node.translation.empty()) {
            if (node.translation.size() != 3) r.Fail("node '" + node.name + "': translation needs 3 entries");
            for (int i = 0; i < 3; ++i) t[i] = node.translation[i];
        }
        if (!node.scale.empty()) {
            if (node.scale.size() != 3) r.Fail("node '" + node.name + "': scale needs 3 entries");
            for (int i = 0; i < 3; ++i) s[i] = node.scale[i];
        }
        if (!node.rotation.empty()) {
            if (node.rotation.size() != 4) r.Fail("node '" + node.name + "': rotation needs 4 entries");
            double len = std::sqrt(Sqr(node.rotation[0]) + Sqr(node.rotation[1]) + Sqr(node.rotation[2]) +
                                   Sqr(node.rotation[3]));
            if (!(len > 0)) r.Fail("node '" + node.name + "': the rotation quaternion is zero");
            for (int i = 0; i < 4; ++i) q[i] = node.rotation[i] / len;
        }
        // Rotation matrix of the unit quaternion (x, y, z, w).
        double x = q[0], y = q[1], z = q[2], w = q[3];
        double rm[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                           {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                           {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) m[i][j] = rm[i][j] * s[j];
            m[i][3] = t[i];
        }
        m[3][3] = 1;
    }
    for (const auto &row : m)
        for (double v : row)
            if (!std::isfinite(v)) r.Fail("node '" + node.name + "': the transform is not finite");
    try {
        *out = Transform(m);
    } catch (const std::exception &) {
        return false;
    }
    return true;
}

/// One primitive as a local-space mesh (nullopt: skipped, reason appended to `skipped`).
std::optional<TriangleMesh> ReadPrimitive(const GltfReader &r, const tinygltf::Primitive &prim,
                                          const std::string &meshName, std::size_t primIndex,
                                          std::string *skipped) {
    std::string where = "mesh '" + meshName + "' primitive " + std::to_string(primIndex);
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        if (skipped) *skipped += (skipped->empty() ? "" : "; ") + where + " (mode " + ModeName(mode) + ")";
        return std::nullopt;
    }
    auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) r.Fail(where + " has no POSITION attribute");

    TriangleMesh m;
    std::vector<double> p = r.Read(pos->second, 3, (where + " POSITION").c_str(), true);
    std::size_t nv = p.size() / 3;
    m.positions.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) m.positions[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
        std::vector<double> n = r.Read(it->second, 3, (where + " NORMAL").c_str(), true);
        if (n.size() != p.size()) r.Fail(where + ": NORMAL and POSITION counts differ");
        m.normals.resize(nv);
        for (std::size_t i = 0; i < nv; ++i) m.normals[i] = Vec3(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
    }
    if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
        std::vector<double> t = r.Read(it->second, 2, (where + " TEXCOORD_0").c_str(), true);
        if (t.size() / 2 != nv) r.Fail(where + ": TEXCOORD_0 and POSITION counts differ");
        m.uvs.resize(nv);
        for (std::size_t i = 0; i < nv; ++i) m.uvs[i] = Vec2(t[2 * i], t[2 * i + 1]);
    }

    // Vertex order: the index accessor (unsigned byte/short/int) or 0, 1, 2, …
    std::vector<uint32_t> order;
    if (prim.indices >= 0) {
        int ct = prim.indices < int(r.model_.accessors.size())
                     ? r.model_.accessors[prim.indices].componentType
                     : 0;
        if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            r.Fail(where + ": indices must be unsigned byte, short or int");
        std::vector<double> idx = r.Read(prim.indices, 1, (where + " indices").c_str(), true);
        order.reserve(idx.size());
        for (double v : idx) {
            if (v >= double(nv))
                r.Fail(where + ": index " + std::to_string(uint64_t(v)) + " is out of range (" +
                       std::to_string(nv) + " vertices)");
            order.push_back(uint32_t(v));
        }
    } else {
        order.resize(nv);
        for (std::size_t i = 0; i < nv; ++i) order[i] = uint32_t(i);
    }

    // Triangles (glTF 2.0 §3.7.2.1, "topology types").
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (order.size() % 3 != 0)
            r.Fail(where + ": the vertex count of a TRIANGLES primitive is not a multiple of 3");
        m.indices = std::move(order);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (std::size_t i = 0; i + 2 < order.size(); ++i) {
            m.indices.push_back(order[i]);
            m.indices.push_back(order[i + 1 + i % 2]);
            m.indices.push_back(order[i + 2 - i % 2]);
        }
    } else {
        for (std::size_t i = 1; i + 1 < order.size(); ++i) {
            m.indices.push_back(order[i]);
            m.indices.push_back(order[i + 1]);
            m.indices.push_back(order[0]);
        }
    }
    m.Validate(r.path_ + ": " + where);
    return m;
}

/// Replaces shared vertices by one copy per triangle corner with the flat (geometric) normal —
/// what glTF prescribes when a primitive has no normals but the merged mesh needs them.
void FlatNormals(TriangleMesh &m) {
    TriangleMesh out;
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        Vec3 p[3] = {m.positions[m.indices[i]], m.positions[m.indices[i + 1]], m.positions[m.indices[i + 2]]};
        Vec3 n = Cross(p[1] - p[0], p[2] - p[0]);
        double len = Length(n);
        n = len > 0 ? n / len : Vec3(0, 0, 1);
        for (int k = 0; k < 3; ++k) {
            out.indices.push_back(uint32_t(out.positions.size()));
            out.positions.push_back(p[k]);
            out.normals.push_back(n);
            if (!m.uvs.empty()) out.uvs.push_back(m.uvs[m.indices[i + k]]);
        }
    }
    m = std::move(out);
}

}  // namespace

TriangleMesh LoadGltf(const std::string &path, std::string *skipped) {
    if (skipped) skipped->clear();
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw Error(path + ": cannot open the glTF file");
    char magic[4] = {0, 0, 0, 0};
    probe.read(magic, 4);
    bool binary = probe.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
    probe.close();

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(IgnoreImage, nullptr);
    std::string err, warn;
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                    : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    } catch (const std::exception &e) {
        throw Error(path + ": cannot read the glTF file: " + e.what());
    }
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        throw Error(path +
                    ": cannot read the glTF file: " + (err.empty() ? std::string("unknown error") : err));
    }

    GltfReader r(path, model);
    std::vector<TriangleMesh> parts;

    // Depth-first over the node tree; `depth` guards against cycles in a corrupt file.
    std::function<void(int, const Transform &, std::size_t)> visit = [&](int ni, const Transform &parent,
                                                                         std::size_t depth) {
        if (ni < 0 || ni >= int(model.nodes.size())) r.Fail("node " + std::to_string(ni) + " does not exist");
        if (depth > model.nodes.size()) r.Fail("the node hierarchy contains a cycle");
        const tinygltf::Node &node = model.nodes[ni];
        Transform local;
        if (!NodeTransform(node, &local, r)) {
            if (skipped)
                *skipped +=
                    (skipped->empty() ? "" : "; ") + ("node '" + node.name + "' (singular transform)");
            return;
        }
        Transform world = parent * local;
        if (node.mesh >= 0) {
            if (node.mesh >= int(model.meshes.size()))
                r.Fail("mesh " + std::to_string(node.mesh) + " does not exist");
            const tinygltf::Mesh &mesh = model.meshes[node.mesh];
            for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
                std::optional<TriangleMesh> m = ReadPrimitive(r, mesh.primitives[pi], mesh.name, pi, skipped);
                if (!m) continue;
                m->Transform(world);
                parts.push_back(std::move(*m));
            }
        }
        for (int c : node.children) visit(c, world, depth + 1);
    };

    std::vector<int> roots;
    int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : (model.scenes.empty() ? -1 : 0);
    if (sceneIndex >= int(model.scenes.size())) r.Fail("the default scene does not exist");
    if (sceneIndex >= 0) {
        roots = model.scenes[sceneIndex].nodes;
    } else {
        // No scene: every node that is nobody's child is a root.
        std::vector<bool> isChild(model.nodes.size(), false);
        for (const auto &n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && c < int(isChild.size())) isChild[c] = true;
        for (std::size_t i = 0; i < model.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
    }
    for (int root : roots) visit(root, Transform(), 0);

    // Merge. Normals: kept if any part has them (parts without get flat normals, as glTF
    // prescribes); uvs: kept if any part has them (missing ones become (0, 0)).
    bool anyNormals = false, anyUvs = false;
    for (const auto &p : parts) {
        anyNormals |= !p.normals.empty();
        anyUvs |= !p.uvs.empty();
    }
    TriangleMesh out;
    for (auto &p : parts) {
        if (anyNormals && p.normals.empty()) FlatNormals(p);
        if (anyUvs && p.uvs.empty()) p.uvs.assign(p.positions.size(), Vec2(0, 0));
        if (out.positions.size() + p.positions.size() > 0xFFFFFFFFull) r.Fail("too many vertices");
        uint32_t offset = uint32_t(out.positions.size());
        out.positions.insert(out.positions.end(), p.positions.begin(), p.positions.end());
        out.normals.insert(out.normals.end(), p.normals.begin(), p.normals.end());
        out.uvs.insert(out.uvs.end(), p.uvs.begin(), p.uvs.end());
        for (uint32_t i : p.indices) out.indices.push_back(i + offset);
    }
    if (out.TriangleCount() == 0) r.Fail("the default scene contains no triangles");
    // Degenerate normals (zero vectors in the file) would poison shading; reject them.
    for (const Vec3 &n : out.normals)
        if (!(LengthSquared(n) > 0)) r.Fail("a NORMAL is zero or not finite");
    out.Validate(path);
    return out;
}

}  // namespace phasor
