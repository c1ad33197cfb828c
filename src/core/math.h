// SPDX-License-Identifier: Apache-2.0
// phasor — small vector maths. Everything is double precision; Embree gets floats at its boundary.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string>

namespace phasor {

inline constexpr double Pi = 3.14159265358979323846;
inline constexpr double InvPi = 1.0 / Pi;
inline constexpr double Inv2Pi = 0.5 / Pi;
inline constexpr double Inv4Pi = 0.25 / Pi;
inline constexpr double Infinity = std::numeric_limits<double>::infinity();

using Complex = std::complex<double>;

template <typename T>
constexpr T Sqr(T v) { return v * v; }
inline double Clamp(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
inline double Lerp(double t, double a, double b) { return (1 - t) * a + t * b; }
inline double SafeSqrt(double v) { return std::sqrt(std::max(0.0, v)); }
inline double Radians(double deg) { return deg * (Pi / 180.0); }
inline double Degrees(double rad) { return rad * (180.0 / Pi); }
/// The principal square root of z (Re ≥ 0; the imaginary part takes Im z's sign, signed zeros
/// included: √(−4 − 0i) = −2i) as std::sqrt gives it, without libm's csqrt handling of infinities
/// and NaN (C99 Annex G) where |z|² is a normal number: √z = (t, y/2t) for x ≥ 0, t = √((|x| + |z|)/2),
/// and (|y|/2t, ±t) for x < 0 — no cancellation on either side. Elsewhere std::sqrt.
inline Complex SqrtFinite(Complex z) {
    const double x = z.real(), y = z.imag(), m2 = x * x + y * y;
    if (!(m2 > 1e-300 && m2 < 1e300)) return std::sqrt(z);  // 0, tiny, huge, inf, NaN
    const double t = std::sqrt(0.5 * (std::abs(x) + std::sqrt(m2)));
    return x >= 0 ? Complex(t, y / (2 * t)) : Complex(std::abs(y) / (2 * t), std::copysign(t, y));
}

struct Vec2 {
    double x = 0, y = 0;
    constexpr Vec2() = default;
    constexpr Vec2(double x_, double y_) : x(x_), y(y_) {}
    double operator[](int i) const { return i == 0 ? x : y; }
    double &operator[](int i) { return i == 0 ? x : y; }
    Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
    Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
    Vec2 operator*(double s) const { return {x * s, y * s}; }
    Vec2 operator/(double s) const { return {x / s, y / s}; }
    Vec2 operator-() const { return {-x, -y}; }
    bool operator==(const Vec2 &) const = default;
};
inline Vec2 operator*(double s, Vec2 v) { return v * s; }
inline double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double LengthSquared(Vec2 v) { return Dot(v, v); }
inline double Length(Vec2 v) { return std::sqrt(Dot(v, v)); }

struct Vec3 {
    double x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    double &operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    Vec3 operator+(const Vec3 &o) const { return {x + o.x, y + o.y, z + o.z}; }
    Vec3 operator-(const Vec3 &o) const { return {x - o.x, y - o.y, z - o.z}; }
    Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    Vec3 operator*(const Vec3 &o) const { return {x * o.x, y * o.y, z * o.z}; }
    Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    Vec3 operator-() const { return {-x, -y, -z}; }
    Vec3 &operator+=(const Vec3 &o) { x += o.x; y += o.y; z += o.z; return *this; }
    Vec3 &operator-=(const Vec3 &o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    Vec3 &operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
    bool operator==(const Vec3 &) const = default;
};
inline Vec3 operator*(double s, const Vec3 &v) { return v * s; }
inline double Dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double AbsDot(const Vec3 &a, const Vec3 &b) { return std::abs(Dot(a, b)); }
inline Vec3 Cross(const Vec3 &a, const Vec3 &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double LengthSquared(const Vec3 &v) { return Dot(v, v); }
inline double Length(const Vec3 &v) { return std::sqrt(Dot(v, v)); }
inline Vec3 Normalize(const Vec3 &v) { return v / Length(v); }
inline Vec3 Min(const Vec3 &a, const Vec3 &b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 Max(const Vec3 &a, const Vec3 &b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline double MaxComponent(const Vec3 &v) { return std::max({v.x, v.y, v.z}); }
inline bool IsFinite(const Vec3 &v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
/// Mirror direction of w about the unit normal n (both pointing away from the surface).
inline Vec3 Reflect(const Vec3 &w, const Vec3 &n) { return 2 * Dot(w, n) * n - w; }
std::string ToString(const Vec3 &v);

/// Axis-aligned bounding box.
struct Bounds3 {
    Vec3 lo{Infinity, Infinity, Infinity}, hi{-Infinity, -Infinity, -Infinity};
    void Extend(const Vec3 &p) { lo = Min(lo, p); hi = Max(hi, p); }
    void Extend(const Bounds3 &b) { lo = Min(lo, b.lo); hi = Max(hi, b.hi); }
    bool Empty() const { return lo.x > hi.x; }
    Vec3 Diagonal() const { return hi - lo; }
    Vec3 Center() const { return 0.5 * (lo + hi); }
};

/// Orthonormal frame (s, t, n); ToLocal maps world vectors to (x=s, y=t, z=n) coordinates.
struct Frame {
    Vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};
    /// Builds a frame around a unit normal (Duff et al. 2017, branchless ONB).
    static Frame FromNormal(const Vec3 &n);
    /// Frame with normal n and first tangent along the projection of dpdu (falls back to FromNormal).
    static Frame FromNormalTangent(const Vec3 &n, const Vec3 &dpdu);
    Vec3 ToLocal(const Vec3 &v) const { return {Dot(v, s), Dot(v, t), Dot(v, n)}; }
    Vec3 ToWorld(const Vec3 &v) const { return s * v.x + t * v.y + n * v.z; }
};

/// Affine 4×4 transform (row-major, last row 0 0 0 1) with its inverse kept alongside.
class Transform {
  public:
    using Mat = std::array<std::array<double, 4>, 4>;
    Transform();  // identity
    Transform(const Mat &m, const Mat &mInv) : m_(m), mInv_(mInv) {}
    explicit Transform(const Mat &m);  // computes the inverse; throws on a singular matrix

    static Transform Translate(const Vec3 &d);
    static Transform Scale(const Vec3 &s);
    /// Rotation by `angle` radians about `axis` (right-handed).
    static Transform Rotate(double angle, const Vec3 &axis);
    /// Camera-to-world transform: +z looks from eye towards target, +y is up.
    static Transform LookAt(const Vec3 &eye, const Vec3 &target, const Vec3 &up);

    Transform operator*(const Transform &o) const;  // (A*B)(p) = A(B(p))
    Transform Inverse() const { return Transform(mInv_, m_); }
    Vec3 Point(const Vec3 &p) const;
    Vec3 Vector(const Vec3 &v) const;
    /// Transforms a normal (uses the inverse transpose); not normalised.
    Vec3 Normal(const Vec3 &n) const;
    const Mat &Matrix() const { return m_; }
    bool IsIdentity() const;
    bool operator==(const Transform &o) const { return m_ == o.m_; }

  private:
    Mat m_, mInv_;
};

}  // namespace phasor
