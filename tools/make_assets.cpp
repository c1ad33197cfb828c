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
// and the cages and maps of the showcase scenes (scenes/showcase, docs/gallery.md), in cm:
//   bornite_cage.obj             an ore chip: a cube-sphere with random lumps and broken faces.
//   beetle_elytra.obj, beetle_pronotum.obj, beetle_head.obj, beetle_legs.obj
//                                a leaf beetle in four parts (one per material).
//   leaf.obj                     the leaf it sits on (an open sheet with uvs).
//   boa_cage.obj                 a rainbow boa: a tube with uvs along (u) and around (v) the body.
//   boa_skin.png                 its colour pattern over (u, v), sRGB.
//   boa_scales.png               one random (groove angle, period) pair per scale, as data.
//
// Usage: phasor_make_assets <output directory>   (normally scenes/assets)
// The glTF writer below is minimal and written for these assets only (glTF 2.0 spec §3, GLB §4).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <algorithm>
#include <array>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

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

// ---- showcase cages (scenes/showcase) -------------------------------------------------------
// Cages in centimetres (the scenes scale them by 0.01), y up. Deterministic: a fixed-seed
// generator and sums of sinusoids, no library noise.

/// A polygon cage with optional face-varying texture coordinates (ft parallels f).
struct Cage {
    std::vector<Vec3> v;
    std::vector<Vec2> vt;
    std::vector<std::vector<int>> f, ft;
    void Append(const Cage &c) {
        const int nv = int(v.size()), nt = int(vt.size());
        v.insert(v.end(), c.v.begin(), c.v.end());
        vt.insert(vt.end(), c.vt.begin(), c.vt.end());
        for (auto face : c.f) {
            for (int &i : face) i += nv;
            f.push_back(face);
        }
        for (auto face : c.ft) {
            for (int &i : face) i += nt;
            ft.push_back(face);
        }
    }
};

bool WriteCage(const std::string &path, const Cage &c, const std::string &what) {
    std::ofstream out(path);
    out << "# phasor subdivision cage: " << what << " (generated by phasor_make_assets; units: cm)\n";
    for (const Vec3 &p : c.v) out << "v " << Num(p.x) << " " << Num(p.y) << " " << Num(p.z) << "\n";
    for (const Vec2 &t : c.vt) out << "vt " << Num(t.x) << " " << Num(t.y) << "\n";
    for (std::size_t i = 0; i < c.f.size(); ++i) {
        out << "f";
        for (std::size_t k = 0; k < c.f[i].size(); ++k) {
            out << " " << c.f[i][k] + 1;
            if (!c.ft.empty()) out << "/" << c.ft[i][k] + 1;
        }
        out << "\n";
    }
    return bool(out);
}

/// A small deterministic generator (SplitMix64) for the cages' random parameters.
struct Rng {
    uint64_t s;
    double Uniform() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return double((z ^ (z >> 31)) >> 11) * 0x1p-53;
    }
    Vec3 Direction() {
        double z = 1 - 2 * Uniform(), phi = 2 * phasor::Pi * Uniform(), r = std::sqrt(std::max(0.0, 1 - z * z));
        return Vec3(r * std::cos(phi), r * std::sin(phi), z);
    }
};

/// The unit sphere as a cube of k×k quads per face projected outwards (quads only; the 8 cube
/// corners are the cage's only extraordinary vertices, of valence 3). Faces counter-clockwise
/// seen from outside.
Cage CubeSphere(int k) {
    Cage c;
    std::vector<int> index((k + 1) * (k + 1) * (k + 1), -1);
    auto vertex = [&](int i, int j, int l) {
        int &id = index[(i * (k + 1) + j) * (k + 1) + l];
        if (id < 0) {
            id = int(c.v.size());
            c.v.push_back(phasor::Normalize(Vec3(2.0 * i / k - 1, 2.0 * j / k - 1, 2.0 * l / k - 1)));
        }
        return id;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side : {0, k})
            for (int a = 0; a < k; ++a)
                for (int b = 0; b < k; ++b) {
                    std::vector<int> q;
                    for (auto [da, db] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
                        int g[3];
                        g[axis] = side;
                        g[(axis + 1) % 3] = a + da;
                        g[(axis + 2) % 3] = b + db;
                        q.push_back(vertex(g[0], g[1], g[2]));
                    }
                    // (axis+1, axis+2) is right-handed about +axis: flip the quads of the − side.
                    if (side == 0) std::swap(q[1], q[3]);
                    c.f.push_back(q);
                }
    return c;
}

