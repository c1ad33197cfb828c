// SPDX-License-Identifier: Apache-2.0
// The cells of the fine-pixel sweep (issue 20 §1) on scenes/validation/fine_pixels.wscene: one row
// of this table is one cell of an accuracy map (pixel pitch/λ, source, opening, position of the
// row, incidence), rendered by `grt` and by `rs` and compared within 2e-3 of the row's peak.
// tests/validation/fine_pixels_test.cpp runs FinePixelCases(); bench/fine_pixels_bench.cpp runs a
// larger grid and the full rows.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "parser/parser.h"

namespace phasor::test {

struct FinePixelCase {
    double pitchOverLambda;  // pixel pitch / λ (the pixel std is pitch/√12)
    const char *source;      // "plane" | "beam" (TEM00, w0 = 90 µm, waist 10 mm before the plate)
    const char *aperture;    // "disc" (60 µm) | "slits" (2 × 20 µm, 60 µm apart, 300 µm long)
    double offsetUm = 0;     // the row's centre off the axis [µm]
    double tiltDeg = 0;      // incidence of the source [degrees]
    int pixels = 3;          // pixels in the row
};

constexpr double FinePixelLambda = 632.8e-9;

/// The scene's Defines for one cell.
inline DefineList FinePixelDefines(const FinePixelCase &c, int spp = 0) {
    char pitch[32], offset[32], tilt[32];
    std::snprintf(pitch, sizeof pitch, "%.6gum", c.pitchOverLambda * FinePixelLambda * 1e6);
    std::snprintf(offset, sizeof offset, "%.6gum", c.offsetUm);
    std::snprintf(tilt, sizeof tilt, "%.6gdeg", c.tiltDeg);
    DefineList d = {{"pitch", pitch},
                    {"n", std::to_string(c.pixels)},
                    {"offset", offset},
                    {"tilt", tilt},
                    {"source", std::string("\"") + c.source + "\""},
                    {"aperture", std::string("\"") + c.aperture + "\""}};
    if (spp > 0) d.push_back({"spp", std::to_string(spp)});
    return d;
}

inline std::string FinePixelName(const FinePixelCase &c) {
    char s[160];
    std::snprintf(s, sizeof s, "pitch %5.2f lambda, %-5s, %-5s, offset %3g um, tilt %g deg", c.pitchOverLambda,
                  c.source, c.aperture, c.offsetUm, c.tiltDeg);
    return s;
}

/// The cells `make test` checks: every pitch of the range for its scene (plane wave, hole,
/// on the axis), and the other sources, openings and positions at the extremes and in between.
inline std::vector<FinePixelCase> FinePixelCases() {
    std::vector<FinePixelCase> c;
    for (double p : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0}) c.push_back({p, "plane", "disc"});
    for (double p : {0.5, 2.0, 20.0}) c.push_back({p, "beam", "disc"});
    for (double p : {0.5, 2.0, 20.0}) c.push_back({p, "plane", "slits"});
    for (double p : {1.0, 10.0}) c.push_back({p, "beam", "slits"});
    for (double p : {0.5, 5.0, 20.0}) c.push_back({p, "plane", "disc", 80, 0.2});
    c.push_back({2.0, "beam", "slits", 50, 0.1});
    return c;
}

}  // namespace phasor::test
