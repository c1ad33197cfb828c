// SPDX-License-Identifier: Apache-2.0
// phasor — Wavefront OBJ reader (geometry only: v, vt, vn, f). Every malformed line is an error
// "file:line: reason"; unknown statements (o, g, s, usemtl, mtllib, l, p, …) are ignored.
#include <array>
#include <charconv>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "core/diagnostics.h"
#include "core/geometry/mesh_io.h"

namespace phasor {

namespace {

struct Corner {
    int v = -1, vt = -1, vn = -1;  // 0-based after resolution; -1 = absent
};

struct ObjData {
    std::vector<Vec3> v, vn;
    std::vector<Vec2> vt;
    std::vector<Corner> corners;
    std::vector<int> faceSizes;
    std::vector<int> faceLines;
};

class ObjReader {
  public:
    explicit ObjReader(std::string path) : path_(std::move(path)) {}

    [[noreturn]] void Fail(const std::string &reason) const {
        throw Error(path_ + ":" + std::to_string(line_) + ": " + reason);
    }

    ObjData Read(bool wantAttributes) {
        std::ifstream in(path_, std::ios::binary);
        if (!in) throw Error(path_ + ": cannot open the OBJ file");
        ObjData d;
        std::string raw, logical;
        int lineNo = 0;
        while (std::getline(in, raw)) {
            ++lineNo;
            if (!raw.empty() && raw.back() == '\r') raw.pop_back();
            // A trailing backslash continues the statement on the next line.
            if (!raw.empty() && raw.back() == '\\') {
                if (logical.empty()) line_ = lineNo;
                raw.pop_back();
                logical += raw + " ";
                continue;
            }
            if (logical.empty()) line_ = lineNo;
            logical += raw;
            ParseLine(logical, d, wantAttributes);
            logical.clear();
        }
        if (!logical.empty()) ParseLine(logical, d, wantAttributes);
        if (in.bad()) throw Error(path_ + ": read error");
        line_ = 0;
        if (d.faceSizes.empty()) throw Error(path_ + ": the OBJ file contains no faces");
        return d;
    }

    int line_ = 0;

  private:
    static std::vector<std::string_view> Split(std::string_view s) {
        std::vector<std::string_view> out;
        std::size_t i = 0;
        while (i < s.size()) {
            while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
            std::size_t j = i;
            while (j < s.size() && s[j] != ' ' && s[j] != '\t') ++j;
            if (j > i) out.push_back(s.substr(i, j - i));
            i = j;
        }
        return out;
    }

    double Number(std::string_view tok, const char *what) const {
        double v = 0;
        const char *b = tok.data(), *e = tok.data() + tok.size();
        if (b != e && *b == '+') ++b;
        auto [ptr, ec] = std::from_chars(b, e, v);
        if (ec != std::errc() || ptr != e)
            Fail(std::string("expected a number for ") + what + ", got '" + std::string(tok) + "'");
        if (!std::isfinite(v)) Fail(std::string(what) + " is not finite");
        return v;
    }