/// The bornite ore: a cube-sphere of 6·12² quads, its radius modulated by a sum of 40 sinusoids
/// of random directions (lumps from 2 to ~0.3 cm), cut by 12 random planes (flat broken faces, as
/// ore chips have) and stretched to about 7 × 4.5 × 5 cm; its base flattened to sit on y = 0.
Cage Bornite() {
    Cage c = CubeSphere(12);
    Rng rng{20240117};
    struct Wave {
        Vec3 dir;
        double freq, amp, phase;
    };
    std::vector<Wave> waves;
    for (int i = 0; i < 40; ++i) {
        double freq = 1.5 + 14 * rng.Uniform() * rng.Uniform();
        waves.push_back({rng.Direction(), freq, 0.11 / std::sqrt(freq), 2 * phasor::Pi * rng.Uniform()});
    }
    std::vector<std::pair<Vec3, double>> cuts;
    for (int i = 0; i < 12; ++i) cuts.push_back({rng.Direction(), 0.7 + 0.15 * rng.Uniform()});
    for (Vec3 &p : c.v) {
        double r = 1;
        for (const Wave &w : waves) r += w.amp * std::sin(w.freq * phasor::Dot(w.dir, p) + w.phase);
        p = r * p;
        for (const auto &[n, d] : cuts) {
            double h = phasor::Dot(p, n);
            if (h > d) p = p - (h - d) * n;
        }
        p = Vec3(3.5 * p.x, 2.3 * p.y, 2.6 * p.z);
        if (p.y < -1.6) p.y = -1.6;  // the base it rests on
        p.y += 1.6;
    }
    return c;
}

/// An ellipsoid (semi-axes r, centre c) as a cube-sphere of k×k quads per face; points below
/// y = floor are pressed onto it (a flat underside).
Cage Ellipsoid(Vec3 c, Vec3 r, int k, double floor) {
    Cage e = CubeSphere(k);
    for (Vec3 &p : e.v) p = Vec3(c.x + r.x * p.x, std::max(floor, c.y + r.y * p.y), c.z + r.z * p.z);
    return e;
}

/// A tube of `sides` vertices per ring along the polyline `path` with radius `radius[i]` at
/// point i (frames by parallel transport, ring scaled by `flatten` along the frame axis nearest
/// to +y), closed by an n-gon at each end. With `uv`: u = arc length / total along the tube,
/// v = angle / 2π around it (the seam repeated at v = 1), the caps on single uvs.
Cage Tube(const std::vector<Vec3> &path, const std::vector<double> &radius, int sides, double flatten, bool uv) {
    Cage c;
    const int n = int(path.size());
    std::vector<double> arc(n, 0);
    for (int i = 1; i < n; ++i) arc[i] = arc[i - 1] + phasor::Length(path[i] - path[i - 1]);
    Vec3 up(0, 1, 0);
    Vec3 t0 = phasor::Normalize(path[1] - path[0]);
    Vec3 nrm = phasor::Normalize(phasor::Cross(t0, phasor::Cross(up, t0)));  // ⊥ t0, towards +y
    if (!(phasor::Length(nrm) > 0.5)) nrm = Vec3(1, 0, 0);
    for (int i = 0; i < n; ++i) {
        Vec3 t = phasor::Normalize(path[std::min(i + 1, n - 1)] - path[std::max(i - 1, 0)]);
        nrm = phasor::Normalize(nrm - phasor::Dot(nrm, t) * t);  // parallel transport
        Vec3 bn = phasor::Cross(t, nrm);
        for (int k = 0; k < sides; ++k) {
            double a = 2 * phasor::Pi * k / sides;
            c.v.push_back(path[i] + radius[i] * (flatten * std::cos(a) * nrm + std::sin(a) * bn));
        }
        if (uv)
            for (int k = 0; k <= sides; ++k) c.vt.push_back(Vec2(arc[i] / arc[n - 1], double(k) / sides));
    }
    const int capStart = int(c.vt.size());
    if (uv) {
        c.vt.push_back(Vec2(0, 0.5));
        c.vt.push_back(Vec2(1, 0.5));
    }
    for (int i = 0; i + 1 < n; ++i)
        for (int k = 0; k < sides; ++k) {
            // Counter-clockwise from outside: the ring turns counter-clockwise about t (from nrm
            // to bn = t × nrm), so around the ring first, then back along the tube.
            c.f.push_back({i * sides + k, i * sides + (k + 1) % sides, (i + 1) * sides + (k + 1) % sides, (i + 1) * sides + k});
            if (uv)
                c.ft.push_back({i * (sides + 1) + k, i * (sides + 1) + k + 1, (i + 1) * (sides + 1) + k + 1,
                                (i + 1) * (sides + 1) + k});
        }
    std::vector<int> first, last;
    for (int k = 0; k < sides; ++k) {
        first.push_back(sides - 1 - k);  // normal −t at the start
        last.push_back((n - 1) * sides + k);  // +t at the end
    }
    c.f.push_back(first);
    c.f.push_back(last);
    if (uv) {
        c.ft.push_back(std::vector<int>(sides, capStart));
        c.ft.push_back(std::vector<int>(sides, capStart + 1));
    }
    return c;
}

