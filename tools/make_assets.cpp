// SPDX-License-Identifier: Apache-2.0
// phasor_make_assets — writes the geometry assets that phasor ships, so that none is downloaded:
//
//   torus_knot.glb               demo object for the Cornell box: a (2,3) torus knot tube of
//                                4608 triangles with normals and uvs, under a two-node hierarchy
//                                (a tilted, scaled root and a translated child).
//   test_node_transform.gltf     small test asset (embedded base64 buffer): quads with known
//   test_node_transform.glb      positions under TRS, matrix, non-uniform and mirroring node
//                                transforms; indices of all three unsigned types; a strip; a
//                                POINTS primitive that loaders must skip. Same content in both.
//   jack_cage.obj                subdivision cage: a cube with every face extruded (30 quads).
//
// Usage: phasor_make_assets <output directory>   (normally scenes/assets)
// The glTF writer below is minimal and written for these assets only (glTF 2.0 spec §3, GLB §4).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/math.h"

using phasor::Vec2;
using phasor::Vec3;

namespace {

constexpr int kFloat = 5126, kUByte = 5121, kUShort = 5123, kUInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

std::string Num(double v) {
    std::ostringstream os;
    os.precision(9);
    os << v;
    return os.str();
}

std::string Base64(const std::vector<uint8_t> &in) {
    static const char *tbl = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        uint32_t v = (uint32_t(in[i]) << 16) | (uint32_t(in[i + 1]) << 8) | in[i + 2];
        for (int k = 3; k >= 0; --k) out += tbl[(v >> (6 * k)) & 63];
    }
    if (i + 1 == in.size()) {
        uint32_t v = uint32_t(in[i]) << 16;
        out += tbl[(v >> 18) & 63];
        out += tbl[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == in.size()) {
        uint32_t v = (uint32_t(in[i]) << 16) | (uint32_t(in[i + 1]) << 8);
        out += tbl[(v >> 18) & 63];
        out += tbl[(v >> 12) & 63];
        out += tbl[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

/// Accumulates one binary buffer plus JSON fragments for views, accessors, meshes and nodes.
class GltfBuilder {
  public:
    int AddFloats(const std::vector<float> &data, int comps, bool minMax) {
        int view = AddView(data.data(), data.size() * 4, kArrayBuffer);
        std::string type = comps == 2 ? "VEC2" : "VEC3";
        std::string extra;
        if (minMax) {
            std::vector<float> lo(comps, INFINITY), hi(comps, -INFINITY);
            for (std::size_t i = 0; i < data.size(); ++i) {
                lo[i % comps] = std::min(lo[i % comps], data[i]);
                hi[i % comps] = std::max(hi[i % comps], data[i]);
            }
            extra = ",\"min\":[" + Join(lo) + "],\"max\":[" + Join(hi) + "]";
        }
        return AddAccessor(view, kFloat, data.size() / comps, type, extra);
    }
    template <typename T>
    int AddIndices(const std::vector<T> &idx, int componentType) {
        int view = AddView(idx.data(), idx.size() * sizeof(T), kElementArrayBuffer);
        return AddAccessor(view, componentType, idx.size(), "SCALAR", "");
    }
    /// attributes: e.g. {"POSITION", 0}; indices < 0: none; mode 4 = TRIANGLES.
    std::string Primitive(const std::vector<std::pair<std::string, int>> &attrs, int indices, int mode = 4) {
        std::string s = "{\"attributes\":{";
        for (std::size_t i = 0; i < attrs.size(); ++i)
            s += (i ? "," : "") + ("\"" + attrs[i].first + "\":" + std::to_string(attrs[i].second));
        s += "}";
        if (indices >= 0) s += ",\"indices\":" + std::to_string(indices);
        s += ",\"mode\":" + std::to_string(mode) + "}";
        return s;
    }
    int AddMesh(const std::string &name, const std::vector<std::string> &prims) {
        std::string s = "{\"name\":\"" + name + "\",\"primitives\":[";
        for (std::size_t i = 0; i < prims.size(); ++i) s += (i ? "," : "") + prims[i];
        meshes_.push_back(s + "]}");
        return int(meshes_.size() - 1);
    }
    /// `fields` is the JSON body after the name, e.g. "\"mesh\":0,\"translation\":[1,2,3]".
    int AddNode(const std::string &name, const std::string &fields) {
        nodes_.push_back("{\"name\":\"" + name + "\"" + (fields.empty() ? "" : "," + fields) + "}");
        return int(nodes_.size() - 1);
    }
    void SetSceneNodes(const std::vector<int> &n) { sceneNodes_ = n; }

    std::string Json(bool embedded) const {
        std::string s = "{\n\"asset\":{\"version\":\"2.0\",\"generator\":\"phasor_make_assets\"},\n";
        s += "\"scene\":0,\n\"scenes\":[{\"nodes\":[";
        for (std::size_t i = 0; i < sceneNodes_.size(); ++i)
            s += (i ? "," : "") + std::to_string(sceneNodes_[i]);
        s += "]}],\n\"nodes\":[\n" + JoinLines(nodes_) + "\n],\n\"meshes\":[\n" + JoinLines(meshes_) +
             "\n],\n";
        s += "\"accessors\":[\n" + JoinLines(accessors_) + "\n],\n\"bufferViews\":[\n" + JoinLines(views_) +
             "\n],\n";
        s += "\"buffers\":[{\"byteLength\":" + std::to_string(bin_.size());
        if (embedded) s += ",\"uri\":\"data:application/octet-stream;base64," + Base64(bin_) + "\"";
        s += "}]\n}\n";
        return s;
    }
    bool WriteGltf(const std::string &path) const {
        std::ofstream out(path, std::ios::binary);
        out << Json(true);
        return bool(out);
    }
    bool WriteGlb(const std::string &path) const {
        // GLB: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros.
        std::string json = Json(false);
        while (json.size() % 4) json += ' ';
        std::vector<uint8_t> bin = bin_;
        while (bin.size() % 4) bin.push_back(0);
        uint32_t total = uint32_t(12 + 8 + json.size() + 8 + bin.size());
        std::ofstream out(path, std::ios::binary);
        auto u32 = [&](uint32_t v) {
            out.write(reinterpret_cast<const char *>(&v), 4);
        };                 // little endian host
        u32(0x46546C67u);  // "glTF"
        u32(2);
        u32(total);
        u32(uint32_t(json.size()));
        u32(0x4E4F534Au);  // "JSON"
        out.write(json.data(), std::streamsize(json.size()));
        u32(uint32_t(bin.size()));
        u32(0x004E4942u);  // "BIN\0"
        out.write(reinterpret_cast<const char *>(bin.data()), std::streamsize(bin.size()));
        return bool(out);
    }

  private:
    int AddView(const void *data, std::size_t bytes, int target) {
        while (bin_.size() % 4) bin_.push_back(0);
        std::size_t offset = bin_.size();
        bin_.insert(bin_.end(), static_cast<const uint8_t *>(data),
                    static_cast<const uint8_t *>(data) + bytes);
        views_.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" +
                         std::to_string(bytes) + ",\"target\":" + std::to_string(target) + "}");
        return int(views_.size() - 1);
    }
    int AddAccessor(int view, int componentType, std::size_t count, const std::string &type,
                    const std::string &extra) {
        accessors_.push_back("{\"bufferView\":" + std::to_string(view) + ",\"componentType\":" +
                             std::to_string(componentType) + ",\"count\":" + std::to_string(count) +
                             ",\"type\":\"" + type + "\"" + extra + "}");
        return int(accessors_.size() - 1);
    }
    static std::string Join(const std::vector<float> &v) {
        std::string s;
        for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + Num(v[i]);
        return s;
    }
    static std::string JoinLines(const std::vector<std::string> &v) {
        std::string s;
        for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ",\n" : "") + v[i];
        return s;
    }

    std::vector<uint8_t> bin_;
    std::vector<std::string> views_, accessors_, meshes_, nodes_;
    std::vector<int> sceneNodes_;
};

/// The small asset whose loaded result the tests know exactly (see tests/core/geometry).
GltfBuilder TestAsset() {
    GltfBuilder b;
    int quad = b.AddFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, 3, true);
    int nUp = b.AddFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, 3, false);
    int nTilt = b.AddFloats({0.6f, 0, 0.8f, 0.6f, 0, 0.8f, 0.6f, 0, 0.8f, 0.6f, 0, 0.8f}, 3, false);
    int uv = b.AddFloats({0, 0, 1, 0, 1, 1, 0, 1}, 2, false);
    int i8 = b.AddIndices(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, kUByte);
    int i16 = b.AddIndices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kUShort);
    int i32 = b.AddIndices(std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, kUInt);
    int strip = b.AddFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, 3, true);

    int m0 =
        b.AddMesh("quad_u16", {b.Primitive({{"POSITION", quad}, {"NORMAL", nUp}, {"TEXCOORD_0", uv}}, i16)});
    int m1 = b.AddMesh("quad_u8", {b.Primitive({{"POSITION", quad}, {"NORMAL", nUp}}, i8),
                                   b.Primitive({{"POSITION", quad}}, -1, 0)});  // POINTS: skipped
    int m2 = b.AddMesh("quad_u32", {b.Primitive({{"POSITION", quad}, {"NORMAL", nTilt}}, i32)});
    int m3 = b.AddMesh("strip", {b.Primitive({{"POSITION", strip}, {"NORMAL", nUp}}, -1, 5)});

    // parent: T(1,2,3)·R_z(180°)·S(2); child: matrix = T(0,0,1)·R_x(90°) (column-major).
    int parent = b.AddNode("parent",
                           "\"children\":[1],\"translation\":[1,2,3],\"rotation\":[0,0,1,0],"
                           "\"scale\":[2,2,2]");
    b.AddNode("child",
              "\"mesh\":" + std::to_string(m0) + ",\"matrix\":[1,0,0,0, 0,0,1,0, 0,-1,0,0, 0,0,1,1]");
    int plain = b.AddNode("plain", "\"mesh\":" + std::to_string(m1));
    int scaled = b.AddNode(
        "scaled", "\"mesh\":" + std::to_string(m2) + ",\"matrix\":[1,0,0,0, 0,2,0,0, 0,0,3,0, -1,0,0,1]");
    int mirrored = b.AddNode("mirrored", "\"mesh\":" + std::to_string(m3) + ",\"scale\":[-1,1,1]");
    b.AddNode("orphan", "\"mesh\":" + std::to_string(m0));  // not in the scene: ignored
    b.SetSceneNodes({parent, plain, scaled, mirrored});
    return b;
}

