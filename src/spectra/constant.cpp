// SPDX-License-Identifier: Apache-2.0
// `constant`: the same value at every wavelength (ConstantSpectrum in spectrum.h). A bare number
// where a spectrum is expected means the same thing. As an emitter seen by the radiometric sensor
// its support is unbounded; the wavelength sampler then samples 360–830 nm (spectrum.h).
#include "core/render/registry.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

/// Factory for ConstantSpectrum (the class itself lives in the spectrum module).
class ConstantSpectrumPlugin {
  public:
    static const Schema &GetSchema() {
        static const Schema s{"spectrum",
                              "constant",
                              "The same value at every wavelength.",
                              {P::Number("value", "the value (spectra are never negative)").Required().Min(0)}};
        return s;
    }
    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<ConstantSpectrum>(d.GetNumber("value"));
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict().Set("value", Value::Number(1)), ParamDict().Set("value", Value::Number(0.25))};
    }
};

PHASOR_EXPORT_PLUGIN(Spectrum, ConstantSpectrumPlugin)

}  // namespace phasor
