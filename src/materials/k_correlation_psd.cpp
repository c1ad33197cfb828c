// SPDX-License-Identifier: Apache-2.0
// phasor — the K-correlation PSD of `harvey_shack` and its visible-mass table (k_correlation_psd.h).
#include "materials/k_correlation_psd.h"

#include <map>
#include <mutex>

#include "core/math.h"
#include "core/numerics/gauss_legendre.h"

namespace phasor {

double KCorrelationPsd::Density(double t, double r2) const {
    // theory §4.3: ((γ−1)T/2π)(1 + T|ζ|²)^{−(γ+1)/2}, in ξ = ζ/k units (t = k²T).
    return (gamma_ - 1) * t * Inv2Pi * std::exp(-0.5 * (gamma_ + 1) * std::log1p(t * r2));
}

double KCorrelationPsd::RadialCdf(double t, double r) const {
    return -std::expm1(-0.5 * (gamma_ - 1) * std::log1p(t * r * r));
}

double KCorrelationPsd::InverseRadialCdf(double t, double c) const {
    // theory §4.3 step 2: r = √(((1 − c)^{−2/(γ−1)} − 1)/t).
    return std::sqrt(std::max(0.0, std::expm1(-2 / (gamma_ - 1) * std::log1p(-c))) / t);
}

double KCorrelationPsd::ArcHalfAngle(double r, double s) {
    if (r <= 1 - s) return Pi;  // the whole circle is visible (also r = 0 and s = 0 with r ≤ 1)
    if (r >= 1 + s) return 0;
    return std::acos(Clamp((r * r + s * s - 1) / (2 * r * s), -1.0, 1.0));
}

double KCorrelationPsd::VisibleMass(double s, double t) const {
    s = Clamp(s, 0.0, 1.0);
    const double c0 = RadialCdf(t, 1 - s), m = RadialCdf(t, 1 + s);
    if (!(m > c0)) return c0;
    // ∫_{c0}^{m} φ_max(P⁻¹(c), s)/π dc with c = c0 + (m − c0)(1 − cos τ)/2, dc = (m − c0)/2·sin τ dτ.
    const double half = 0.5 * (m - c0);
    auto integrand = [&](double tau) {
        const double c = c0 + half * (1 - std::cos(tau));
        return ArcHalfAngle(InverseRadialCdf(t, std::min(c, m)), s) * InvPi * std::sin(tau);
    };
    return c0 + half * IntegrateGaussLegendre(integrand, 0.0, Pi, 32, 2);
}

VisibleMassTable::VisibleMassTable(double gamma) : psd_(gamma) {
    logMin_ = std::log(TableTMin);
    logStep_ = (std::log(TableTMax) - logMin_) / (LogTNodes - 1);
    v_.resize(std::size_t(CosNodes) * LogTNodes);
    for (int j = 0; j < LogTNodes; ++j) {
        const double t = std::exp(logMin_ + j * logStep_);
        for (int i = 0; i < CosNodes; ++i) {
            const double x = double(i) / (CosNodes - 1), cosT = x * x;
            v_[std::size_t(j) * CosNodes + std::size_t(i)] = psd_.VisibleMass(SafeSqrt(1 - cosT * cosT), t);
        }
    }
}

std::shared_ptr<const VisibleMassTable> VisibleMassTable::For(double gamma) {
    static std::mutex mutex;
    static std::map<double, std::shared_ptr<const VisibleMassTable>> tables;
    std::lock_guard<std::mutex> lock(mutex);
    auto &slot = tables[gamma];
    if (!slot) slot = std::make_shared<const VisibleMassTable>(gamma);
    return slot;
}

namespace {
// Catmull–Rom weights for the four nodes around a point at fraction f ∈ [0, 1] of its interval.
void CatmullRom(double f, double w[4]) {
    const double f2 = f * f, f3 = f2 * f;
    w[0] = 0.5 * (-f3 + 2 * f2 - f);
    w[1] = 0.5 * (3 * f3 - 5 * f2 + 2);
    w[2] = 0.5 * (-3 * f3 + 4 * f2 + f);
    w[3] = 0.5 * (f3 - f2);
}
}  // namespace

double VisibleMassTable::Eval(double cosTheta, double t) const {
    const double x = std::sqrt(Clamp(cosTheta, 0.0, 1.0));
    const double lt = std::log(t);
    if (!(lt >= logMin_) || !(lt <= logMin_ + logStep_ * (LogTNodes - 1)))
        return psd_.VisibleMass(SafeSqrt(1 - Sqr(Clamp(cosTheta, 0.0, 1.0))), t);
    const double fx = x * (CosNodes - 1), fy = (lt - logMin_) / logStep_;
    const int ix = std::min(CosNodes - 2, int(fx)), iy = std::min(LogTNodes - 2, int(fy));
    double wx[4], wy[4];
    CatmullRom(fx - ix, wx);
    CatmullRom(fy - iy, wy);
    double v = 0;
    for (int b = 0; b < 4; ++b) {
        // At the table's edges the missing outer node is extrapolated linearly (2·edge − inner),
        // which keeps the rule exact for linear data.
        const int j = iy - 1 + b;
        for (int a = 0; a < 4; ++a) {
            const int i = ix - 1 + a;
            auto node = [&](int ii, int jj) {
                auto clampedJ = [&](int ii2) {
                    if (jj < 0) return 2 * Node(ii2, 0) - Node(ii2, 1);
                    if (jj >= LogTNodes) return 2 * Node(ii2, LogTNodes - 1) - Node(ii2, LogTNodes - 2);
                    return Node(ii2, jj);
                };
                if (ii < 0) return 2 * clampedJ(0) - clampedJ(1);
                if (ii >= CosNodes) return 2 * clampedJ(CosNodes - 1) - clampedJ(CosNodes - 2);
                return clampedJ(ii);
            };
            v += wx[a] * wy[b] * node(i, j);
        }
    }
    return Clamp(v, 0.0, 1.0);
}

}  // namespace phasor
