// SPDX-License-Identifier: Apache-2.0
// phasor — text of the program's outputs: numbers and CSV fields (profile, compare, plot data).
#pragma once

#include <cstdio>
#include <string>

namespace phasor {

/// `v` with `digits` significant digits (printf's %g: "0.000123777", "1.5e-05", "nan", "inf").
inline std::string FormatNumber(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

/// A CSV field, quoted as RFC 4180 says when it holds a comma, a quote or a line break.
inline std::string CsvField(const std::string &s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace phasor