/// The volume enclosed by a closed cage (faces fanned from their first vertex): positive when
/// every face is counter-clockwise seen from outside. The generators check their cages with it.
double SignedVolume(const Cage &c) {
    double vol = 0;
    for (const auto &f : c.f)
        for (std::size_t k = 1; k + 1 < f.size(); ++k)
            vol += phasor::Dot(c.v[f[0]], phasor::Cross(c.v[f[k]], c.v[f[k + 1]])) / 6;
    return vol;
}

/// A leaf beetle (Chrysomelidae), about 1.1 cm long, head towards +z, resting on y = 0: elytra
/// (one dome, its suture a shallow groove), pronotum and head (flattened ellipsoids), and six short legs
/// and two beaded antennae (tubes) — four cages, one per material.
Cage BeetleElytra() {
    Cage e = Ellipsoid(Vec3(0, 0.29, -0.12), Vec3(0.34, 0.29, 0.50), 6, 0.12);
    for (Vec3 &p : e.v)
        if (std::abs(p.x) < 1e-9 && p.y > 0.3) p.y -= 0.015;  // the suture between the two elytra
    return e;
}
Cage BeetlePronotum() { return Ellipsoid(Vec3(0, 0.27, 0.40), Vec3(0.29, 0.15, 0.16), 4, 0.15); }
Cage BeetleHead() { return Ellipsoid(Vec3(0, 0.22, 0.57), Vec3(0.14, 0.10, 0.09), 4, 0.13); }
Cage BeetleLegs() {
    Cage legs;
    for (double side : {-1.0, 1.0}) {
        // Legs: from under the body out, up over the femur's knee, down to the ground, tarsus forward.
        const double z0[3] = {0.36, 0.10, -0.12}, swing[3] = {0.16, 0.0, -0.2};
        for (int i = 0; i < 3; ++i) {
            const double z = z0[i], dz = swing[i];
            std::vector<Vec3> path = {Vec3(side * 0.08, 0.14, z), Vec3(side * 0.22, 0.16, z + 0.3 * dz),
                                      Vec3(side * 0.32, 0.15, z + 0.6 * dz), Vec3(side * 0.37, 0.09, z + 0.8 * dz),
                                      Vec3(side * 0.40, 0.03, z + dz), Vec3(side * 0.43, 0.025, z + dz + 0.07 * (dz >= 0 ? 1 : -1))};
            legs.Append(Tube(path, {0.055, 0.055, 0.045, 0.036, 0.03, 0.026}, 6, 1, false));
        }
        // An antenna: eleven beads forward and outwards from the front of the head.
        std::vector<Vec3> path;
        std::vector<double> radius;
        for (int k = 0; k <= 12; ++k) {
            const double t = k / 12.0;
            path.push_back(Vec3(side * (0.06 + 0.16 * t), 0.25 + 0.05 * std::sin(2.5 * t), 0.62 + 0.32 * t));
            radius.push_back((k % 2 ? 0.016 : 0.022) * (1 + 0.5 * t));
        }
        legs.Append(Tube(path, radius, 6, 1, false));
    }
    return legs;
}

/// A leaf about 6 cm long (along z) and 3 cm wide on which the beetle sits: an open 10×6 grid of
/// quads with a pointed outline, a midrib groove and edges curling down; uvs u along, v across.
Cage Leaf() {
    Cage c;
    const int nu = 10, nv = 6;
    for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nv; ++j) {
            const double u = double(i) / nu, v = double(j) / nv, across = 2 * v - 1;
            const double halfWidth = 1.6 * std::pow(std::sin(phasor::Pi * std::min(1.0, 0.04 + 0.96 * u)), 0.8) + 0.05;
            const double x = across * halfWidth, z = -3.2 + 6.4 * u;
            const double y = -0.35 * across * across * halfWidth / 1.6 + 0.08 * std::abs(across) - 0.1 * (u - 0.5) * (u - 0.5);
            c.v.push_back(Vec3(x, y, z));
            c.vt.push_back(Vec2(u, v));
        }
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const int a = i * (nv + 1) + j;
            c.f.push_back({a, a + nv + 1, a + nv + 2, a + 1});  // normal +y
            c.ft.push_back({a, a + nv + 1, a + nv + 2, a + 1});
        }
    return c;
}

