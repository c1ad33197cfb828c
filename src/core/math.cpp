// SPDX-License-Identifier: Apache-2.0
#include "core/math.h"

#include <sstream>
#include <stdexcept>

namespace phasor {

std::string ToString(const Vec3 &v) {
    std::ostringstream os;
    os.precision(17);
    os << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return os.str();
}

Frame Frame::FromNormal(const Vec3 &n) {
    // Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017).
    double sign = std::copysign(1.0, n.z);
    double a = -1.0 / (sign + n.z);
    double b = n.x * n.y * a;
    Frame f;
    f.n = n;
    f.s = Vec3(1 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.t = Vec3(b, sign + n.y * n.y * a, -n.y);
    return f;
}

Frame Frame::FromNormalTangent(const Vec3 &n, const Vec3 &dpdu) {
    Vec3 s = dpdu - Dot(dpdu, n) * n;
    double len = Length(s);
    if (!(len > 1e-12 * (Length(dpdu) + 1e-300))) return FromNormal(n);
    Frame f;
    f.n = n;
    f.s = s / len;
    f.t = Cross(n, f.s);
    return f;
}

namespace {
using Mat = Transform::Mat;
Mat Identity() {
    Mat m{};
    for (int i = 0; i < 4; ++i) m[i][i] = 1;
    return m;
}
Mat Mul(const Mat &a, const Mat &b) {
    Mat r{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) r[i][j] += a[i][k] * b[k][j];
    return r;
}
Mat Transpose(const Mat &a) {
    Mat r{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r[i][j] = a[j][i];
    return r;
}
// Gauss–Jordan elimination with partial pivoting.
bool Invert(const Mat &in, Mat &out) {
    Mat a = in;
    out = Identity();
    for (int c = 0; c < 4; ++c) {
        int piv = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
        if (std::abs(a[piv][c]) < 1e-300) return false;
        std::swap(a[c], a[piv]);
        std::swap(out[c], out[piv]);
        double inv = 1.0 / a[c][c];
        for (int j = 0; j < 4; ++j) { a[c][j] *= inv; out[c][j] *= inv; }
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            double f = a[r][c];
            for (int j = 0; j < 4; ++j) { a[r][j] -= f * a[c][j]; out[r][j] -= f * out[c][j]; }
        }
    }
    return true;
}
}  // namespace

Transform::Transform() : m_(Identity()), mInv_(Identity()) {}

Transform::Transform(const Mat &m) : m_(m) {
    if (!Invert(m, mInv_)) throw std::invalid_argument("transform matrix is singular");
}

Transform Transform::Translate(const Vec3 &d) {
    Mat m = Identity(), mi = Identity();
    for (int i = 0; i < 3; ++i) { m[i][3] = d[i]; mi[i][3] = -d[i]; }
    return Transform(m, mi);
}

Transform Transform::Scale(const Vec3 &s) {
    if (s.x == 0 || s.y == 0 || s.z == 0) throw std::invalid_argument("scale factor is zero");
    Mat m = Identity(), mi = Identity();
    for (int i = 0; i < 3; ++i) { m[i][i] = s[i]; mi[i][i] = 1 / s[i]; }
    return Transform(m, mi);
}

Transform Transform::Rotate(double angle, const Vec3 &axis) {
    if (!(Length(axis) > 0)) throw std::invalid_argument("rotation axis has zero length");
    Vec3 a = Normalize(axis);
    double s = std::sin(angle), c = std::cos(angle);
    Mat m = Identity();
    m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
    m[0][1] = a.x * a.y * (1 - c) - a.z * s;
    m[0][2] = a.x * a.z * (1 - c) + a.y * s;
    m[1][0] = a.x * a.y * (1 - c) + a.z * s;
    m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
    m[1][2] = a.y * a.z * (1 - c) - a.x * s;
    m[2][0] = a.x * a.z * (1 - c) - a.y * s;
    m[2][1] = a.y * a.z * (1 - c) + a.x * s;
    m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
    return Transform(m, Transpose(m));
}

Transform Transform::LookAt(const Vec3 &eye, const Vec3 &target, const Vec3 &up) {
    Vec3 dir = target - eye;
    if (!(Length(dir) > 0)) throw std::invalid_argument("lookat: eye and target coincide");
    dir = Normalize(dir);
    Vec3 right = Cross(Normalize(up), dir);
    if (!(Length(right) > 1e-9)) throw std::invalid_argument("lookat: up is parallel to the view direction");
    right = Normalize(right);
    Vec3 newUp = Cross(dir, right);
    Mat m = Identity();
    for (int i = 0; i < 3; ++i) {
        m[i][0] = right[i];
        m[i][1] = newUp[i];
        m[i][2] = dir[i];
        m[i][3] = eye[i];
    }
    return Transform(m);
}

Transform Transform::operator*(const Transform &o) const {
    return Transform(Mul(m_, o.m_), Mul(o.mInv_, mInv_));
}

Vec3 Transform::Point(const Vec3 &p) const {
    return {m_[0][0] * p.x + m_[0][1] * p.y + m_[0][2] * p.z + m_[0][3],
            m_[1][0] * p.x + m_[1][1] * p.y + m_[1][2] * p.z + m_[1][3],
            m_[2][0] * p.x + m_[2][1] * p.y + m_[2][2] * p.z + m_[2][3]};
}

Vec3 Transform::Vector(const Vec3 &v) const {
    return {m_[0][0] * v.x + m_[0][1] * v.y + m_[0][2] * v.z,
            m_[1][0] * v.x + m_[1][1] * v.y + m_[1][2] * v.z,
            m_[2][0] * v.x + m_[2][1] * v.y + m_[2][2] * v.z};
}

Vec3 Transform::Normal(const Vec3 &n) const {
    return {mInv_[0][0] * n.x + mInv_[1][0] * n.y + mInv_[2][0] * n.z,
            mInv_[0][1] * n.x + mInv_[1][1] * n.y + mInv_[2][1] * n.z,
            mInv_[0][2] * n.x + mInv_[1][2] * n.y + mInv_[2][2] * n.z};
}

bool Transform::IsIdentity() const { return m_ == Identity(); }

}  // namespace phasor
