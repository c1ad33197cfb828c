// SPDX-License-Identifier: Apache-2.0
// phasor — triangle meshes, the shared mesh shape, ray-origin offsetting and the default
// (brute-force) Shape::Intersect.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/diagnostics.h"
#include "core/geometry/intersect.h"
#include "core/geometry/shape.h"

namespace phasor {

namespace {

double MaxAbs(const Vec3 &v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/// Determinant of the linear (upper-left 3×3) part of an affine transform.
double LinearDeterminant(const Transform &t) {
    const auto &m = t.Matrix();
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

}  // namespace

// ---- TriangleMesh ---------------------------------------------------------------------------

Bounds3 TriangleMesh::Bounds() const {
    Bounds3 b;
    for (const Vec3 &p : positions) b.Extend(p);
    return b;
}

double TriangleMesh::Area() const {
    double a = 0;
    for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
        const Vec3 &p0 = positions[indices[i]], &p1 = positions[indices[i + 1]],
                   &p2 = positions[indices[i + 2]];
        a += 0.5 * Length(Cross(p1 - p0, p2 - p0));
    }
    return a;
}

void TriangleMesh::Validate(const std::string &what) const {
    if (indices.size() % 3 != 0)
        throw Error(what + ": the index count (" + std::to_string(indices.size()) +
                    ") is not a multiple of 3");
    if (!normals.empty() && normals.size() != positions.size())
        throw Error(what + ": " + std::to_string(normals.size()) + " normals for " +
                    std::to_string(positions.size()) + " positions");
    if (!uvs.empty() && uvs.size() != positions.size())
        throw Error(what + ": " + std::to_string(uvs.size()) + " uvs for " +
                    std::to_string(positions.size()) + " positions");
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!IsFinite(positions[i])) throw Error(what + ": position " + std::to_string(i) + " is not finite");
    for (std::size_t i = 0; i < normals.size(); ++i)
        if (!IsFinite(normals[i])) throw Error(what + ": normal " + std::to_string(i) + " is not finite");
    for (std::size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= positions.size())
            throw Error(what + ": index " + std::to_string(indices[i]) + " (triangle " +
                        std::to_string(i / 3) + ") is out of range; there are " +
                        std::to_string(positions.size()) + " vertices");
}

void TriangleMesh::Transform(const phasor::Transform &t) {
    for (Vec3 &p : positions) p = t.Point(p);
    for (Vec3 &n : normals) {
        // Normals transform with the inverse transpose; renormalise afterwards.
        Vec3 m = t.Normal(n);
        double len = Length(m);
        n = len > 0 ? m / len : m;
    }
    // A mirroring transform flips the orientation of every triangle; swap two vertices so that
    // the winding (counter-clockwise seen from outside) stays consistent with the normals.
    if (LinearDeterminant(t) < 0)
        for (std::size_t i = 0; i + 2 < indices.size(); i += 3) std::swap(indices[i + 1], indices[i + 2]);
}

// ---- SurfaceInteraction ---------------------------------------------------------------------

Vec3 SurfaceInteraction::SpawnOrigin(const Vec3 &w) const {
    // Offset along the geometric normal to the side of w. The offset scales with the magnitude
    // of the coordinates: 1e-9 relative covers double-precision analytic intersections; mesh
    // shapes are intersected by Embree in float, whose rounding of vertices and ray origins is
    // ≤ 1 ulp ≤ 2^-23·|x| per coordinate, so we add 8·2^-24 (4–8 ulp) of the largest
    // coordinate of the point or of the shape's bounds (vertices may be larger than p).
    double mag = MaxAbs(p);
    double offset = 1e-9 * (1 + mag);
    if (!shape || shape->Mesh()) {
        double scale = mag;
        if (shape) {
            Bounds3 b = shape->Bounds();
            if (!b.Empty()) scale = std::max({scale, MaxAbs(b.lo), MaxAbs(b.hi)});
        }
        offset += 8 * std::ldexp(1.0, -24) * scale;
    }
    return Dot(w, n) >= 0 ? p + offset * n : p - offset * n;
}

// ---- Shape ----------------------------------------------------------------------------------

std::optional<ShapeSolidAngleSample> Shape::SampleSolidAngle(const Vec3 &, const Vec2 &) const { return std::nullopt; }
double Shape::PdfSolidAngle(const Vec3 &) const { return 0; }

std::optional<double> Shape::Intersect(const Ray &ray, double tMin, double tMax) const {
    // Reference implementation for meshes: brute force over every triangle in double precision
    // (Embree is used for real queries; this serves tests and tiny meshes).
    const TriangleMesh *mesh = Mesh();
    if (!mesh) return std::nullopt;
    std::optional<double> best;
    for (std::size_t i = 0; i + 2 < mesh->indices.size(); i += 3) {
        auto h = RayTriangle(ray, mesh->positions[mesh->indices[i]], mesh->positions[mesh->indices[i + 1]],
                             mesh->positions[mesh->indices[i + 2]], tMin, tMax);
        if (h) {
            best = h->t;
            tMax = h->t;
        }
    }
    return best;
}

// ---- MeshShape ------------------------------------------------------------------------------

MeshGeometry::MeshGeometry(TriangleMesh m, std::string k) : mesh(std::move(m)), key(std::move(k)) {
    mesh.Validate("triangle mesh");
    bounds = mesh.Bounds();
    // CDF over triangles by area for area-uniform sampling.
    std::size_t n = mesh.TriangleCount();
    areaCdf.resize(n);
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 &p0 = mesh.positions[mesh.indices[3 * i]];
        const Vec3 &p1 = mesh.positions[mesh.indices[3 * i + 1]];
        const Vec3 &p2 = mesh.positions[mesh.indices[3 * i + 2]];
        sum += 0.5 * Length(Cross(p1 - p0, p2 - p0));
        areaCdf[i] = sum;
    }
    area = sum;
}

