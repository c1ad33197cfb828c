// SPDX-License-Identifier: Apache-2.0
// phasor — analytic sphere and disk, double precision throughout.
#include "core/geometry/analytic.h"

#include <cmath>
#include <sstream>

#include "core/diagnostics.h"

namespace phasor {

namespace {

Vec3 Column(const Transform &t, int c) {
    const auto &m = t.Matrix();
    return {m[0][c], m[1][c], m[2][c]};
}

}  // namespace

// ---- AnalyticSphere ----------------------------------------------------------------------------

AnalyticSphere::AnalyticSphere(const Vec3 &center, double radius, const Transform &rotation)
    : center_(center), radius_(radius), rotation_(rotation) {
    if (!(radius > 0) || !std::isfinite(radius))
        throw Error("sphere: the radius must be positive and finite, got " + std::to_string(radius));
    if (!IsFinite(center)) throw Error("sphere: the center is not finite");
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(Dot(Column(rotation, i), Column(rotation, j)) - (i == j ? 1 : 0)) > 1e-9)
                throw Error("sphere: the orientation is not a rotation");
}

AnalyticSphere AnalyticSphere::FromTransform(const Vec3 &center, double radius, const Transform &toWorld) {
    // A similarity maps a sphere to a sphere: its linear part A satisfies AᵀA = s²·I.
    Vec3 c0 = Column(toWorld, 0), c1 = Column(toWorld, 1), c2 = Column(toWorld, 2);
    double s = std::cbrt(std::abs(Dot(c0, Cross(c1, c2))));
    if (!(s > 0) || !std::isfinite(s)) throw Error("sphere: to_world is singular");
    const Vec3 cols[3] = {c0 / s, c1 / s, c2 / s};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(Dot(cols[i], cols[j]) - (i == j ? 1 : 0)) > 1e-9)
                throw Error(
                    "sphere: to_world must be a rotation, uniform scale and translation "
                    "(a non-uniform scale or shear would make an ellipsoid)");
    Transform::Mat r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[i][j] = cols[j][i];
    r[3][3] = 1;
    Transform::Mat rt{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) rt[i][j] = r[j][i];
    return AnalyticSphere(toWorld.Point(center), radius * s, Transform(r, rt));
}

std::optional<double> AnalyticSphere::Intersect(const Ray &ray, double tMin, double tMax) const {
    // |o + t·d − c|² = r²  ⇔  a·t² + 2b·t + c = 0 with a = d·d, b = (o−c)·d,
    // c = |o−c|² − r².
    Vec3 oc = ray.o - center_;
    double a = LengthSquared(ray.d);
    double b = Dot(oc, ray.d);
    // Discriminant b² − a·c in the cancellation-free form a·(r² − |oc − (b/a)·d|²)
    // (Haines et al., "Precision improvements for ray/sphere intersection", Ray Tracing Gems 2019).
    Vec3 f = oc - (b / a) * ray.d;
    double fl = Length(f);
    double disc = a * (radius_ - fl) * (radius_ + fl);
    if (!(disc >= 0)) return std::nullopt;
    // Stable roots (Numerical Recipes §5.6): q = −(b + sign(b)·√disc), t0 = q/a, t1 = c/q.
    double q = -(b + std::copysign(std::sqrt(disc), b));
    double ocl = Length(oc);
    double c = (ocl - radius_) * (ocl + radius_);
    double t0, t1;
    if (q == 0) {
        t0 = t1 = -b / a;
    } else {
        t0 = q / a;
        t1 = c / q;
    }
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > tMin && t0 < tMax) return t0;
    if (t1 > tMin && t1 < tMax) return t1;
    return std::nullopt;
}

SurfaceInteraction AnalyticSphere::Interaction(const Ray &ray, double t, unsigned, double, double) const {
    SurfaceInteraction si;
    si.t = t;
    si.shape = this;
    si.material = material;
    si.areaLight = areaLight;
    // Project the hit back onto the sphere (removes the rounding of o + t·d).
    Vec3 d = ray.At(t) - center_;
    double len = Length(d);
    Vec3 n = len > 0 ? d / len : Vec3(0, 0, 1);
    si.p = center_ + radius_ * n;
    si.n = n;
    Vec3 l = rotation_.Inverse().Vector(n);
    double phi = std::atan2(l.y, l.x);
    if (phi < 0) phi += 2 * Pi;
    double theta = std::acos(Clamp(l.z, -1, 1));
    si.uv = Vec2(phi * Inv2Pi, theta * InvPi);
    // ∂p/∂u is along the local azimuthal direction (−y, x, 0); it vanishes at the poles, where
    // Frame::FromNormalTangent falls back to an arbitrary tangent.
    Vec3 dpdu = rotation_.Vector(Vec3(-l.y, l.x, 0));
    si.shading = Frame::FromNormalTangent(n, dpdu);
    // p = c + r·(sinθ cosφ, sinθ sinφ, cosθ) with u = φ/2π, v = θ/π.
    si.dpdu = (2 * Pi * radius_) * dpdu;
    si.dpdv = (Pi * radius_) * rotation_.Vector(Vec3(l.z * std::cos(phi), l.z * std::sin(phi), -std::sin(theta)));
    return si;
}

