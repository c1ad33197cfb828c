// SPDX-License-Identifier: Apache-2.0
// phasor — a coated or bare smooth surface (smooth_surface.h).
#include "materials/smooth_surface.h"

#include <array>
#include <sstream>
#include <vector>

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

template <typename F>
auto SmoothSurface::WithLayers(double lambda, bool fromInside, const TextureEvalContext &tex, F &&f) const {
    // Short coatings (every film, most stacks) live on the stack; long ones on the heap.
    constexpr int Small = 8;
    const int count = LayerCount();
    std::array<Layer, Small> small;
    std::vector<Layer> big(count > Small ? count : 0);
    Layer *layers = count > Small ? big.data() : small.data();
    for (int j = 0; j < count; ++j) {
        const CoatingLayer &c = coating_->layers[fromInside ? count - 1 - j : j];
        layers[j] = Layer{c.ior->Eval(lambda), c.thickness.Eval(tex)};
    }
    return f(std::span<const Layer>(layers, count));
}

StackResponse SmoothSurface::Response(double lambda, double etaOutside, double cosI, bool fromInside,
                                      const TextureEvalContext &tex, Complex substrate) const {
    const Complex outside(etaOutside, 0);
    return WithLayers(lambda, fromInside, tex, [&](std::span<const Layer> layers) {
        return LayerStackResponse(lambda, fromInside ? substrate : outside, Complex(cosI, 0), layers,
                                  fromInside ? outside : substrate);
    });
}

IncoherentStackResponse SmoothSurface::IncoherentResponse(double lambda, double etaOutside, double cosI,
                                                          bool fromInside, const TextureEvalContext &tex,
                                                          Complex substrate) const {
    const Complex outside(etaOutside, 0);
    return WithLayers(lambda, fromInside, tex, [&](std::span<const Layer> layers) {
        return LayerStackIncoherent(lambda, fromInside ? substrate : outside, Complex(cosI, 0), layers,
                                    fromInside ? outside : substrate);
    });
}

Vec2 SmoothSurface::ShearVector(double lambda, double etaOutside, const Vec3 &wi, bool fromInside,
                                const TextureEvalContext &tex) const {
    const double tangential = std::hypot(wi.x, wi.y);
    if (LayerCount() == 0 || !(tangential > 0)) return Vec2(0, 0);
    return Vec2(-wi.x, -wi.y) * (Shear(lambda, etaOutside, std::abs(wi.z), fromInside, tex) / tangential);
}

double SmoothSurface::Shear(double lambda, double etaOutside, double cosI, bool fromInside,
                            const TextureEvalContext &tex) const {
    if (!coating_) return 0;
    const Complex incident = fromInside ? SubstrateIndex(lambda) : Complex(etaOutside, 0);
    return WithLayers(lambda, fromInside, tex, [&](std::span<const Layer> layers) {
        return LayerStackShear(incident, Complex(cosI, 0), layers);
    });
}

double SmoothSurface::Bandwidth(double lambda, double etaOutside, double kappa, bool fromInside,
                                const TextureEvalContext &tex, double tol) const {
    const Complex substrate = SubstrateIndex(lambda), outside(etaOutside, 0);
    const Complex incident = fromInside ? substrate : outside;
    // cosθ in the incident medium for this κ (complex beyond grazing: the bound then still holds).
    const Complex cosI = std::sqrt(1.0 - Complex(kappa * kappa, 0) / (incident * incident));
    return WithLayers(lambda, fromInside, tex, [&](std::span<const Layer> layers) {
        return LayerStackBandwidth(lambda, incident, cosI, layers, fromInside ? outside : substrate, tol);
    });
}

std::string SmoothSurface::ToString() const {
    std::ostringstream os;
    os << "substrate = " << substrate_->ToString();
    if (cauchyB_ != 0) os << " + " << cauchyB_ << " m^2/λ²";
    if (coating_) os << ", coating = " << coating_->ToString();
    return os.str();
}

}  // namespace phasor
