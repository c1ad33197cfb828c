// SPDX-License-Identifier: Apache-2.0
// phasor — a coated or bare smooth surface (smooth_surface.h).
#include "materials/smooth_surface.h"

#include <array>
#include <sstream>

namespace phasor {

std::string Coating::ToString() const {
    std::ostringstream os;
    os << "[";
    for (std::size_t j = 0; j < layers.size(); ++j)
        os << (j ? ", " : " ") << "layer(ior = " << layers[j].ior->ToString()
           << ", thickness = " << layers[j].thickness.ToString() << ")";
    os << " ]";
    return os.str();
}

StackResponse SmoothSurface::Response(double lambda, double etaOutside, double cosI, bool fromInside,
                                      const TextureEvalContext &tex) const {
    const int count = LayerCount();
    const Complex outside(etaOutside, 0), substrate = SubstrateIndex(lambda);
    const Complex nIn = fromInside ? substrate : outside, nOut = fromInside ? outside : substrate;
    // A bare interface needs no layer buffer (filling MaxLayers default layers costs more than the
    // Fresnel coefficients; gratings ask once per order listing and wavelength).
    if (count == 0) return LayerStackResponse(lambda, nIn, Complex(cosI, 0), std::span<const Layer>(), nOut);
    std::array<Layer, MaxLayers> layers;
    for (int j = 0; j < count; ++j) {
        const CoatingLayer &c = coating_->layers[fromInside ? count - 1 - j : j];
        layers[j] = Layer{c.ior->Eval(lambda), c.thickness.Eval(tex)};
    }
    return LayerStackResponse(lambda, nIn, Complex(cosI, 0), std::span<const Layer>(layers.data(), count), nOut);
}

std::string SmoothSurface::ToString() const {
    std::ostringstream os;
    os << "substrate = " << substrate_->ToString();
    if (cauchyB_ != 0) os << " + " << cauchyB_ << " m^2/λ²";
    if (coating_) os << ", coating = " << coating_->ToString();
    return os.str();
}

}  // namespace phasor
