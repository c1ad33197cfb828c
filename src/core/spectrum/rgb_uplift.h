// SPDX-License-Identifier: Apache-2.0
// phasor — a linear RGB reflectance uplifted to a smooth spectrum (Smits 1999): the one
// RGB → spectrum conversion, used by the `rgb` spectrum and the `bitmap` texture.
#pragma once

#include <array>

#include "core/math.h"

namespace phasor {

/// A linear Rec.709 RGB reflectance/albedo, each component in [0, 1], uplifted by Smits' method
/// (B. Smits, "An RGB-to-Spectrum Conversion for Reflectances", Journal of Graphics Tools 4(4),
/// 1999): the colour is spent as white (the smallest component), then one secondary (cyan, magenta
/// or yellow), then one primary, using his seven published basis spectra sampled in ten equal bins
/// over 380–720 nm. Each bin value sits at the bin centre, values are interpolated linearly
/// between centres and held beyond the outer ones (so a reflectance stays defined in the infrared
/// and ultraviolet), then clamped to [0, 1] (the published bases slightly exceed 1 in places).
class SmitsSpectrum {
  public:
    static constexpr int Bins = 10;
    explicit SmitsSpectrum(const Vec3 &rgb);
    /// The reflectance at vacuum wavelength `lambda` [m], in [0, 1].
    double Eval(double lambda) const;
    /// The largest bin value (the spectrum's maximum).
    double MaxValue() const;
    /// An upper bound of the uplift of any colour whose largest component is `maxComponent`:
    /// the basis weights are non-negative and sum to the largest component, so no value exceeds
    /// min(1, maxComponent × the largest basis value).
    static double UpperBound(double maxComponent);

  private:
    std::array<double, Bins> bins_;
};

}  // namespace phasor
