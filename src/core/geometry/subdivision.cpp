// SPDX-License-Identifier: Apache-2.0
// phasor — Catmull–Clark subdivision through OpenSubdiv Far: uniform refinement of a polygon
// cage, vertex positions interpolated level by level in double precision, shading normals from
// the limit-surface tangents (PrimvarRefiner::Limit) of the last level's vertices; the cage's uvs,
// if any, as a face-varying primvar.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cmath>
#include <memory>
#include <mutex>

#include "core/diagnostics.h"
#include "core/geometry/mesh_io.h"

namespace phasor {

namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

/// A primvar in the form OpenSubdiv's templates expect (Clear / AddWithWeight).
struct Point3 {
    double x = 0, y = 0, z = 0;
    void Clear(void * = nullptr) { x = y = z = 0; }
    void AddWithWeight(const Point3 &s, double w) {
        x += w * s.x;
        y += w * s.y;
        z += w * s.z;
    }
};

// OpenSubdiv reports topology errors through a global callback; collect the first message of
// the current thread so it can be thrown as a phasor::Error.
thread_local std::string osdError;
void OsdErrorCallback(Far::ErrorType, const char *message) {
    if (osdError.empty()) osdError = message ? message : "unknown OpenSubdiv error";
}
void OsdWarningCallback(const char *) {}

struct Point2 {
    double x = 0, y = 0;
    void Clear(void * = nullptr) { x = y = 0; }
    void AddWithWeight(const Point2 &s, double w) {
        x += w * s.x;
        y += w * s.y;
    }
};

/// The refined mesh with uvs: one vertex per distinct (vertex, uv value) pair of the last level's
/// face corners (a seam vertex is repeated once per chart), triangles as in `mesh`.
TriangleMesh SplitAtUvSeams(const TriangleMesh &mesh, const Far::TopologyLevel &last,
                            const std::vector<Point2> &uv) {
    TriangleMesh out;
    std::vector<std::vector<std::pair<int, uint32_t>>> copies(mesh.positions.size());  // (uv value, new vertex)
    auto vertex = [&](int v, int t) {
        for (const auto &[value, index] : copies[std::size_t(v)])
            if (value == t) return index;
        const uint32_t index = uint32_t(out.positions.size());
        out.positions.push_back(mesh.positions[std::size_t(v)]);
        out.normals.push_back(mesh.normals[std::size_t(v)]);
        out.uvs.push_back(Vec2(uv[std::size_t(t)].x, uv[std::size_t(t)].y));
        copies[std::size_t(v)].emplace_back(t, index);
        return index;
    };
    // The same triangulation as the caller's (quads split along corner 0, fans otherwise).
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        Far::ConstIndexArray fv = last.GetFaceVertices(f);
        Far::ConstIndexArray ft = last.GetFaceFVarValues(f, 0);
        for (int k = 1; k + 1 < fv.size(); ++k)
            for (int c : {0, k, k + 1}) out.indices.push_back(vertex(fv[c], ft[c]));
    }
    return out;
}

}  // namespace

PolyMesh CubeCage() {
    PolyMesh m;
    for (int i = 0; i < 8; ++i) m.positions.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    // Vertex i has x = bit 0, y = bit 1, z = bit 2. Faces counter-clockwise seen from outside.
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &f : faces) {
        m.faceSizes.push_back(4);
        for (int v : f) m.faceIndices.push_back(v);
    }
    return m;
}

