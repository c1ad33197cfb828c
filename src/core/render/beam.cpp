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

PltBeam PltBeam::Source(const Vec3 &travel, int count) {
    PltBeam b;
    b.count = count;
    for (int i = 0; i < NumWavelengths; ++i) b.S[std::size_t(i)] = Stokes{i < count ? 1.0 : 0.0, 0, 0, 0};
    b.d = Normalize(travel);
    b.t = Frame::FromNormal(b.d).s;
    return b;
}

void PltBeam::Propagate(double length) { dist += length; }

void PltBeam::RotateFrame(const Vec3 &newT) {
    const Mueller r = Mueller::Rotation(-AngleAbout(t, newT, d));
    for (int i = 0; i < count; ++i) S[std::size_t(i)] = r * S[std::size_t(i)];
    t = newT;
}

void PltBeam::Interact(const Vec3 &s, const Vec3 &out, const std::array<Mueller, NumWavelengths> &m) {
    RotateFrame(PerpendicularTo(d, s));
    for (int i = 0; i < count; ++i) S[std::size_t(i)] = m[std::size_t(i)] * S[std::size_t(i)];
    d = Normalize(out);
    t = PerpendicularTo(d, s);
}

Stokes PltBeam::Measure(int i, const Vec3 &x, const std::optional<double> &polarizer) const {
    Stokes out = RotateStokesFrame(S[std::size_t(i)], t, PerpendicularTo(d, x), d);
    if (polarizer) out = LinearPolarizer(*polarizer) * out;
    return out;
}

}  // namespace phasor
