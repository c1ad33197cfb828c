// SPDX-License-Identifier: Apache-2.0
// phasor — complex-valued spectra: a refractive index n(λ) + iκ(λ) as a function of vacuum
// wavelength λ [m], with κ ≥ 0 for absorbing media (time dependence e^{-iωt}, the convention of
// materials/fresnel.h). Kernels read one with BuildContext::GetComplexSpectrum
// (core/params/build_context.h) from a `complex spectrum` parameter, which accepts
//   1.5                      a real constant (κ = 0)
//   0.2+3.4i                 a complex constant n + iκ
//   "Au"                     a named material (core/spectrum/named_ior.h: Al, Ag, Au, Cu, BK7, …)
//   table(…), @name, …       any (real) spectrum: n(λ) with κ = 0
//   nk(n = …, k = …)         separate spectra for n(λ) and κ(λ) (e.g. two tables; k defaults to 0)
#pragma once

#include <memory>
#include <string>

#include "core/math.h"
#include "core/spectrum/named_ior.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

class ComplexSpectrum {
  public:
    virtual ~ComplexSpectrum() = default;
    /// n + iκ at vacuum wavelength lambda [m].
    virtual Complex Eval(double lambda) const = 0;
    /// The scene-file text that builds it (for messages and ToString of kernels).
    virtual std::string ToString() const = 0;
};

/// The same n + iκ at every wavelength.
class ConstantComplexSpectrum final : public ComplexSpectrum {
  public:
    explicit ConstantComplexSpectrum(Complex c) : c_(c) {}
    Complex Eval(double) const override { return c_; }
    std::string ToString() const override;

  private:
    Complex c_;
};

/// n(λ) and κ(λ) from two real spectra; k may be null (κ = 0).
class NkSpectrum final : public ComplexSpectrum {
  public:
    NkSpectrum(std::shared_ptr<const Spectrum> n, std::shared_ptr<const Spectrum> k)
        : n_(std::move(n)), k_(std::move(k)) {}
    Complex Eval(double lambda) const override { return {n_->Eval(lambda), k_ ? k_->Eval(lambda) : 0.0}; }
    std::string ToString() const override;

  private:
    std::shared_ptr<const Spectrum> n_, k_;
};

/// A named material of core/spectrum/named_ior.h.
class NamedComplexSpectrum final : public ComplexSpectrum {
  public:
    explicit NamedComplexSpectrum(const NamedIndex &m) : m_(m) {}
    Complex Eval(double lambda) const override { return m_.index(lambda); }
    std::string ToString() const override { return std::string("\"") + m_.name + "\""; }

  private:
    const NamedIndex &m_;
};

}  // namespace phasor