std::size_t MeshGeometry::Bytes() const {
    return sizeof(*this) + key.size() + (mesh.positions.size() + mesh.normals.size()) * sizeof(Vec3) +
           mesh.uvs.size() * sizeof(Vec2) + mesh.indices.size() * sizeof(uint32_t) + areaCdf.size() * sizeof(double);
}

MeshShape::MeshShape(TriangleMesh mesh) : geom_(std::make_shared<const MeshGeometry>(std::move(mesh), "")) {}

MeshShape::MeshShape(std::shared_ptr<const MeshGeometry> geometry) : geom_(std::move(geometry)) {}

MeshShape::PointNormals MeshShape::PointAt(unsigned prim, double b1, double b2) const {
    const TriangleMesh &mesh = geom_->mesh;
    const uint32_t *idx = &mesh.indices[3 * std::size_t(prim)];
    const Vec3 &p0 = mesh.positions[idx[0]], &p1 = mesh.positions[idx[1]], &p2 = mesh.positions[idx[2]];
    const double b0 = 1 - b1 - b2;
    PointNormals r;
    r.p = b0 * p0 + b1 * p1 + b2 * p2;

    // Geometric normal from the winding (counter-clockwise seen from outside).
    Vec3 ng = Cross(p1 - p0, p2 - p0);
    double len = Length(ng);
    ng = len > 0 ? ng / len : Vec3(0, 0, 1);

    // Shading normal: interpolated vertex normals; the geometric normal is flipped to its side
    // so that both describe the same "outside" even when the winding disagrees with the normals.
    Vec3 ns = ng;
    if (!mesh.normals.empty()) {
        Vec3 m = b0 * mesh.normals[idx[0]] + b1 * mesh.normals[idx[1]] + b2 * mesh.normals[idx[2]];
        double ml = Length(m);
        if (ml > 0) {
            ns = m / ml;
            if (Dot(ng, ns) < 0) ng = -ng;
        }
    }
    r.ng = ng;
    r.ns = ns;
    return r;
}

