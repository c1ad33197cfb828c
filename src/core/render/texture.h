// SPDX-License-Identifier: Apache-2.0
// phasor — textures: values that vary over a surface (docs/kernels.md "Textures").
//
// One plug-in family `Texture`. A texture yields either a spectrum (per sampled wavelength,
// e.g. a reflectance) or a scalar with a physical dimension (a thickness in metres, an angle in
// radians, a plain number). Kernels do not hold textures directly: they read a parameter of kind
// constant-or-texture through BuildContext::GetFloatTexture / GetSpectrumTexture and keep the
// FloatTexture / SpectrumTexture handle below, which is a constant or a texture.
#pragma once

#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "core/math.h"
#include "core/geometry/shape.h"
#include "core/spectrum/spectrum.h"
#include "core/units.h"

namespace phasor {

/// Where a texture is evaluated. World space, metres.
struct TextureEvalContext {
    Vec2 uv;          // surface parameters of the hit (SurfaceInteraction::uv)
    Vec3 p;           // world position [m]
    Vec3 dpdu, dpdv;  // ∂p/∂u, ∂p/∂v [m per unit of u, v]; zero where the shape's uv is degenerate
    Vec3 n{0, 0, 1};  // shading normal (unit)
    /// Footprint radius β = √β² [m] of the incident generalized ray (theory §1.2); 0 for a
    /// classical ray. No texture filters over it yet; it is here so that filtering can be added
    /// without changing the interface.
    double beta = 0;

    TextureEvalContext() = default;
    /// The context at a surface hit, for a ray of footprint radius `beta` [m].
    explicit TextureEvalContext(const SurfaceInteraction &si, double beta = 0)
        : uv(si.uv), p(si.p), dpdu(si.dpdu), dpdv(si.dpdv), n(si.shading.n), beta(beta) {}
    /// Only surface parameters (tests, uv-only callers): p, dp/du, dp/dv zero.
    static TextureEvalContext AtUV(Vec2 uv) {
        TextureEvalContext c;
        c.uv = uv;
        return c;
    }
};

/// The tangent direction at angle `alpha` [rad] from the first shading tangent, counter-clockwise
/// about the shading normal, in the local shading frame. The shading frame's first tangent is
/// dp/du projected onto the tangent plane (Frame::FromNormalTangent), so this is dp/du rotated
/// by alpha about n: how a kernel turns an angle texture (e.g. a groove direction) into a
/// direction. World space: SurfaceInteraction::shading.ToWorld(TangentAtAngle(alpha)).
inline Vec3 TangentAtAngle(double alpha) { return {std::cos(alpha), std::sin(alpha), 0}; }

/// A texture plug-in (family `Texture`).
class Texture {
  public:
    virtual ~Texture() = default;
    /// nullopt: a spectral texture. Otherwise a scalar texture whose values are SI numbers of
    /// this dimension (ScalarTexture::EvalScalar); a dimensionless scalar texture also serves
    /// where a spectrum is expected (the same value at every wavelength).
    virtual std::optional<Dim> ScalarDim() const = 0;
    /// Value for the sampled wavelengths (spectral and dimensionless scalar textures).
    virtual SampledSpectrum Eval(const TextureEvalContext &ctx, const SampledWavelengths &wl) const = 0;
    /// Bounds over the surface and all wavelengths, SI (used to check e.g. a reflectance ≤ 1).
    virtual double MinValue() const = 0;
    virtual double MaxValue() const = 0;
    virtual std::string ToString() const = 0;
    /// A texture whose values depend on whether they are read as data (a thickness, an angle, a
    /// weight: BuildContext::GetFloatTexture) or as a colour (a reflectance: GetSpectrumTexture)
    /// returns here the colour reading; nullptr (the default) when both are the same. A `bitmap`
    /// with colorspace = "auto" is such a texture: raw values as data, decoded from its colour
    /// space (sRGB for 8-bit images) as a colour.
    virtual std::shared_ptr<const Texture> AsColour() const { return nullptr; }

    /// "a spectrum", "a length", "an angle", "a plain number" — for messages.
    std::string DescribeYield() const {
        const std::optional<Dim> d = ScalarDim();
        return d ? d->Describe() : "a spectrum";
    }
};

/// A texture that yields one SI number of a fixed dimension per point.
class ScalarTexture : public Texture {
  public:
    explicit ScalarTexture(Dim dim) : dim_(dim) {}
    std::optional<Dim> ScalarDim() const final { return dim_; }
    Dim GetDim() const { return dim_; }
    /// Value at ctx, SI, of dimension GetDim().
    virtual double EvalScalar(const TextureEvalContext &ctx) const = 0;
    SampledSpectrum Eval(const TextureEvalContext &ctx, const SampledWavelengths &) const final {
        return SampledSpectrum(EvalScalar(ctx));
    }

  private:
    Dim dim_;
};

/// A scalar kernel parameter that is a constant or a scalar texture (pbrt-v4's FloatTexture,
/// Mitsuba 3's get_texture), read with BuildContext::GetFloatTexture. Values are SI numbers of
/// the parameter's dimension.
class FloatTexture {
  public:
    FloatTexture() = default;
    FloatTexture(double constant, Dim dim) : constant_(constant), dim_(dim) {}
    explicit FloatTexture(std::shared_ptr<const ScalarTexture> t) : tex_(std::move(t)), dim_(tex_->GetDim()) {}

    double Eval(const TextureEvalContext &ctx) const { return tex_ ? tex_->EvalScalar(ctx) : constant_; }
    bool IsConstant() const { return !tex_; }
    Dim GetDim() const { return dim_; }
    double MinValue() const { return tex_ ? tex_->MinValue() : constant_; }
    double MaxValue() const { return tex_ ? tex_->MaxValue() : constant_; }
    std::string ToString() const {
        if (tex_) return tex_->ToString();
        double scale = 1;
        const std::string unit = PreferredUnit(dim_, constant_, &scale);
        std::ostringstream os;
        os << constant_ / scale << (unit.empty() ? "" : " " + unit);
        return os.str();
    }

  private:
    std::shared_ptr<const ScalarTexture> tex_;
    double constant_ = 0;
    Dim dim_;
};

/// A spectral kernel parameter that is a spectrum or a texture (spectral, or scalar and
/// dimensionless), read with BuildContext::GetSpectrumTexture.
class SpectrumTexture {
  public:
    SpectrumTexture() = default;
    explicit SpectrumTexture(std::shared_ptr<const Spectrum> s) : spectrum_(std::move(s)) {}
    explicit SpectrumTexture(std::shared_ptr<const Texture> t) : tex_(std::move(t)) {}

    /// Value at ctx for the sampled wavelengths.
    SampledSpectrum Eval(const TextureEvalContext &ctx, const SampledWavelengths &wl) const {
        if (tex_) return tex_->Eval(ctx, wl);
        SampledSpectrum r;
        for (int i = 0; i < wl.Count(); ++i) r[i] = spectrum_->Eval(wl.lambda[i]);
        return r;
    }
    bool IsTexture() const { return tex_ != nullptr; }
    /// Bounds over the surface and all wavelengths. Spectra are never negative (every spectrum
    /// plug-in refuses negative values), so 0 bounds a spectrum from below.
    double MinValue() const { return tex_ ? tex_->MinValue() : 0; }
    double MaxValue() const { return tex_ ? tex_->MaxValue() : spectrum_->MaxValue(); }
    std::string ToString() const { return tex_ ? tex_->ToString() : spectrum_->ToString(); }

  private:
    std::shared_ptr<const Spectrum> spectrum_;
    std::shared_ptr<const Texture> tex_;
};

}  // namespace phasor
