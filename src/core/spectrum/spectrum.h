// SPDX-License-Identifier: Apache-2.0
// phasor — spectra, sampled wavelengths, sensor responses (theory §0 D10, §4.10).
// Wavelengths are vacuum wavelengths in metres everywhere.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"

namespace phasor {

/// Number of wavelengths carried by a path: the hero and its companions (theory §0 D10).
inline constexpr int NumWavelengths = 4;

/// Per-wavelength values along a path (throughput, emission, reflectance …).
struct SampledSpectrum {
    std::array<double, NumWavelengths> v{};
    SampledSpectrum() = default;
    explicit SampledSpectrum(double c) { v.fill(c); }
    double operator[](int i) const { return v[i]; }
    double &operator[](int i) { return v[i]; }
#define PHASOR_SS_OP(op)                                                                   \
    SampledSpectrum operator op(const SampledSpectrum &o) const {                          \
        SampledSpectrum r;                                                                 \
        for (int i = 0; i < NumWavelengths; ++i) r.v[i] = v[i] op o.v[i];                  \
        return r;                                                                          \
    }                                                                                      \
    SampledSpectrum operator op(double s) const {                                          \
        SampledSpectrum r;                                                                 \
        for (int i = 0; i < NumWavelengths; ++i) r.v[i] = v[i] op s;                       \
        return r;                                                                          \
    }                                                                                      \
    SampledSpectrum &operator op##=(const SampledSpectrum &o) { return *this = *this op o; } \
    SampledSpectrum &operator op##=(double s) { return *this = *this op s; }
    PHASOR_SS_OP(+)
    PHASOR_SS_OP(-)
    PHASOR_SS_OP(*)
    PHASOR_SS_OP(/)
#undef PHASOR_SS_OP
    bool IsZero() const {
        for (double x : v)
            if (x != 0) return false;
        return true;
    }
    double Max() const { return std::max(std::max(v[0], v[1]), std::max(v[2], v[3])); }
    double Average() const { return (v[0] + v[1] + v[2] + v[3]) / NumWavelengths; }
    bool IsFinite() const {
        for (double x : v)
            if (!std::isfinite(x)) return false;
        return true;
    }
};
inline SampledSpectrum operator*(double s, const SampledSpectrum &a) { return a * s; }

/// The wavelengths one path carries. For a continuous spectrum `pdf[i]` is a density [1/m] and
/// all NumWavelengths entries are used; when `delta` is true the path carries exactly one
/// discrete emission line (entry 0, `pdf[0]` = the probability of picking that line, other
/// entries have pdf 0 and are ignored).
struct SampledWavelengths {
    std::array<double, NumWavelengths> lambda{};  // [m]
    std::array<double, NumWavelengths> pdf{};
    bool delta = false;
    /// Drops the companions (a dispersive near-delta lobe was taken; theory §0 D10). The hero's
    /// pdf is divided by NumWavelengths, so averaging L/pdf over all NumWavelengths entries
    /// (skipping pdf 0, as the film does) stays unbiased. No-op for a delta sample.
    void TerminateSecondary();
    bool SecondaryTerminated() const;
    int Count() const { return delta ? 1 : NumWavelengths; }
};

/// A spectral distribution: emission [W/m²/sr/m for radiance spectra, or relative], reflectance,
/// index … as a function of vacuum wavelength [m].
class Spectrum {
  public:
    virtual ~Spectrum() = default;
    /// Value at `lambda` [m]. For a line (IsLine()), the value at exactly the line wavelength is
    /// the line's integrated strength and 0 elsewhere.
    virtual double Eval(double lambda) const = 0;
    /// Upper bound of Eval over all wavelengths (for sampling and checks).
    virtual double MaxValue() const = 0;
    /// Wavelength interval outside which the spectrum is zero (or negligible, < 1e-6 of peak)
    /// [m]; infinite bounds for a constant.
    virtual std::pair<double, double> Support() const = 0;
    /// A discrete emission line at this wavelength (theory §0 D10), or nullopt.
    virtual std::optional<double> LineWavelength() const { return std::nullopt; }
    virtual std::string ToString() const = 0;

    /// Values at the sampled wavelengths. Emission spectra must use EvalEmission instead.
    SampledSpectrum Sample(const SampledWavelengths &wl) const;
};

/// Emission at the sampled wavelengths, honouring lines: a line spectrum contributes only to a
/// `delta` sample at its wavelength, a continuous one only to continuous samples.
SampledSpectrum EvalEmission(const Spectrum &s, const SampledWavelengths &wl);

class ConstantSpectrum final : public Spectrum {
  public:
    explicit ConstantSpectrum(double c) : c_(c) {}
    double Eval(double) const override { return c_; }
    double MaxValue() const override { return c_; }
    std::pair<double, double> Support() const override { return {0, Infinity}; }
    std::string ToString() const override;

