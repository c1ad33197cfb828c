// SPDX-License-Identifier: Apache-2.0
// An independent reference for layered surfaces under extended sources (issue 20 §2, theory §0
// D15), written for the tests and sharing no code with src/materials: the transfer matrix of a
// stack of homogeneous layers per polarisation (forward/backward field amplitudes, the textbook
// interface matrix (1/t)[[1, r], [r, 1]] and the propagation diag(e^{−iφ}, e^{iφ}); Born & Wolf
// §1.6, Yeh "Optical Waves in Layered Media" ch. 5), and brute-force averages over a light's
// angular profile: a uniform disc of radius sin α and a Gaussian of variance Ω in the direction
// cosines transverse to its central direction (the irradiance measure of a `distant` source), by
// dense polar quadrature (composite Gauss–Legendre in the radius, the trapezoidal rule in the angle).
#pragma once

#include <cmath>
#include <complex>
#include <vector>

#include "core/math.h"
#include "core/numerics/gauss_legendre.h"

namespace phasor::test {

using Cplx = std::complex<double>;

struct TmmLayer {
    Cplx n;
    double d = 0;  // [m]
};

/// Power reflectance and transmittance per polarisation (T into the substrate, power flux normal
/// to the interfaces, as R + T = 1 for lossless media).
struct TmmRT {
    double Rs = 0, Rp = 0, Ts = 0, Tp = 0;
    double R() const { return 0.5 * (Rs + Rp); }
    double T() const { return 0.5 * (Ts + Tp); }
};

/// The stack `layers` (incident side first) between a real incident medium n0 and a substrate nSub,
/// for a plane wave of vacuum wavelength lambda with sinθ = sin0 in the incident medium.
inline TmmRT Tmm(double lambda, double n0, double sin0, const std::vector<TmmLayer> &layers, Cplx nSub) {
    const double k0 = 2 * Pi / lambda;
    const Cplx kappa(n0 * sin0, 0);
    // q = n·cosθ = √(n² − κ²), the branch with Im q ≥ 0 (a decaying or outgoing wave).
    auto q = [&](Cplx n) {
        Cplx r = std::sqrt(n * n - kappa * kappa);
        if (r.imag() < 0 || (r.imag() == 0 && r.real() < 0)) r = -r;
        return r;
    };
    std::vector<Cplx> ns{Cplx(n0, 0)};
    for (const TmmLayer &l : layers) ns.push_back(l.n);
    ns.push_back(nSub);
    TmmRT out;
    for (int pol = 0; pol < 2; ++pol) {
        // M = Π (interface · propagation) from the incident side; [E0+, E0−] = M·[Es+, 0].
        Cplx m00 = 1, m01 = 0, m10 = 0, m11 = 1;
        for (std::size_t j = 0; j + 1 < ns.size(); ++j) {
            const Cplx na = ns[j], nb = ns[j + 1], qa = q(na), qb = q(nb);
            Cplx r, t;
            if (pol == 0) {
                r = (qa - qb) / (qa + qb);
                t = 2.0 * qa / (qa + qb);
            } else {  // E-field coefficients of p: (n_b cosθ_a − n_a cosθ_b)/(…), cosθ = q/n
                const Cplx ca = qa / na, cb = qb / nb;
                r = (nb * ca - na * cb) / (nb * ca + na * cb);
                t = 2.0 * na * ca / (nb * ca + na * cb);
            }
            // Interface matrix (1/t)[[1, r], [r, 1]].
            const Cplx a00 = 1.0 / t, a01 = r / t;
            const Cplx n00 = m00 * a00 + m01 * a01, n01 = m00 * a01 + m01 * a00;
            const Cplx n10 = m10 * a00 + m11 * a01, n11 = m10 * a01 + m11 * a00;
            m00 = n00, m01 = n01, m10 = n10, m11 = n11;
            if (j + 2 < ns.size()) {  // then through layer j+1: diag(e^{−iφ}, e^{iφ})
                const Cplx phi = k0 * qb * layers[j].d;
                const Cplx em = std::exp(Cplx(0, -1) * phi), ep = std::exp(Cplx(0, 1) * phi);
                m00 *= em, m10 *= em, m01 *= ep, m11 *= ep;
            }
        }
        const Cplx r = m10 / m00, t = 1.0 / m00;
        const Cplx q0 = q(ns.front()), qs = q(ns.back());
        const double R = std::norm(r);
        double T;
        if (pol == 0) T = (qs.real() / q0.real()) * std::norm(t);
        else T = (std::real(qs / nSub * std::conj(nSub)) / std::real(q0 / ns.front() * std::conj(ns.front()))) * std::norm(t);
        (pol == 0 ? out.Rs : out.Rp) = R;
        (pol == 0 ? out.Ts : out.Tp) = T;
    }
    return out;
}

/// Quadrature sizes for DiscAverage / GaussianAverage when the integrand's phase changes by at most
/// `phase` [rad] across the profile: Gauss–Legendre panels of ≤ 5 rad each in the radius (8 nodes
/// integrate a 5 rad oscillation to ~1e-7 of its amplitude, A&S 25.4.30) and trapezoid points resolving
/// the phase around a circle (≤ phase/2 rad per half-turn at the rim: the rule is spectrally
/// accurate once it has ≳ 1 point per radian, plus a margin).
struct PolarResolution {
    int panels = 4, angles = 64;
    static PolarResolution For(double phase) {
        return {std::max(4, int(std::ceil(phase / 5)) + 2), std::max(64, int(std::ceil(phase)) + 48)};
    }
};

/// An orthonormal basis (e1, e2) ⊥ axis.
inline void Basis(const Vec3 &axis, Vec3 *e1, Vec3 *e2) {
    const Vec3 h = std::abs(axis.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    *e1 = Normalize(h - axis * Dot(h, axis));
    *e2 = Cross(axis, *e1);
}

/// The direction with transverse direction cosines (x, y) about `axis`.
inline Vec3 AboutAxis(const Vec3 &axis, const Vec3 &e1, const Vec3 &e2, double x, double y) {
    return e1 * x + e2 * y + axis * std::sqrt(std::max(0.0, 1 - x * x - y * y));
}

/// ⟨f⟩ over the directions whose transverse direction cosines about `axis` lie in a disc of radius
/// `radius`, uniformly (composite 8-point Gauss–Legendre over `panels` panels in the radius, `npsi`
/// trapezoid points in the angle). f(direction) returns a double.
template <typename F>
double DiscAverage(const Vec3 &axis, double radius, F &&f, int panels = 64, int npsi = 512) {
    Vec3 e1, e2;
    Basis(axis, &e1, &e2);
    const GaussLegendreRule &g = GaussLegendre(8);
    double sum = 0, norm = 0;
    for (int p = 0; p < panels; ++p)
        for (int i = 0; i < 8; ++i) {
            const double rho = (p + 0.5 + 0.5 * g.x[i]) * radius / panels, w = 0.5 * g.w[i] * rho;
            for (int j = 0; j < npsi; ++j) {
                const double psi = 2 * Pi * (j + 0.5) / npsi;
                sum += w * f(AboutAxis(axis, e1, e2, rho * std::cos(psi), rho * std::sin(psi)));
                norm += w;
            }
        }
    return sum / norm;
}

/// ⟨f⟩ over a Gaussian N(0, variance·I) of the transverse direction cosines about `axis`
/// (truncated at 7σ; composite Gauss–Legendre over the radius, trapezoid in the angle).
template <typename F>
double GaussianAverage(const Vec3 &axis, double variance, F &&f, int panels = 64, int npsi = 512) {
    Vec3 e1, e2;
    Basis(axis, &e1, &e2);
    const GaussLegendreRule &g = GaussLegendre(8);
    const double reach = 7 * std::sqrt(variance);
    double sum = 0, norm = 0;
    for (int p = 0; p < panels; ++p)
        for (int i = 0; i < 8; ++i) {
            const double rho = (p + 0.5 + 0.5 * g.x[i]) * reach / panels;
            const double w = 0.5 * g.w[i] * rho * std::exp(-0.5 * rho * rho / variance);
            for (int j = 0; j < npsi; ++j) {
                const double psi = 2 * Pi * (j + 0.5) / npsi;
                sum += w * f(AboutAxis(axis, e1, e2, rho * std::cos(psi), rho * std::sin(psi)));
                norm += w;
            }
        }
    return sum / norm;
}

}  // namespace phasor::test
