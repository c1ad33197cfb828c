// SPDX-License-Identifier: Apache-2.0
// phasor — what the refractive-index formula plug-ins `sellmeier` and `cauchy` share: the band
// [lo, hi] a fit is valid on (`range`; outside it the value at the nearer end, as
// core/spectrum/dispersion.h does for the named glasses), the check that the formula is a
// positive, finite index over that band, and its maximum.
#pragma once

#include <string>
#include <utility>

#include "core/diagnostics.h"
#include "core/render/registry.h"
#include "core/spectrum/spectrum.h"
#include "spectra/common.h"

namespace phasor {

class IndexFormulaSpectrum : public Spectrum {
  public:
    IndexFormulaSpectrum(double lo, double hi) : lo_(lo), hi_(hi) {}

    double MaxValue() const override { return max_; }
    std::pair<double, double> Support() const override { return {0, Infinity}; }

    /// The `range` parameter: the band of the fit, two wavelengths.
    static ParamSpec RangeSpec() {
        return P::NumberList("range", "wavelength band of the fit [lo, hi]; outside it the value at the nearer end is used",
                             Dim::Length())
            .Default(Value::List({Value::Number(200e-9, Dim::Length()), Value::Number(3.7e-6, Dim::Length())}))
            .Size(2)
            .Min(0, true);
    }
    /// Reads `range`; throws at it unless lo < hi.
    static std::pair<double, double> ReadRange(const ParamDict &d) {
        const std::vector<double> r = d.GetNumbers("range");
        if (!(r[0] < r[1]))
            throw Error(d.Loc("range"), "'range' must be [lo, hi] with lo < hi; it is [" + spectra::Nm(r[0]) + ", " +
                                            spectra::Nm(r[1]) + "]");
        return {r[0], r[1]};
    }

  protected:
    /// After construction: checks that Eval is a finite index ≥ 1e-3 on a fine grid over the band
    /// (throws at `where` naming the first wavelength where it is not) and records its maximum.
    void Finish(const FileLoc &where) {
        constexpr int Steps = 4000;
        max_ = 0;
        for (int i = 0; i <= Steps; ++i) {
            const double lambda = lo_ * std::pow(hi_ / lo_, double(i) / Steps);
            const double n = Eval(lambda);
            if (!(n >= 1e-3) || !std::isfinite(n))
                throw Error(where, "the formula gives no positive index at " + spectra::Nm(lambda) + " (n = " +
                                       spectra::Num(n) + "); adjust the coefficients or 'range'");
            max_ = std::max(max_, n);
        }
    }
    std::string RangeText() const { return "range = [" + spectra::Num(lo_ * 1e9) + " " + spectra::Num(hi_ * 1e9) + "] nm"; }

    double lo_, hi_;
    double max_ = 0;
};

}  // namespace phasor
