// SPDX-License-Identifier: Apache-2.0
// Fine pixels behind an aperture (issue 20 §1; docs/narrow_pixels.md) on
// scenes/validation/fine_pixels.wscene: a plane wave or a TEM00 beam (633 nm) through a 60 µm hole
// or a pair of short slits onto Gaussian pixels 20 mm behind, with pitches from λ/2 to 20λ, on and
// off the axis — `grt` against `rs` (which integrates the flux over each pixel's Gaussian exactly;
// its own references are in tests/integrators/rs_test.cpp and the double-slit validation).
// Before the pixel's state was evaluated non-paraxially, grt's centre pixel fell with the pitch
// (−0.5 %, −6.3 %, −26 %, −60 % at 5.1, 2.6, 1.7, 1.0 µm); the tolerance is the double slit's,
// 2e-3 of the row's peak, at every cell of fine_pixels_cases.h. The test catches that: with the
// paraxial GR put back for labels inside the propagating disc (PixelWavelet::Preferred() false
// for them), 14 of its 18 cells fail (−56 % at λ/2, −2.3 % at 5λ, −3.1e-3 at 10λ of the peak);
// the cells pass at 4e-6 … 2.4e-5 of the peak with the fix.
#include <gtest/gtest.h>

#include <cstdio>

#include "validation/fine_pixels_cases.h"
#include "validation/render_row.h"

namespace phasor {
namespace {

using test::MaxDiffOfPeak;
using test::RenderRow;
using test::Row;

TEST(FinePixels, GrtMatchesRsAtEveryPitchSourceAndOpening) {
    const std::string scene = test::ValidationScene("fine_pixels.wscene");
    for (const test::FinePixelCase &c : test::FinePixelCases()) {
        const DefineList defs = test::FinePixelDefines(c);
        const Row grt = RenderRow(scene, defs, "grt"), rs = RenderRow(scene, defs, "rs");
        ASSERT_EQ(grt.v.size(), std::size_t(c.pixels));
        ASSERT_EQ(rs.v.size(), std::size_t(c.pixels));
        ASSERT_GT(rs.Peak(), 0);
        const double e = MaxDiffOfPeak(grt, rs);
        std::printf("%s: max|grt-rs| = %.1e of peak (centre grt/rs - 1 = %+.1e; grt %.2f s, rs %.2f s)\n",
                    test::FinePixelName(c).c_str(), e, grt.v[grt.v.size() / 2] / rs.v[rs.v.size() / 2] - 1,
                    grt.seconds, rs.seconds);
        EXPECT_LE(e, 2e-3) << test::FinePixelName(c);
    }
}

}  // namespace
}  // namespace phasor
