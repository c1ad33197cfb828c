// SPDX-License-Identifier: Apache-2.0
// phasor — a coated or bare smooth surface (smooth_surface.h).
#include "materials/smooth_surface.h"

#include <array>
#include <sstream>
#include <vector>

#include "materials/fresnel.h"

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

void SmoothSurface::Thicknesses(const TextureEvalContext &tex, double *thickness) const {
    for (int j = 0; j < LayerCount(); ++j) thickness[j] = coating_->layers[std::size_t(j)].thickness.Eval(tex);
}

template <typename F>
auto SmoothSurface::WithThicknesses(const TextureEvalContext &tex, F &&f) const {
    // Short coatings (every film, most stacks) on the stack; long ones on the heap.
    constexpr int Small = 8;
    std::array<double, Small> small;
    std::vector<double> big(LayerCount() > Small ? LayerCount() : 0);
    double *d = LayerCount() > Small ? big.data() : small.data();
    Thicknesses(tex, d);
    return f(d);
}

template <typename F>
auto SmoothSurface::WithLayers(double lambda, bool fromInside, const double *thickness, F &&f) const {
    // Short coatings (every film, most stacks) live on the stack; long ones on the heap.
    constexpr int Small = 8;
    const int count = LayerCount();
    std::array<Layer, Small> small;
    std::vector<Layer> big(count > Small ? count : 0);
    Layer *layers = count > Small ? big.data() : small.data();
    for (int j = 0; j < count; ++j) {
        const int k = fromInside ? count - 1 - j : j;
        layers[j] = Layer{coating_->layers[std::size_t(k)].ior->Eval(lambda), thickness[k]};
    }
    return f(std::span<const Layer>(layers, count));
}

StackResponse SmoothSurface::Response(double lambda, double etaOutside, double cosI, bool fromInside,
                                      const TextureEvalContext &tex) const {
    return WithThicknesses(tex, [&](const double *d) {
        return Response(lambda, etaOutside, cosI, fromInside, d, SubstrateIndex(lambda));
    });
}

StackResponse SmoothSurface::Response(double lambda, double etaOutside, double cosI, bool fromInside,
                                      const double *thickness, Complex substrate) const {
    const Complex outside(etaOutside, 0);
    return WithLayers(lambda, fromInside, thickness, [&](std::span<const Layer> layers) {
        return LayerStackResponse(lambda, fromInside ? substrate : outside, Complex(cosI, 0), layers,
                                  fromInside ? outside : substrate);
    });
}

double SmoothSurface::Power(double lambda, double etaOutside, double cosI, bool fromInside, const double *thickness,
                            Complex substrate, bool transmitted) const {
    // A bare interface from a real medium: n1 → n2 as Response orders them.
    if (LayerCount() == 0 && substrate.imag() >= 0 && (!fromInside || substrate.imag() == 0)) {
        const double n1 = fromInside ? substrate.real() : etaOutside;
        const Complex n2 = fromInside ? Complex(etaOutside, 0) : substrate;
        if (!transmitted) return FresnelReflectanceReal(cosI, n1, n2);
        if (n2.imag() == 0) return FresnelTransmittanceReal(cosI, n1, n2.real());
    }
    const StackResponse r = Response(lambda, etaOutside, cosI, fromInside, thickness, substrate);
    return transmitted ? r.T() : r.R();
}

IncoherentStackResponse SmoothSurface::IncoherentResponse(double lambda, double etaOutside, double cosI,
                                                          bool fromInside, const TextureEvalContext &tex) const {
    return WithThicknesses(tex, [&](const double *d) {
        return IncoherentResponse(lambda, etaOutside, cosI, fromInside, d, SubstrateIndex(lambda));
    });
}

IncoherentStackResponse SmoothSurface::IncoherentResponse(double lambda, double etaOutside, double cosI,
                                                          bool fromInside, const double *thickness,
                                                          Complex substrate) const {
    const Complex outside(etaOutside, 0);
    return WithLayers(lambda, fromInside, thickness, [&](std::span<const Layer> layers) {
        return LayerStackIncoherent(lambda, fromInside ? substrate : outside, Complex(cosI, 0), layers,
                                    fromInside ? outside : substrate);
    });
}

Vec2 SmoothSurface::ShearVector(double lambda, double etaOutside, const Vec3 &wi, bool fromInside,
                                const TextureEvalContext &tex) const {
    return WithThicknesses(tex, [&](const double *d) { return ShearVector(lambda, etaOutside, wi, fromInside, d); });
}

Vec2 SmoothSurface::ShearVector(double lambda, double etaOutside, const Vec3 &wi, bool fromInside,
                                const double *thickness) const {
    const double tangential = std::hypot(wi.x, wi.y);
    if (LayerCount() == 0 || !(tangential > 0)) return Vec2(0, 0);
    return Vec2(-wi.x, -wi.y) * (Shear(lambda, etaOutside, std::abs(wi.z), fromInside, thickness) / tangential);
}

double SmoothSurface::Shear(double lambda, double etaOutside, double cosI, bool fromInside,
                            const TextureEvalContext &tex) const {
    return WithThicknesses(tex, [&](const double *d) { return Shear(lambda, etaOutside, cosI, fromInside, d); });
}

double SmoothSurface::Shear(double lambda, double etaOutside, double cosI, bool fromInside,
                            const double *thickness) const {
    if (!coating_) return 0;
    const Complex incident = fromInside ? SubstrateIndex(lambda) : Complex(etaOutside, 0);
    return WithLayers(lambda, fromInside, thickness, [&](std::span<const Layer> layers) {
        return LayerStackShear(incident, Complex(cosI, 0), layers);
    });
}

double SmoothSurface::Bandwidth(double lambda, double etaOutside, double kappa, bool fromInside,
                                const double *thickness, Complex substrate, double tol) const {
    const Complex outside(etaOutside, 0);
    const Complex incident = fromInside ? substrate : outside;
    // cosθ in the incident medium for this κ (complex beyond grazing: the bound then still holds).
    const Complex cosI = std::sqrt(1.0 - Complex(kappa * kappa, 0) / (incident * incident));
    return WithLayers(lambda, fromInside, thickness, [&](std::span<const Layer> layers) {
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