Bounds3 AnalyticSphere::Bounds() const {
    Vec3 r(radius_, radius_, radius_);
    Bounds3 b;
    b.Extend(center_ - r);
    b.Extend(center_ + r);
    return b;
}

double AnalyticSphere::Area() const { return 4 * Pi * radius_ * radius_; }

ShapeSample AnalyticSphere::Sample(const Vec2 &u) const {
    // Uniform direction: z uniform in [−1, 1] (Archimedes), φ uniform.
    double z = 1 - 2 * u.x;
    double rr = SafeSqrt(1 - z * z);
    double phi = 2 * Pi * u.y;
    Vec3 n(rr * std::cos(phi), rr * std::sin(phi), z);
    ShapeSample s;
    s.n = n;
    s.p = center_ + radius_ * n;
    s.pdfArea = 1 / Area();
    return s;
}

std::string AnalyticSphere::ToString() const {
    std::ostringstream os;
    os.precision(17);
    os << "AnalyticSphere[center=" << phasor::ToString(center_) << " m, radius=" << radius_ << " m]";
    return os.str();
}

// ---- AnalyticDisk ------------------------------------------------------------------------------

AnalyticDisk::AnalyticDisk(double radius, const Transform &toWorld)
    : radius_(radius), toWorld_(toWorld), toLocal_(toWorld.Inverse()) {
    if (!(radius > 0) || !std::isfinite(radius))
        throw Error("disk: the radius must be positive and finite, got " + std::to_string(radius));
    // The affine image of the disk has area π r² |A·x̂ × A·ŷ|.
    Vec3 cross = Cross(Column(toWorld, 0), Column(toWorld, 1));
    double scale = Length(cross);
    if (!(scale > 0) || !std::isfinite(scale)) throw Error("disk: to_world is singular");
    area_ = Pi * radius * radius * scale;
    Vec3 n = toWorld.Normal(Vec3(0, 0, 1));
    normal_ = Normalize(n);
}

std::optional<double> AnalyticDisk::Intersect(const Ray &ray, double tMin, double tMax) const {
    // In local space the disk lies in z = 0; t is invariant under the affine map because the
    // direction is mapped without renormalisation.
    Vec3 o = toLocal_.Point(ray.o), d = toLocal_.Vector(ray.d);
    if (d.z == 0) return std::nullopt;
    double t = -o.z / d.z;
    if (!(t > tMin && t < tMax)) return std::nullopt;
    double x = o.x + t * d.x, y = o.y + t * d.y;
    if (x * x + y * y > radius_ * radius_) return std::nullopt;
    return t;
}

SurfaceInteraction AnalyticDisk::Interaction(const Ray &ray, double t, unsigned, double, double) const {
    Vec3 o = toLocal_.Point(ray.o), d = toLocal_.Vector(ray.d);
    double x = o.x + t * d.x, y = o.y + t * d.y;
    SurfaceInteraction si;
    si.t = t;
    si.shape = this;
    si.material = material;
    si.areaLight = areaLight;
    si.p = toWorld_.Point(Vec3(x, y, 0));
    si.n = normal_;
    double phi = std::atan2(y, x);
    if (phi < 0) phi += 2 * Pi;
    si.uv = Vec2(phi * Inv2Pi, std::sqrt(x * x + y * y) / radius_);
    si.shading = Frame::FromNormalTangent(normal_, toWorld_.Vector(Vec3(-y, x, 0)));
    // p = to_world·(ρ cosφ, ρ sinφ, 0) with u = φ/2π, v = ρ/radius.
    si.dpdu = toWorld_.Vector(Vec3(-2 * Pi * y, 2 * Pi * x, 0));
    si.dpdv = toWorld_.Vector(Vec3(radius_ * std::cos(phi), radius_ * std::sin(phi), 0));
    return si;
}

Bounds3 AnalyticDisk::Bounds() const {
    // Exact box of an ellipse c + r·(cos φ·a + sin φ·b): half-extent r·√(a_i² + b_i²).
    Vec3 a = Column(toWorld_, 0), b = Column(toWorld_, 1);
    Vec3 c = toWorld_.Point(Vec3(0, 0, 0));
    Vec3 e(radius_ * std::hypot(a.x, b.x), radius_ * std::hypot(a.y, b.y), radius_ * std::hypot(a.z, b.z));
    Bounds3 bb;
    bb.Extend(c - e);
    bb.Extend(c + e);
    return bb;
}

ShapeSample AnalyticDisk::Sample(const Vec2 &u) const {
    // Uniform in the local disk (ρ = r√u); an affine map has a constant Jacobian, so the image
    // is uniform by area too.
    double rho = radius_ * std::sqrt(u.x), phi = 2 * Pi * u.y;
    ShapeSample s;
    s.p = toWorld_.Point(Vec3(rho * std::cos(phi), rho * std::sin(phi), 0));
    s.n = normal_;
    s.pdfArea = 1 / area_;
    return s;
}

std::string AnalyticDisk::ToString() const {
    std::ostringstream os;
    os.precision(17);
    os << "AnalyticDisk[radius=" << radius_ << " m, center=" << phasor::ToString(toWorld_.Point(Vec3()))
       << " m, normal=" << phasor::ToString(normal_) << ", area=" << area_ << " m^2]";
    return os.str();
}

}  // namespace phasor
