// SPDX-License-Identifier: Apache-2.0
// phasor — the PLT beam (beam.h).
#include "core/render/beam.h"

#include <cmath>

namespace phasor {

Mueller LinearPolarizer(double angle) {
    const double c = std::cos(2 * angle), s = std::sin(2 * angle);
    Mueller m;
    const double v[4] = {1, c, s, 0};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m.m[i][j] = 0.5 * v[i] * v[j];
    return m;
}

Mueller ReciprocalMueller(const Mueller &m) {
    Mueller r;
    const double p[4] = {1, 1, -1, 1};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = p[i] * m.m[j][i] * p[j];
    return r;
}

double AngleAbout(const Vec3 &from, const Vec3 &to, const Vec3 &d) {
    return std::atan2(Dot(Cross(from, to), d), Dot(from, to));
}

Stokes RotateStokesFrame(const Stokes &s, const Vec3 &from, const Vec3 &to, const Vec3 &d) {
    // A field component along the new axis x' = cosψ·x + sinψ·y: E' = Q·E with Q = [[c, s], [−s, c]],
    // so S1' = cos2ψ·S1 + sin2ψ·S2, S2' = −sin2ψ·S1 + cos2ψ·S2 = Rotation(−ψ)·S (theory §4.9).
    return Mueller::Rotation(-AngleAbout(from, to, d)) * s;
}

Vec3 PerpendicularTo(const Vec3 &d, const Vec3 &hint) {
    const Vec3 p = hint - d * Dot(hint, d);
    const double l = Length(p);
    if (l > 1e-9 * std::max(1.0, Length(hint))) return p / l;
    return Frame::FromNormal(d).s;
}

PltBeam PltBeam::Source(const Vec3 &travel, int count, double omega) {
    PltBeam b;
    b.count = count;
    for (int i = 0; i < NumWavelengths; ++i) b.S[std::size_t(i)] = Stokes{i < count ? 1.0 : 0.0, 0, 0, 0};
    b.d = Normalize(travel);
    b.t = Frame::FromNormal(b.d).s;
    b.K = Sym2::Isotropic(omega);
    return b;
}

void PltBeam::Propagate(double length) { dist += length; }

void PltBeam::RotateFrame(const Vec3 &newT) {
    const double psi = AngleAbout(t, newT, d);
    const Mueller r = Mueller::Rotation(-psi);
    for (int i = 0; i < count; ++i) S[std::size_t(i)] = r * S[std::size_t(i)];
    // Coordinates in the new basis: v' = Q·v, Q = [[c, s], [−s, c]]; K' = Q K Qᵀ.
    const double c = std::cos(psi), s = std::sin(psi);
    const double q[2][2] = {{c, s}, {-s, c}};
    const double k[2][2] = {{K.xx, K.xy}, {K.xy, K.yy}};
    double r2[2][2] = {};
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int m = 0; m < 2; ++m)
                for (int n = 0; n < 2; ++n) r2[a][b] += q[a][m] * k[m][n] * q[b][n];
    K = Sym2{r2[0][0], 0.5 * (r2[0][1] + r2[1][0]), r2[1][1]};
    t = newT;
}

void PltBeam::SetWindow(int i, double windowVariance) {
    const double omega = K.xx;
    share[std::size_t(i)] = !(omega > 0) || !(windowVariance < Infinity) ? 1.0 : windowVariance / (omega + windowVariance);
}

double PltBeam::MutualCoherence(const Vec3 &v, double k0, int i) const {
    if (K.IsZero()) return 1;
    const Vec3 y = Cross(d, t);
    return std::exp(-0.5 * k0 * k0 * share[std::size_t(i)] * K.Quadratic(Dot(v, t), Dot(v, y)));
}

void PltBeam::Interact(const Vec3 &s, const Vec3 &out, const std::array<Mueller, NumWavelengths> &m,
                       double inPlaneScale, bool resetCoherence) {
    RotateFrame(PerpendicularTo(d, s));
    for (int i = 0; i < count; ++i) S[std::size_t(i)] = m[std::size_t(i)] * S[std::size_t(i)];
    d = Normalize(out);
    t = PerpendicularTo(d, s);
    if (resetCoherence) K = Sym2{};
    else K = Sym2{K.xx, K.xy * inPlaneScale, K.yy * inPlaneScale * inPlaneScale};
}

Stokes PltBeam::Measure(int i, const Vec3 &x, const std::optional<double> &polarizer) const {
    Stokes out = RotateStokesFrame(S[std::size_t(i)], t, PerpendicularTo(d, x), d);
    if (polarizer) out = LinearPolarizer(*polarizer) * out;
    return out;
}

}  // namespace phasor
