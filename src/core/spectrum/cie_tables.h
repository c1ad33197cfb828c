// SPDX-License-Identifier: Apache-2.0
// phasor — internal: raw colorimetric tables of the spectrum module (cie_tables.cpp).
#pragma once

namespace phasor::detail {

/// CIE 1931 2° colour-matching functions, 1 nm steps from CieTableFirstNm to CieTableLastNm.
inline constexpr int CieTableFirstNm = 360, CieTableLastNm = 830;
inline constexpr int CieTableSize = CieTableLastNm - CieTableFirstNm + 1;  // 471
extern const double CieXBar1931[CieTableSize];
extern const double CieYBar1931[CieTableSize];
extern const double CieZBar1931[CieTableSize];

/// CIE illuminant D65 relative SPD, 5 nm steps from D65FirstNm to D65LastNm, 100 at 560 nm.
inline constexpr int D65FirstNm = 300, D65LastNm = 830, D65StepNm = 5;
inline constexpr int D65TableSize = (D65LastNm - D65FirstNm) / D65StepNm + 1;  // 107
extern const double CieD65Spd[D65TableSize];

}  // namespace phasor::detail
