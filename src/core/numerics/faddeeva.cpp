// SPDX-License-Identifier: Apache-2.0
// phasor — the Faddeeva function (faddeeva.h).
#include "core/numerics/faddeeva.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

// libcerf 1.3 (C99 header): the Faddeeva function, used as the reference implementation.
extern "C" double _Complex w_of_z(double _Complex z);

namespace phasor {

namespace {

constexpr double InvSqrtPi = 0.56418958354775628695;  // 1/√π

// Weideman (1994): w(z) ≈ 2·p(Z)/(L − iz)² + (1/√π)/(L − iz), Z = (L + iz)/(L − iz), with the
// coefficients of p from a discrete Fourier transform of e^{−t²}(L² + t²) at t = L·tan(θ/2).
constexpr int WeidemanN = 28;
struct Weideman {
    double L = 0;
    std::array<double, WeidemanN> a{};  // highest power first (Horner order)
    Weideman() {
        const int n = WeidemanN, m = 2 * n, m2 = 2 * m;
        L = std::sqrt(n / std::sqrt(2.0));
        std::vector<double> f(static_cast<std::size_t>(m2), 0.0);
        for (int k = -m + 1; k <= m - 1; ++k) {
            const double t = L * std::tan(k * Pi / (2 * m));
            f[std::size_t(k + m)] = std::exp(-t * t) * (L * L + t * t);
        }
        // Real part of the DFT of the (shifted) samples.
        std::vector<double> g(static_cast<std::size_t>(m2));
        for (int i = 0; i < m2; ++i) g[std::size_t(i)] = f[std::size_t((i + m2 / 2) % m2)];
        for (int j = 1; j <= n; ++j) {
            double s = 0;
            for (int i = 0; i < m2; ++i) s += g[std::size_t(i)] * std::cos(2 * Pi * double(i) * j / m2);
            a[std::size_t(n - j)] = s / m2;
        }
    }
};
const Weideman &WeidemanCoefficients() {
    static const Weideman w;
    return w;
}

}  // namespace

Complex FaddeevaW(Complex z) {
    double _Complex c;
    static_assert(sizeof(c) == sizeof(Complex), "std::complex<double> and double _Complex share a layout");
    std::memcpy(static_cast<void *>(&c), &z, sizeof c);
    const double _Complex r = w_of_z(c);
    Complex out;
    std::memcpy(static_cast<void *>(&out), &r, sizeof out);
    return out;
}

void FaddeevaWUpperBatch(int n, const double *zr, const double *zi, double *wr, double *wi) {
    const Weideman &c = WeidemanCoefficients();
    constexpr int Block = 16;
    for (int base = 0; base < n; base += Block) {
        const int m = std::min(Block, n - base);
        double Zr[Block], Zi[Block], Ur[Block], Ui[Block], Pr[Block], Pi_[Block];
        for (int i = 0; i < m; ++i) {
            // den = L − iz = (L + y, −x), num = L + iz = (L − y, x).
            const double x = zr[base + i], y = zi[base + i];
            const double dr = c.L + y, di = -x, nr = c.L - y, ni = x;
            const double inv = 1 / (dr * dr + di * di);
            Zr[i] = (nr * dr + ni * di) * inv;
            Zi[i] = (ni * dr - nr * di) * inv;
            Ur[i] = dr * inv;  // 1/den
            Ui[i] = -di * inv;
            Pr[i] = 0;
            Pi_[i] = 0;
        }
        for (int k = 0; k < WeidemanN; ++k) {
            const double ak = c.a[std::size_t(k)];
            for (int i = 0; i < m; ++i) {
                const double r = Pr[i] * Zr[i] - Pi_[i] * Zi[i] + ak;
                Pi_[i] = Pr[i] * Zi[i] + Pi_[i] * Zr[i];
                Pr[i] = r;
            }
        }
        for (int i = 0; i < m; ++i) {
            const double u2r = Ur[i] * Ur[i] - Ui[i] * Ui[i], u2i = 2 * Ur[i] * Ui[i];
            wr[base + i] = 2 * (Pr[i] * u2r - Pi_[i] * u2i) + InvSqrtPi * Ur[i];
            wi[base + i] = 2 * (Pr[i] * u2i + Pi_[i] * u2r) + InvSqrtPi * Ui[i];
        }
    }
}

Complex FaddeevaWUpper(Complex z) {
    const double zr = z.real(), zi = z.imag();
    double wr, wi;
    FaddeevaWUpperBatch(1, &zr, &zi, &wr, &wi);
    return {wr, wi};
}

}  // namespace phasor