SurfaceInteraction MeshShape::Interaction(const Ray &, double t, unsigned prim, double b1, double b2) const {
    const TriangleMesh &mesh = geom_->mesh;
    const uint32_t *idx = &mesh.indices[3 * std::size_t(prim)];
    const Vec3 &p0 = mesh.positions[idx[0]], &p1 = mesh.positions[idx[1]], &p2 = mesh.positions[idx[2]];
    const double b0 = 1 - b1 - b2;
    const PointNormals pn = PointAt(prim, b1, b2);

    SurfaceInteraction si;
    si.t = t;
    si.shape = this;
    si.material = material;
    si.areaLight = areaLight;
    si.p = pn.p;
    si.n = pn.ng;
    const Vec3 &ns = pn.ns;

    // Texture coordinates (default parameterisation (0,0), (1,0), (1,1) as in pbrt) and dp/du
    // from the 2×2 system dp02 = duv02.u·dpdu + duv02.v·dpdv, dp12 = duv12.u·dpdu + duv12.v·dpdv.
    Vec2 uv0(0, 0), uv1(1, 0), uv2(1, 1);
    if (!mesh.uvs.empty()) {
        uv0 = mesh.uvs[idx[0]];
        uv1 = mesh.uvs[idx[1]];
        uv2 = mesh.uvs[idx[2]];
    }
    si.uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
    Vec2 duv02 = uv0 - uv2, duv12 = uv1 - uv2;
    Vec3 dp02 = p0 - p2, dp12 = p1 - p2;
    double det = duv02.x * duv12.y - duv02.y * duv12.x;
    Vec3 dpdu;
    if (std::abs(det) > 1e-14 * (LengthSquared(duv02) + LengthSquared(duv12))) {
        dpdu = (duv12.y * dp02 - duv02.y * dp12) / det;
        si.dpdu = dpdu;
        si.dpdv = (duv02.x * dp12 - duv12.x * dp02) / det;
    } else {
        dpdu = p1 - p0;  // only orients the shading frame; si.dpdu, si.dpdv stay zero
    }
    si.shading = Frame::FromNormalTangent(ns, dpdu);
    return si;
}

ShapeSample MeshShape::Sample(const Vec2 &u) const {
    const double area = geom_->area;
    const std::vector<double> &cdf = geom_->areaCdf;
    ShapeSample ss;
    if (!(area > 0)) return ss;
    // Choose a triangle with probability proportional to its area, then reuse u.x.
    double target = u.x * area;
    auto it = std::upper_bound(cdf.begin(), cdf.end(), target);
    std::size_t i = std::min<std::size_t>(it - cdf.begin(), cdf.size() - 1);
    while (i > 0 && cdf[i] == cdf[i - 1]) --i;  // never a zero-area triangle
    double lo = i > 0 ? cdf[i - 1] : 0, hi = cdf[i];
    double ux = hi > lo ? Clamp((target - lo) / (hi - lo), 0, 1) : 0.5;

    // Uniform point on the triangle (square-root parameterisation, Osada et al. 2002).
    double su = std::sqrt(ux);
    double b1 = (1 - u.y) * su, b2 = u.y * su;
    const PointNormals pn = PointAt(unsigned(i), b1, b2);  // (no shading frame: not needed here)
    ss.p = pn.p;
    ss.n = pn.ng;
    ss.pdfArea = 1 / area;
    return ss;
}

Shape::NormalCone MeshShape::Normals() const {
    const TriangleMesh &mesh = geom_->mesh;
    const std::size_t n = mesh.TriangleCount();
    // Each triangle's normal(s) as PointAt reports them at its corners.
    std::vector<Vec3> normals;
    normals.reserve(n);
    Vec3 sum;
    for (std::size_t i = 0; i < n; ++i) {
        const unsigned prim = unsigned(i);
        const uint32_t *idx = &mesh.indices[3 * i];
        const double area = 0.5 * Length(Cross(mesh.positions[idx[1]] - mesh.positions[idx[0]],
                                               mesh.positions[idx[2]] - mesh.positions[idx[0]]));
        if (!(area > 0)) continue;  // never sampled
        const Vec3 a = PointAt(prim, 0, 0).ng, b = PointAt(prim, 1, 0).ng, c = PointAt(prim, 0, 1).ng;
        normals.push_back(a);
        if (Dot(a, b) < 0 || Dot(a, c) < 0) normals.push_back(-a);  // its corners disagree: both sides
        sum = sum + a * area;
    }
    NormalCone cone;
    const double len = Length(sum);
    if (!(len > 1e-6 * geom_->area)) return cone;  // closed or folded: all directions
    cone.w = sum / len;
    cone.cosTheta = 1;
    for (const Vec3 &v : normals) cone.cosTheta = std::min(cone.cosTheta, Dot(v, cone.w));
    // Round-off in the normals: widen by 1e-9 so that no reported normal falls outside.
    cone.cosTheta = std::max(-1.0, cone.cosTheta - 1e-9);
    return cone;
}

std::string MeshShape::ToString() const {
    const TriangleMesh &mesh = geom_->mesh;
    const double area = geom_->area;
    std::ostringstream os;
    os << "MeshShape[triangles=" << mesh.TriangleCount() << ", vertices=" << mesh.positions.size()
       << ", normals=" << (mesh.normals.empty() ? "no" : "yes")
       << ", uvs=" << (mesh.uvs.empty() ? "no" : "yes") << ", area=" << area << " m^2]";
    return os.str();
}

}  // namespace phasor