TriangleMesh SubdivideCatmullClark(const PolyMesh &cage, int levels) {
    // Validate the cage (OpenSubdiv asserts rather than reports on some malformed input).
    if (levels < 0 || levels > 10)
        throw Error("subdivision: levels must be in [0, 10], got " + std::to_string(levels));
    if (cage.faceSizes.empty()) throw Error("subdivision: the cage has no faces");
    std::size_t total = 0;
    for (std::size_t f = 0; f < cage.faceSizes.size(); ++f) {
        if (cage.faceSizes[f] < 3)
            throw Error("subdivision: face " + std::to_string(f) + " has fewer than 3 vertices");
        total += std::size_t(cage.faceSizes[f]);
    }
    if (total != cage.faceIndices.size())
        throw Error("subdivision: face sizes sum to " + std::to_string(total) + " but there are " +
                    std::to_string(cage.faceIndices.size()) + " face indices");
    for (int v : cage.faceIndices)
        if (v < 0 || v >= int(cage.positions.size()))
            throw Error("subdivision: vertex index " + std::to_string(v) + " is out of range");
    for (const Vec3 &p : cage.positions)
        if (!IsFinite(p)) throw Error("subdivision: a cage vertex is not finite");
    const bool hasUv = !cage.faceUvIndices.empty();
    if (hasUv) {
        if (cage.faceUvIndices.size() != cage.faceIndices.size())
            throw Error("subdivision: " + std::to_string(cage.faceUvIndices.size()) + " uv indices for " +
                        std::to_string(cage.faceIndices.size()) + " face corners");
        for (int t : cage.faceUvIndices)
            if (t < 0 || t >= int(cage.uvs.size()))
                throw Error("subdivision: uv index " + std::to_string(t) + " is out of range");
        for (const Vec2 &t : cage.uvs)
            if (!std::isfinite(t.x) || !std::isfinite(t.y)) throw Error("subdivision: a cage uv is not finite");
    }

    // Topology: Catmull–Clark, sharp boundary edges and corners.
    Far::TopologyDescriptor desc;
    desc.numVertices = int(cage.positions.size());
    desc.numFaces = int(cage.faceSizes.size());
    desc.numVertsPerFace = cage.faceSizes.data();
    desc.vertIndicesPerFace = cage.faceIndices.data();
    Far::TopologyDescriptor::FVarChannel uvChannel;
    if (hasUv) {
        uvChannel.numValues = int(cage.uvs.size());
        uvChannel.valueIndices = cage.faceUvIndices.data();
        desc.numFVarChannels = 1;
        desc.fvarChannels = &uvChannel;
    }
    Sdc::Options sdcOptions;
    sdcOptions.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    // uvs: smooth inside a chart, linear only at the corners of its boundary (seams stay put).
    sdcOptions.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_CORNERS_ONLY);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;

    static std::mutex callbackMutex;  // SetErrorCallback is process-global
    std::unique_ptr<Far::TopologyRefiner> refiner;
    {
        std::lock_guard<std::mutex> lock(callbackMutex);
        osdError.clear();
        Far::SetErrorCallback(OsdErrorCallback);
        Far::SetWarningCallback(OsdWarningCallback);
        refiner.reset(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdcOptions)));
        if (!refiner || !osdError.empty())
            throw Error("subdivision: invalid cage topology: " +
                        (osdError.empty() ? std::string("rejected") : osdError));
        Far::TopologyRefiner::UniformOptions uniform(levels);
        uniform.fullTopologyInLastLevel = true;  // needed by PrimvarRefiner::Limit
        refiner->RefineUniform(uniform);
        if (!osdError.empty()) throw Error("subdivision: refinement failed: " + osdError);
    }

    // Positions, level by level (double precision).
    std::vector<Point3> src(cage.positions.size());
    for (std::size_t i = 0; i < src.size(); ++i)
        src[i] = {cage.positions[i].x, cage.positions[i].y, cage.positions[i].z};
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    for (int level = 1; level <= levels; ++level) {
        std::vector<Point3> dst(refiner->GetLevel(level).GetNumVertices());
        primvar.Interpolate(level, src, dst);
        src.swap(dst);
    }

    // uvs (face-varying), level by level.
    std::vector<Point2> uvSrc;
    if (hasUv) {
        uvSrc.resize(cage.uvs.size());
        for (std::size_t i = 0; i < uvSrc.size(); ++i) uvSrc[i] = {cage.uvs[i].x, cage.uvs[i].y};
        for (int level = 1; level <= levels; ++level) {
            std::vector<Point2> dst(refiner->GetLevel(level).GetNumFVarValues(0));
            primvar.InterpolateFaceVarying(level, uvSrc, dst, 0);
            uvSrc.swap(dst);
        }
    }

    const Far::TopologyLevel &last = refiner->GetLevel(levels);
    std::size_t nv = std::size_t(last.GetNumVertices());
    TriangleMesh mesh;
    mesh.positions.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) mesh.positions[i] = Vec3(src[i].x, src[i].y, src[i].z);

    // Limit tangents → normals (∂S/∂u × ∂S/∂v points outwards for counter-clockwise faces).
    std::vector<Point3> limitPos(nv), du(nv), dv(nv);
    {
        std::lock_guard<std::mutex> lock(callbackMutex);
        osdError.clear();
        primvar.Limit(src, limitPos, du, dv);
        if (!osdError.empty()) throw Error("subdivision: limit evaluation failed: " + osdError);
    }

    // Triangles: quads split along one diagonal; other polygons (level 0 only) as fans.
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        Far::ConstIndexArray fv = last.GetFaceVertices(f);
        for (int k = 1; k + 1 < fv.size(); ++k) {
            mesh.indices.push_back(uint32_t(fv[0]));
            mesh.indices.push_back(uint32_t(fv[k]));
            mesh.indices.push_back(uint32_t(fv[k + 1]));
        }
    }

    // Area-weighted face normals as a fallback where the limit tangents are degenerate.
    std::vector<Vec3> faceSum(nv);
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const Vec3 &p0 = mesh.positions[mesh.indices[i]], &p1 = mesh.positions[mesh.indices[i + 1]],
                   &p2 = mesh.positions[mesh.indices[i + 2]];
        Vec3 n = Cross(p1 - p0, p2 - p0);
        for (int k = 0; k < 3; ++k) faceSum[mesh.indices[i + k]] += n;
    }
    mesh.normals.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) {
        Vec3 n = Cross(Vec3(du[i].x, du[i].y, du[i].z), Vec3(dv[i].x, dv[i].y, dv[i].z));
        double len = Length(n);
        Vec3 fallback = faceSum[i];
        double flen = Length(fallback);
        if (len > 0 && std::isfinite(len)) {
            n = n / len;
            // Guard against an orientation flip of the limit frame (left-handed parameterisation).
            if (flen > 0 && Dot(n, fallback) < 0) n = -n;
        } else {
            n = flen > 0 ? fallback / flen : Vec3(0, 0, 1);
        }
        mesh.normals[i] = n;
    }
    if (hasUv) mesh = SplitAtUvSeams(mesh, last, uvSrc);
    mesh.Validate("subdivision surface");
    return mesh;
}

}  // namespace phasor
