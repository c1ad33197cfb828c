// SPDX-License-Identifier: Apache-2.0
// A coherent Gaussian beam (`gaussian_beam`) through an aperture (issue 10 §1) on
// scenes/validation/gaussian_beam_aperture.wscene: `rs` (which propagates the beam's exact
// paraxial field) against the Fresnel closed form on the axis, then `grt` against `rs` for a disc
// and a double slit — waists from 0.2× to 20× the opening, waist before and behind the plate,
// on- and off-axis beams, three sensor resolutions. Tolerance 2e-3 of the row's peak, the bound
// the double-slit validation holds grt to (theory §9; its 64×64 lattice and D13 window give
// ≤ 8e-4 there).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

#include "validation/render_row.h"

namespace phasor {
namespace {

using test::MaxDiffOfPeak;
using test::RenderRow;
using test::Row;
const std::string kScene = test::ValidationScene("gaussian_beam_aperture.wscene");

/// On-axis irradiance [W/m²] at distance z behind a disc of radius a lit by a TEM₀₀ beam of power
/// P whose waist (radius w0) lies zw before the plate — the Fresnel integral in closed form:
/// U_inc(r) = C·e^{ikr²/(2q)}, q = zw − i·z_R, |C|² = P/(πβ_s²)·|q(0)/q|², and
/// U(0) = (k/z)·C·∫₀^a e^{−c r²} r dr = (k/z)·C·(1 − e^{−ca²})/(2c), c = −(ik/2)(1/q + 1/z).
double FresnelOnAxis(double lambda, double power, double w0, double zw, double a, double z) {
    const double k = 2 * Pi / lambda, b2 = 0.5 * w0 * w0, zr = k * b2;
    const std::complex<double> q(zw, -zr), q0(0, -zr), i(0, 1);
    const double c2 = power / (Pi * b2) * std::norm(q0 / q);
    const std::complex<double> c = -0.5 * i * k * (1.0 / q + 1.0 / z);
    return c2 * std::norm((k / z) * (1.0 - std::exp(-c * a * a)) / (2.0 * c));
}

TEST(GaussianBeam, RsMatchesTheFresnelClosedFormOnTheAxis) {
    // A tiny pixel on the axis (σ = 0.3 µm ≪ the pattern's λz/D ≈ 160 µm, smoothing < 1e-5) and
    // the paraxial error k·a⁴/(8z³) ≈ 1e-6 rad: the two agree to the quadrature's accuracy.
    struct Case {
        const char *w0, *zw;
        double w0m, zwm;
    } cases[] = {{"0.5mm", "10mm", 0.5e-3, 10e-3}, {"40um", "10mm", 40e-6, 10e-3}, {"4mm", "-20mm", 4e-3, -20e-3}};
    for (const Case &c : cases) {
        const Row rs = RenderRow(kScene, {{"w0", c.w0}, {"zw", c.zw}, {"n", "1"}, {"extent", "2um"}, {"sigma_pix", "0.3um"}},
                                 "rs");
        ASSERT_EQ(rs.v.size(), 1u);
        const double ref = FresnelOnAxis(632.8e-9, 1e-3, c.w0m, c.zwm, 100e-6, 50e-3);
        std::printf("w0 = %s, waist %s before the plate: rs %.6g W/m^2, Fresnel %.6g (rel. %.1e)\n", c.w0, c.zw,
                    rs.v[0], ref, rs.v[0] / ref - 1);
        EXPECT_NEAR(rs.v[0] / ref, 1, 1e-4) << c.w0 << " " << c.zw;
    }
}

struct Setup {
    std::string what;
    DefineList defs;
};

void ExpectGrtMatchesRs(const std::vector<Setup> &setups) {
    for (const Setup &s : setups) {
        const Row grt = RenderRow(kScene, s.defs, "grt"), rs = RenderRow(kScene, s.defs, "rs");
        ASSERT_EQ(grt.v.size(), rs.v.size());
        const double e = MaxDiffOfPeak(grt, rs);
        std::printf("%-46s max|grt-rs| = %.2e of peak (peak %.5g W/m^2; grt %.2f s, rs %.2f s)\n", s.what.c_str(), e,
                    rs.Peak(), grt.seconds, rs.seconds);
        EXPECT_LE(e, 2e-3) << s.what;
        EXPECT_GT(rs.Peak(), 0) << s.what;
    }
}

TEST(GaussianBeam, GrtMatchesRsThroughADisc) {
    // The beam (w0 = 2.5× the disc's diameter, waist 10 mm before the plate) at three
    // resolutions with the default pixel σ = pitch/√12 (as in the report), then waists of
    // 0.2× and 20× the diameter, a waist behind the plate (the beam converges on it) and an
    // off-axis, tilted beam.
    auto sigma = [](int n) { return std::to_string(0.66e3 / n / std::sqrt(12.0)) + "um"; };
    ExpectGrtMatchesRs({
        {"disc, w0 0.5 mm, waist 10 mm before, n = 17", {{"n", "17"}, {"sigma_pix", sigma(17)}}},
        {"disc, w0 0.5 mm, waist 10 mm before, n = 33", {{"n", "33"}, {"sigma_pix", sigma(33)}}},
        {"disc, w0 0.5 mm, waist 10 mm before, n = 65", {{"n", "65"}, {"sigma_pix", sigma(65)}}},
        {"disc, w0 40 um (0.2 D), waist 10 mm before", {{"w0", "40um"}}},
        {"disc, w0 4 mm (20 D), waist 20 mm behind", {{"w0", "4mm"}, {"zw", "-20mm"}}},
        {"disc, w0 100 um, waist 5 mm behind, off-axis",
         {{"w0", "100um"}, {"zw", "-5mm"}, {"offset", "60um"}, {"tilt", "0.3deg"}}},
    });
}

TEST(GaussianBeam, GrtMatchesRsThroughTheDoubleSlit) {
    // The pair spans d + b = 140 µm: waists of 0.2× and 20× that, before and behind the plate,
    // and a beam centred on one slit.
    ExpectGrtMatchesRs({
        {"slits, w0 28 um (0.2x), waist 10 mm before", {{"opening", "slits"}, {"w0", "28um"}}},
        {"slits, w0 2.8 mm (20x), waist 10 mm behind", {{"opening", "slits"}, {"w0", "2.8mm"}, {"zw", "-10mm"}}},
        {"slits, w0 60 um, on slit 2, tilted, n = 65",
         {{"opening", "slits"}, {"w0", "60um"}, {"offset", "50um"}, {"tilt", "0.2deg"}, {"n", "65"}}},
        // A narrow beam tilted by 3° with its waist on the plate and its spot far from most GRs'
        // hits (the expansion must follow the spot; about the opening's centre: 2.0e-3).
        {"slits, w0 20 um, waist on the plate, 3 deg, z 5 mm",
         {{"opening", "slits"}, {"w0", "20um"}, {"zw", "0mm"}, {"offset", "50um"}, {"tilt", "3deg"}, {"z", "5mm"}}},
    });
}

TEST(GaussianBeam, TheAxisPixelDoesNotDependOnTheResolution) {
    // The scene read 1185, 328 and 84 W/m² on the axis at n = 17, 33, 65 (the footprint
    // carried the beam's irradiance at its centre only), where the Fresnel integral gives 2220.4 at
    // a point. The pixel sensitivity is fixed (σ = 5 µm, which smooths the axis value by 0.23 %),
    // so only the sampling of the row changes: the axis pixel must not move with n, and it must
    // equal rs's (RsMatchesTheFresnelClosedFormOnTheAxis checks rs against the closed form).
    const Row rs = RenderRow(kScene, {{"n", "17"}}, "rs");
    const double ref = rs.v[rs.v.size() / 2];
    EXPECT_NEAR(ref / FresnelOnAxis(632.8e-9, 1e-3, 0.5e-3, 10e-3, 100e-6, 50e-3), 1, 5e-3);
    std::vector<double> centres;
    for (int n : {17, 33, 65}) {
        const Row grt = RenderRow(kScene, {{"n", std::to_string(n)}}, "grt");
        centres.push_back(grt.v[grt.v.size() / 2]);
        std::printf("n = %2d: axis pixel %.6g W/m^2 (rs %.6g)\n", n, centres.back(), ref);
        EXPECT_NEAR(centres.back() / ref, 1, 2e-3) << "n = " << n;
    }
    const auto [lo, hi] = std::minmax_element(centres.begin(), centres.end());
    EXPECT_LE(*hi / *lo - 1, 1e-3);
}

}  // namespace
}  // namespace phasor