/// A (p, q) = (2, 3) torus knot tube: centre line r(φ) = ((2 + cos qφ) cos pφ, (2 + cos qφ) sin pφ,
/// −sin qφ), swept with a circle of radius `tube` in the Frenet frame (periodic for this knot).
GltfBuilder TorusKnot() {
    const int segments = 192, sides = 12;
    const double tube = 0.45;
    auto curve = [](double phi) {
        double r = 2 + std::cos(3 * phi);
        return Vec3(r * std::cos(2 * phi), r * std::sin(2 * phi), -std::sin(3 * phi));
    };
    std::vector<float> pos, nrm, uv;
    for (int i = 0; i <= segments; ++i) {
        double phi = 2 * phasor::Pi * (i % segments) / segments, h = 1e-4;
        Vec3 c = curve(phi);
        Vec3 d1 = (curve(phi + h) - curve(phi - h)) / (2 * h);
        Vec3 d2 = (curve(phi + h) - 2 * c + curve(phi - h)) / (h * h);
        Vec3 t = phasor::Normalize(d1);
        Vec3 n = phasor::Normalize(d2 - phasor::Dot(d2, t) * t);
        Vec3 bn = phasor::Cross(t, n);
        for (int j = 0; j <= sides; ++j) {
            double a = 2 * phasor::Pi * (j % sides) / sides;
            Vec3 dir = std::cos(a) * n + std::sin(a) * bn;
            Vec3 p = c + tube * dir;
            pos.insert(pos.end(), {float(p.x), float(p.y), float(p.z)});
            nrm.insert(nrm.end(), {float(dir.x), float(dir.y), float(dir.z)});
            uv.insert(uv.end(), {float(double(i) / segments), float(double(j) / sides)});
        }
    }
    std::vector<uint16_t> idx;
    auto v = [&](int i, int j) { return uint16_t(i * (sides + 1) + j); };
    auto P = [&](uint16_t k) { return Vec3(pos[3 * k], pos[3 * k + 1], pos[3 * k + 2]); };
    auto N = [&](uint16_t k) { return Vec3(nrm[3 * k], nrm[3 * k + 1], nrm[3 * k + 2]); };
    auto tri = [&](uint16_t a, uint16_t b, uint16_t c) {
        // Wind counter-clockwise seen from outside (geometric normal along the vertex normals).
        if (phasor::Dot(phasor::Cross(P(b) - P(a), P(c) - P(a)), N(a) + N(b) + N(c)) < 0) std::swap(b, c);
        idx.insert(idx.end(), {a, b, c});
    };
    for (int i = 0; i < segments; ++i)
        for (int j = 0; j < sides; ++j) {
            tri(v(i, j), v(i + 1, j), v(i + 1, j + 1));
            tri(v(i, j), v(i + 1, j + 1), v(i, j + 1));
        }
    GltfBuilder b;
    int p = b.AddFloats(pos, 3, true), n = b.AddFloats(nrm, 3, false), t = b.AddFloats(uv, 2, false);
    int ix = b.AddIndices(idx, kUShort);
    int mesh =
        b.AddMesh("torus_knot", {b.Primitive({{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}}, ix)});
    // Root: scale 0.15 (the knot spans about ±0.5 units) and a 30° tilt about x; child: lift.
    double half = phasor::Radians(30) / 2;
    int root = b.AddNode("knot_root", "\"children\":[1],\"rotation\":[" + Num(std::sin(half)) + ",0,0," +
                                          Num(std::cos(half)) + "],\"scale\":[0.15,0.15,0.15]");
    b.AddNode("knot", "\"mesh\":" + std::to_string(mesh) + ",\"translation\":[0,0,0.5]");
    b.SetSceneNodes({root});
    return b;
}