/// Half-thickness of the boa at t ∈ [0, 1] along it (head at t = 0) [cm]: snout, head, neck,
/// body, tail tip.
double BoaRadius(double t) {
    if (t < 0.06) {
        const double x = t / 0.06;  // snout → head (widest at x ≈ 0.45) → neck
        return 1.2 + 2.2 * std::sin(phasor::Pi * std::min(1.0, 1.1 * x)) * (1 - 0.35 * x) + 1.2 * x * x;
    }
    if (t < 0.75) return 2.4 + 1.4 * std::sin(phasor::Pi * std::min(1.0, (t - 0.06) / 0.75));
    return 0.3 + 2.9 * std::pow(1 - (t - 0.75) / 0.25, 0.9);
}

/// The centre line of the boa (head at t = 0) [cm]: along −x on the ground, the head and neck
/// straight (x > 40 cm: a long stretch where the ridges' rainbow stripe runs along the body), then
/// an S-curve of 17 cm amplitude; the head slightly raised; the body rests on y = 0.
std::vector<Vec3> BoaPath(int n) {
    std::vector<Vec3> path;
    for (int i = 0; i < n; ++i) {
        const double t = double(i) / (n - 1), x = 75 - 150 * t;
        const double lift = t < 0.1 ? 2.5 * (1 - t / 0.1) * (1 - t / 0.1) : 0;
        const double straight = std::clamp((x - 10) / 30, 0.0, 1.0);  // 1 over the head and neck
        const double bend = 1 - straight * straight * (3 - 2 * straight);
        path.push_back(Vec3(x, 0.8 * BoaRadius(t) + lift, 17 * bend * std::sin(2 * phasor::Pi * x / 100 - 0.5 * phasor::Pi)));
    }
    return path;
}

/// The boa's length along its centre line [cm] (the skin's scale along u).
double BoaLength() {
    const std::vector<Vec3> p = BoaPath(4001);
    double length = 0;
    for (std::size_t i = 1; i < p.size(); ++i) length += phasor::Length(p[i] - p[i - 1]);
    return length;
}

/// A rainbow boa of about 2 m crawling on the ground: a tube of 8 sides along BoaPath, flattened
/// to 0.8 of its width; uvs u = arc length / length (along the body: dp/du is the body's axis,
/// from which a grating's groove angle is measured), v around it (v = 0 on the back, 0.5 on the
/// belly).
Cage Boa() {
    const int n = 100;
    std::vector<double> radius;
    for (int i = 0; i < n; ++i) radius.push_back(BoaRadius(double(i) / (n - 1)));
    return Tube(BoaPath(n), radius, 8, 0.8, true);
}