  private:
    double c_;
};

/// Planck's law for a black body at temperature T [K]: spectral radiance [W/(m²·sr·m)].
double Blackbody(double lambda, double T);

/// The CIE 1931 2° colour-matching functions x̄, ȳ, z̄ at `lambda` [m] (0 outside 360–830 nm),
/// linearly interpolated from a 1 nm (or finer than 5 nm) table.
Vec3 CieXyz(double lambda);
inline constexpr double CieLambdaMin = 360e-9, CieLambdaMax = 830e-9;
/// ∫ȳ(λ) dλ [m] over the table (≈ 106.857e-9).
double CieYIntegral();
/// CIE standard illuminant D65 relative SPD (100 at 560 nm), 0 outside 300–830 nm.
double CieD65(double lambda);
/// XYZ → linear Rec.709/sRGB primaries with D65 white.
Vec3 XyzToLinearSrgb(const Vec3 &xyz);
Vec3 LinearSrgbToXyz(const Vec3 &rgb);

/// What a detector measures per wavelength (theory §0 D10).
class SensorResponse {
  public:
    enum class Kind { CieXyz, Radiometric };
    explicit SensorResponse(Kind k) : kind_(k) {}
    Kind GetKind() const { return kind_; }
    /// Weights of the three output channels at `lambda` (XYZ for CIE; (1,1,1) radiometric).
    /// Channel values are ∫ L(λ)·w(λ) dλ; CIE channels are normalised by ∫ȳ so that a flat
    /// spectrum of value 1 reads Y = 1.
    Vec3 Channels(double lambda) const;
    /// Weight of the monochrome `intensity` channel (ȳ/∫ȳ for CIE, 1 for radiometric).
    double Intensity(double lambda) const;
    /// Both at once, from one look-up of the colour matching functions (the film, per sample):
    /// {Channels(lambda), Intensity(lambda)}.
    struct Weights {
        Vec3 channels;
        double intensity;
    };
    Weights At(double lambda) const;
    /// A sampling density shape (unnormalised, ≥ 0) over wavelength for this response.
    double Importance(double lambda) const;
    std::string Name() const { return kind_ == Kind::CieXyz ? "cie_xyz" : "radiometric"; }

    /// White balance (CIE sensors): from now on WhiteBalance() maps the white of `illuminant` (its
    /// XYZ) to the output white D65 at the same luminance Y, by a von Kries scaling in Bradford cone
    /// space (LMS = M_B·XYZ; Lam 1985, as pbrt-v4's film and ICC v4 do). Intensity() stays ȳ.
    void SetWhiteBalance(const Spectrum &illuminant);
    /// The adaptation of SetWhiteBalance applied to an XYZ value (identity when not balanced). The
    /// film applies it to each pixel's mean, not to samples: the matrix has negative entries, so a
    /// sample's adapted XYZ may be negative, which the film would reject as invalid (a bias).
    Vec3 WhiteBalance(const Vec3 &xyz) const;
    bool WhiteBalanced() const { return balanced_; }

  private:
    Kind kind_;
    bool balanced_ = false;
    std::array<double, 9> adapt_{};  // row-major XYZ → XYZ adaptation (with balanced_)
};

/// Samples wavelengths ∝ (Σ emitter spectra) × sensor importance over whatever range they span
/// (theory §0 D10): discrete lines are chosen with probability ∝ their strength × response, the
/// continuous part is tabulated on a fine grid and sampled with the hero + stratified companions
/// (companion i at CDF offset i/NumWavelengths).
class WavelengthSampler {
  public:
    /// `emitters` are the scene's emission spectra, each with a positive scale (e.g. area·π for
    /// an area light) telling its relative contribution.
    WavelengthSampler(const std::vector<std::pair<const Spectrum *, double>> &emitters,
                      const SensorResponse &response);
    /// u in [0,1): one uniform number drives the whole choice (the hero at CDF value u).
    SampledWavelengths Sample(double u) const;
    /// A pixel sample's wavelengths from a 2-D sample (what the render loop uses): the same
    /// distribution per sample as Sample(u), but when u.x is stratified over a pixel's n samples
    /// (Sobol') the n·NumWavelengths wavelengths are stratified in as many CDF cells — Sample(u)
    /// stratifies only n, repeating them for each companion.
    SampledWavelengths Sample(Vec2 u) const;
    /// Probability density [1/m] of the continuous part at lambda (already including the
    /// probability of choosing the continuous part).
    double Pdf(double lambda) const;
    double LambdaMin() const { return lo_; }
    double LambdaMax() const { return hi_; }

  private:
    SampledWavelengths SampleContinuous(double uc) const;  // hero at CDF value uc of the continuum
    SampledWavelengths SampleLine(double ul) const;        // ul in [0, Σ lineProb_)
    double lo_ = 360e-9, hi_ = 830e-9;
    std::vector<double> grid_, cdf_;   // continuous part: piecewise-constant density on grid cells
    std::vector<uint32_t> guide_;      // guide table: first cell whose CDF interval reaches j/size
    std::vector<double> lines_, lineProb_;  // discrete lines and their selection probability
    double continuousProb_ = 1;
};

}  // namespace phasor