/// A cube [-1,1]³ with each face extruded outwards by 1.3 and shrunk to 0.45: a "jack"
/// that Catmull–Clark turns into a smooth six-lobed blob; scaled by 0.7 so that the refined
/// surface spans about ±1.55. 32 vertices, 30 quads.
bool WriteJackCage(const std::string &path) {
    std::vector<Vec3> v;
    std::vector<std::vector<int>> faces;
    for (int i = 0; i < 8; ++i) v.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    const int cube[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                            {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &f : cube) {
        Vec3 c = (v[f[0]] + v[f[1]] + v[f[2]] + v[f[3]]) / 4;
        Vec3 nrm = phasor::Normalize(phasor::Cross(v[f[1]] - v[f[0]], v[f[2]] - v[f[0]]));
        int base = int(v.size());
        for (int k = 0; k < 4; ++k) v.push_back(c + 1.3 * nrm + 0.45 * (v[f[k]] - c));
        for (int k = 0; k < 4; ++k) {
            int k1 = (k + 1) % 4;
            faces.push_back({f[k], f[k1], base + k1, base + k});  // side wall
        }
        faces.push_back({base, base + 1, base + 2, base + 3});  // cap
    }
    std::ofstream out(path);
    out << "# phasor subdivision cage: cube with extruded faces (generated by phasor_make_assets)\n";
    for (const Vec3 &p : v)
        out << "v " << Num(0.7 * p.x) << " " << Num(0.7 * p.y) << " " << Num(0.7 * p.z) << "\n";
    for (const auto &f : faces)
        out << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << " " << f[3] + 1 << "\n";
    return bool(out);
}

}  // namespace

int main(int argc, char **argv) {
    if (argc != 2) {
        std::cerr << "usage: phasor_make_assets <output directory>\n";
        return 2;
    }
    std::string dir = argv[1];
    if (!dir.empty() && dir.back() != '/') dir += '/';
    GltfBuilder test = TestAsset();
    bool ok = test.WriteGltf(dir + "test_node_transform.gltf") &&
              test.WriteGlb(dir + "test_node_transform.glb") &&
              TorusKnot().WriteGlb(dir + "torus_knot.glb") && WriteJackCage(dir + "jack_cage.obj");
    if (!ok) {
        std::cerr << "phasor_make_assets: cannot write to " << dir << "\n";
        return 1;
    }
    return 0;
}