/// The boa's skin (Epicrates cenchria's pattern, drawn): an orange-brown back with dark rings
/// (light centres) every ~7 cm, dark lateral spots with pale centres, a pale belly. RGB, 512×64,
/// u across (along the body), v up the image from the back (v = 0, bottom row) round the belly
/// (v = 0.5) to the back again. Written as an sRGB PNG through OpenImageIO.
bool WriteBoaSkin(const std::string &path) {
    const int w = 512, h = 64;
    std::vector<uint8_t> px(std::size_t(w) * h * 3);
    auto srgb = [](double x) {
        x = std::clamp(x, 0.0, 1.0);
        x = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
        return uint8_t(std::lround(255 * x));
    };
    const double bodyLength = BoaLength(), girth = 20;  // cm per unit of u, of v
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const double u = (i + 0.5) / w, v = 1 - (j + 0.5) / h;  // row 0 is the top (v → 1)
            const double around = std::min(v, 1 - v);  // 0 on the back, 0.5 on the belly
            // Base colour: orange-brown back fading to a pale belly.
            const double belly = std::clamp((around - 0.3) / 0.12, 0.0, 1.0);
            double r = 0.42 + 0.25 * belly, g = 0.17 + 0.25 * belly, b = 0.06 + 0.2 * belly;
            // Dorsal rings: distance from the ring centres on the back, in cm.
            const double su = u * bodyLength, sv = around * girth, period = 7;
            const double du = su - period * std::round(su / period);
            const double dorsal = std::hypot(du, sv * 1.2);
            // Lateral spots, between the rings, on both flanks.
            const double du2 = su - period * (std::round(su / period - 0.5) + 0.5);
            const double lateral = std::hypot(du2, (sv - 0.3 * girth) * 1.3);
            double dark = 0, light = 0;
            if (u > 0.04 && u < 0.97) {
                dark = std::max(std::exp(-std::pow((dorsal - 1.6) / 0.45, 2)), std::exp(-std::pow(lateral / 0.9, 2)));
                light = std::max(std::exp(-std::pow(dorsal / 0.9, 2)) * 0.6, std::exp(-std::pow(lateral / 0.35, 2)) * 0.5);
            }
            r = r * (1 - 0.85 * dark) + 0.25 * light;
            g = g * (1 - 0.85 * dark) + 0.12 * light;
            b = b * (1 - 0.85 * dark) + 0.05 * light;
            uint8_t *p = &px[(std::size_t(j) * w + i) * 3];
            p[0] = srgb(r);
            p[1] = srgb(g);
            p[2] = srgb(b);
        }
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return false;
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    return out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close();
}

/// The boa's scale map: one cell per scale (1 cm along the body by 1 cm around it, rows
/// staggered by half a cell as snake scales are), each with a random number in the red channel
/// (the scenes map it to the ridges' groove angle) and an independent one in the green channel
/// (the ridge period). Same uv layout as the skin; 3×3 texels per scale, 8 bits per channel,
/// stored as data (the scene reads it with colorspace = "raw").
bool WriteBoaScales(const std::string &path) {
    const int cellsU = int(std::lround(BoaLength())), cellsV = 20, texels = 3, w = cellsU * texels, h = cellsV * texels;
    Rng rng{1968};
    std::vector<std::array<uint8_t, 2>> cell(std::size_t(cellsU + 1) * cellsV);
    for (auto &c : cell) c = {uint8_t(std::lround(255 * rng.Uniform())), uint8_t(std::lround(255 * rng.Uniform()))};
    std::vector<uint8_t> px(std::size_t(w) * h * 3, 0);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const int row = (h - 1 - j) / texels;                     // v rows from the bottom (v = 0)
            const int col = (i + (row % 2 ? texels / 2 + 1 : 0)) / texels;  // odd rows shifted by ½ scale
            const auto &c = cell[std::size_t(row) * (cellsU + 1) + std::size_t(col)];
            uint8_t *p = &px[(std::size_t(j) * w + i) * 3];
            p[0] = c[0];
            p[1] = c[1];
        }
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return false;
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    return out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close();
}

/// Writes one cage after checking that it is closed-and-outward (positive volume) when `closed`.
bool WriteChecked(const std::string &path, const Cage &c, const std::string &what, bool closed) {
    if (closed && !(SignedVolume(c) > 0)) {
        std::cerr << "phasor_make_assets: " << what << " is wound inwards (volume " << SignedVolume(c) << ")\n";
        return false;
    }
    return WriteCage(path, c, what);
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
              TorusKnot().WriteGlb(dir + "torus_knot.glb") && WriteJackCage(dir + "jack_cage.obj") &&
              WriteChecked(dir + "bornite_cage.obj", Bornite(), "bornite ore chip", true) &&
              WriteChecked(dir + "beetle_elytra.obj", BeetleElytra(), "leaf beetle elytra", true) &&
              WriteChecked(dir + "beetle_pronotum.obj", BeetlePronotum(), "leaf beetle pronotum", true) &&
              WriteChecked(dir + "beetle_head.obj", BeetleHead(), "leaf beetle head", true) &&
              WriteChecked(dir + "beetle_legs.obj", BeetleLegs(), "leaf beetle legs and antennae", true) &&
              WriteChecked(dir + "leaf.obj", Leaf(), "leaf (open sheet, uvs)", false) &&
              WriteChecked(dir + "boa_cage.obj", Boa(), "coiled rainbow boa (uvs along and around)", true) &&
              WriteBoaSkin(dir + "boa_skin.png") && WriteBoaScales(dir + "boa_scales.png");
    if (!ok) {
        std::cerr << "phasor_make_assets: cannot write to " << dir << "\n";
        return 1;
    }
    return 0;
}