    /// Resolves a 1-based (or negative, relative) OBJ index against `count` elements so far.
    int Index(std::string_view tok, std::size_t count, const char *what) const {
        long long v = 0;
        auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
        if (ec != std::errc() || ptr != tok.data() + tok.size())
            Fail(std::string("expected an integer ") + what + " index, got '" + std::string(tok) + "'");
        if (v == 0) Fail(std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
        long long r = v > 0 ? v - 1 : (long long)count + v;
        if (r < 0 || r >= (long long)count)
            Fail(std::string(what) + " index " + std::to_string(v) + " is out of range (" +
                 std::to_string(count) + " defined so far)");
        return int(r);
    }

    void ParseLine(const std::string &line, ObjData &d, bool wantAttributes) {
        std::string_view s(line);
        if (auto hash = s.find('#'); hash != std::string_view::npos) s = s.substr(0, hash);
        auto tok = Split(s);
        if (tok.empty()) return;
        std::string_view key = tok[0];
        if (key == "v") {
            // x y z [w] or x y z r g b: only xyz is used.
            if (tok.size() < 4 || tok.size() > 8) Fail("'v' needs 3 coordinates");
            d.v.push_back({Number(tok[1], "x"), Number(tok[2], "y"), Number(tok[3], "z")});
            for (std::size_t i = 4; i < tok.size(); ++i) Number(tok[i], "an extra vertex value");
        } else if (key == "vt") {
            if (tok.size() < 2 || tok.size() > 4) Fail("'vt' needs 1 to 3 coordinates");
            double u = Number(tok[1], "u"), v = tok.size() > 2 ? Number(tok[2], "v") : 0;
            if (tok.size() > 3) Number(tok[3], "w");
            d.vt.push_back({u, v});
        } else if (key == "vn") {
            if (tok.size() != 4) Fail("'vn' needs 3 coordinates");
            d.vn.push_back({Number(tok[1], "x"), Number(tok[2], "y"), Number(tok[3], "z")});
        } else if (key == "f") {
            if (tok.size() < 4)
                Fail("a face needs at least 3 vertices, got " + std::to_string(tok.size() - 1));
            for (std::size_t i = 1; i < tok.size(); ++i) {
                std::string_view c = tok[i];
                Corner k;
                std::size_t s1 = c.find('/');
                k.v = Index(c.substr(0, s1), d.v.size(), "vertex");
                if (s1 != std::string_view::npos) {
                    std::string_view rest = c.substr(s1 + 1);
                    std::size_t s2 = rest.find('/');
                    std::string_view t = rest.substr(0, s2);
                    if (!t.empty() && wantAttributes) k.vt = Index(t, d.vt.size(), "texture coordinate");
                    if (s2 != std::string_view::npos) {
                        std::string_view nrm = rest.substr(s2 + 1);
                        if (nrm.find('/') != std::string_view::npos)
                            Fail("malformed face vertex '" + std::string(c) + "'");
                        if (nrm.empty()) Fail("malformed face vertex '" + std::string(c) + "'");
                        if (wantAttributes) k.vn = Index(nrm, d.vn.size(), "normal");
                    } else if (t.empty()) {
                        Fail("malformed face vertex '" + std::string(c) + "'");
                    }
                }
                d.corners.push_back(k);
            }
            d.faceSizes.push_back(int(tok.size() - 1));
            d.faceLines.push_back(line_);
        }
        // Anything else (o, g, s, usemtl, mtllib, l, p, curves…) carries no triangle geometry.
    }

    std::string path_;
};

}  // namespace

TriangleMesh LoadObj(const std::string &path) {
    ObjReader reader(path);
    ObjData d = reader.Read(true);

    // Normals are kept only if every corner has one (otherwise the geometric normal is used
    // everywhere); missing texture coordinates become (0, 0).
    bool allNormals = true, anyUv = false;
    for (const Corner &c : d.corners) {
        allNormals &= c.vn >= 0;
        anyUv |= c.vt >= 0;
    }

    // OBJ indexes v, vt and vn separately; weld each distinct triple into one vertex.
    struct Hash {
        std::size_t operator()(const std::array<int, 3> &k) const {
            uint64_t h = uint64_t(uint32_t(k[0])) * 0x9E3779B97F4A7C15ull;
            h ^= (uint64_t(uint32_t(k[1])) + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2));
            h ^= (uint64_t(uint32_t(k[2])) + 0x85EBCA77C2B2AE63ull + (h << 6) + (h >> 2));
            return std::size_t(h);
        }
    };
    std::unordered_map<std::array<int, 3>, uint32_t, Hash> welded;
    welded.reserve(d.corners.size());
    TriangleMesh mesh;
    std::vector<uint32_t> faceVerts;
    std::size_t c = 0;
    for (std::size_t f = 0; f < d.faceSizes.size(); ++f) {
        faceVerts.clear();
        for (int k = 0; k < d.faceSizes[f]; ++k, ++c) {
            const Corner &cr = d.corners[c];
            std::array<int, 3> key{cr.v, anyUv ? cr.vt : -1, allNormals ? cr.vn : -1};
            auto [it, inserted] = welded.try_emplace(key, uint32_t(mesh.positions.size()));
            if (inserted) {
                mesh.positions.push_back(d.v[cr.v]);
                if (allNormals) {
                    Vec3 n = d.vn[cr.vn];
                    double len = Length(n);
                    if (!(len > 0)) {
                        reader.line_ = d.faceLines[f];
                        reader.Fail("face uses a zero-length normal");
                    }
                    mesh.normals.push_back(n / len);
                }
                if (anyUv) mesh.uvs.push_back(cr.vt >= 0 ? d.vt[cr.vt] : Vec2(0, 0));
            }
            faceVerts.push_back(it->second);
        }
        // Fan triangulation (exact for convex polygons, which OBJ faces should be).
        for (std::size_t k = 1; k + 1 < faceVerts.size(); ++k) {
            mesh.indices.push_back(faceVerts[0]);
            mesh.indices.push_back(faceVerts[k]);
            mesh.indices.push_back(faceVerts[k + 1]);
        }
    }
    mesh.Validate(path);
    return mesh;
}

PolyMesh LoadObjPolygons(const std::string &path) {
    ObjReader reader(path);
    ObjData d = reader.Read(true);
    // Texture coordinates for every corner or for none (a cage half with uvs has no meaning).
    std::size_t withUv = 0;
    for (const Corner &cr : d.corners) withUv += cr.vt >= 0;
    if (withUv != 0 && withUv != d.corners.size()) {
        std::size_t c = 0;
        for (std::size_t f = 0; f < d.faceSizes.size(); c += d.faceSizes[f], ++f)
            for (int k = 0; k < d.faceSizes[f]; ++k)
                if ((d.corners[c + k].vt >= 0) != (d.corners[0].vt >= 0)) {
                    reader.line_ = d.faceLines[f];
                    reader.Fail(std::string("this face ") + (d.corners[0].vt >= 0 ? "lacks" : "has") +
                                " texture coordinates and the first face " +
                                (d.corners[0].vt >= 0 ? "has them" : "does not") +
                                ": a subdivision cage needs a 'vt' at every corner or at none");
                }
    }
    PolyMesh pm;
    pm.positions = std::move(d.v);
    if (withUv != 0) {
        pm.uvs = std::move(d.vt);
        pm.faceUvIndices.reserve(d.corners.size());
        for (const Corner &cr : d.corners) pm.faceUvIndices.push_back(cr.vt);
    }
    pm.faceSizes = std::move(d.faceSizes);
    pm.faceIndices.reserve(d.corners.size());
    std::size_t c = 0;
    for (std::size_t f = 0; f < pm.faceSizes.size(); ++f) {
        for (int k = 0; k < pm.faceSizes[f]; ++k)
            for (int j = 0; j < k; ++j)
                if (d.corners[c + k].v == d.corners[c + j].v) {
                    reader.line_ = d.faceLines[f];
                    reader.Fail("the face uses vertex " + std::to_string(d.corners[c + k].v + 1) + " twice");
                }
        for (int k = 0; k < pm.faceSizes[f]; ++k) pm.faceIndices.push_back(d.corners[c + k].v);
        c += pm.faceSizes[f];
    }
    return pm;
}

}  // namespace phasor
