// SPDX-License-Identifier: Apache-2.0
// phasor — the scene's wavelength sampler (spectrum.h, theory §0 D10).
//
// Wavelengths are drawn ∝ (Σ_e scale_e · S_e(λ)) · importance(λ) over whatever range the
// emitters span — no fixed visible band, so a 1 µm laser renders with a radiometric sensor.
// The density is a mixture of
//   * discrete atoms, one per emission line (Spectrum::LineWavelength()), of mass
//     scale · strength · importance(λ_line): a picked line gives a `delta` sample carrying that
//     single wavelength with pdf[0] = its selection probability;
//   * a continuous part, tabulated on a fine grid over the union of the continuous emitters'
//     supports (clipped to the response's support) and sampled by inverting its piecewise-constant
//     CDF: the hero at CDF value u and companion i at u + i/NumWavelengths (mod 1), i.e.
//     stratified, each marginally distributed with the tabulated density.
// One uniform number picks the part (continuous first, then the lines in order) and, rescaled,
// drives the continuous inversion.
//
// Choices worth knowing:
//   * Grid: each continuous emitter contributes breakpoints every min(1 nm, width/64) over its
//     support (so narrow Gaussians get ≥ 64 cells), with at most 2e5 cells per emitter; the
//     breakpoints of all emitters are merged. A cell's mass is Simpson's rule on the product, so a
//     cell is sampled whenever the product is positive at either end or in the middle.
//   * Unbounded supports (a constant spectrum seen by the radiometric sensor) fall back to
//     360–830 nm on the unbounded side(s); emission outside that range is not sampled.
//   * A line the response cannot see (CIE at 1 µm) has zero mass and is never picked: it
//     contributes nothing to the image, which is correct. If nothing visible emits at all (or there
//     are no emitters) the sampler draws from the response's importance alone, so rendering still
//     works and yields black.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/spectrum/spectrum.h"

namespace phasor {

namespace {

constexpr double FallbackLo = 360e-9, FallbackHi = 830e-9;  // [m]
constexpr double MaxStep = 1e-9;                            // grid step ≤ 1 nm
constexpr int MinCellsPerEmitter = 64;
constexpr double MaxCellsPerEmitter = 2e5;

std::pair<double, double> ResponseSupport(const SensorResponse &r) {
    if (r.GetKind() == SensorResponse::Kind::CieXyz) return {CieLambdaMin, CieLambdaMax};
    return {0, Infinity};
}

// Replaces unbounded sides of [a, b] by the fallback band.
std::pair<double, double> Bounded(double a, double b) {
    const bool loOpen = !(a > 0) || !std::isfinite(a), hiOpen = !std::isfinite(b);
    if (loOpen && hiOpen) return {FallbackLo, FallbackHi};
    if (hiOpen) return {a, std::max(FallbackHi, 2 * a)};
    if (loOpen) return {std::min(FallbackLo, 0.5 * b), b};
    return {a, b};
}

}  // namespace

WavelengthSampler::WavelengthSampler(const std::vector<std::pair<const Spectrum *, double>> &emitters,
                                     const SensorResponse &response) {
    const auto [respLo, respHi] = ResponseSupport(response);

    // ---- Split the emitters into lines and a continuum.
    std::vector<std::pair<const Spectrum *, double>> continuous;
    std::vector<double> lineWeight;
    for (const auto &[s, scale] : emitters) {
        if (!s || !(scale > 0) || !std::isfinite(scale)) continue;
        if (std::optional<double> line = s->LineWavelength()) {
            const double w = scale * s->Eval(*line) * response.Importance(*line);
            if (!(w > 0) || !std::isfinite(w)) continue;  // invisible to this sensor
            // Merge lines at the same wavelength so every emitter of that line sees the sample.
            auto it = std::find_if(lines_.begin(), lines_.end(), [&](double l) {
                return std::abs(l - *line) <= 1e-12 * std::max(l, *line);
            });
            if (it != lines_.end()) {
                lineWeight[it - lines_.begin()] += w;
            } else {
                lines_.push_back(*line);
                lineWeight.push_back(w);
            }
        } else if (s->MaxValue() > 0) {
            continuous.emplace_back(s, scale);
        }
    }

    // ---- Grid over the union of the continuous supports (∩ the response support).
    auto buildGrid = [&](const std::vector<std::pair<double, double>> &ranges) {
        std::vector<double> pts;
        for (auto [a, b] : ranges) {
            const double width = b - a;
            double step = std::min(MaxStep, width / MinCellsPerEmitter);
            step = std::max(step, width / MaxCellsPerEmitter);
            const int n = std::max(1, int(std::ceil(width / step - 1e-9)));
            for (int k = 0; k <= n; ++k) pts.push_back(k == n ? b : a + width * k / n);
        }
        std::sort(pts.begin(), pts.end());
        std::vector<double> grid;
        for (double p : pts)
            if (grid.empty() || p - grid.back() > 1e-9 * MaxStep) grid.push_back(p);
        return grid;
    };
    std::vector<std::pair<double, double>> ranges;
    for (const auto &[s, scale] : continuous) {
        auto [a, b] = s->Support();
        a = std::max(a, respLo);
        b = std::min(b, respHi);
        std::tie(a, b) = Bounded(a, b);
        if (b > a) ranges.emplace_back(a, b);
    }

    // Density (unnormalised) of the continuous part at λ.
    auto product = [&](double lambda) {
        double e = 0;
        for (const auto &[s, scale] : continuous) e += scale * s->Eval(lambda);
        return std::max(0.0, e) * response.Importance(lambda);
    };
    // Tabulates `f` on `grid` into grid_ / cdf_; returns the total mass (∫ f dλ, Simpson per cell).
    auto tabulate = [&](std::vector<double> grid, auto &&f) {
        grid_ = std::move(grid);
        cdf_.assign(grid_.size(), 0.0);
        if (grid_.size() < 2) return 0.0;
        double fLeft = f(grid_[0]), total = 0;
        for (std::size_t k = 0; k + 1 < grid_.size(); ++k) {
            const double a = grid_[k], b = grid_[k + 1];
            const double fMid = f(0.5 * (a + b)), fRight = f(b);
            const double mass = (b - a) * (fLeft + 4 * fMid + fRight) / 6;  // Simpson's rule
            total += std::isfinite(mass) ? std::max(mass, 0.0) : 0.0;
            cdf_[k + 1] = total;
            fLeft = fRight;
        }
        return total;
    };

    double continuousMass = ranges.empty() ? 0.0 : tabulate(buildGrid(ranges), product);
    double lineMass = 0;
    for (double w : lineWeight) lineMass += w;
    const double total = continuousMass + lineMass;

    if (!(total > 0) || !std::isfinite(total)) {
        // Nothing visible emits: sample the response's importance alone.
        lines_.clear();
        lineWeight.clear();
        auto [a, b] = Bounded(respLo, respHi);
        continuousMass = tabulate(buildGrid({{a, b}}), [&](double l) { return response.Importance(l); });
        continuousProb_ = 1;
    } else {
        continuousProb_ = continuousMass / total;
        for (double w : lineWeight) lineProb_.push_back(w / total);
    }
    if (continuousMass > 0) {
        for (double &c : cdf_) c /= continuousMass;
        cdf_.back() = 1;
    } else {
        grid_.clear();
        cdf_.clear();
    }

    // ---- The range spanned.
    lo_ = Infinity;
    // Guide table (Chen & Asau 1974): guide_[j] is the first cell whose upper CDF value exceeds
    // j/G, so a lookup starts next to its answer instead of bisecting the whole table.
    if (cdf_.size() >= 2) {
        const std::size_t g = cdf_.size() - 1;
        guide_.assign(g, 0);
        std::size_t k = 0;
        for (std::size_t j = 0; j < g; ++j) {
            const double uj = double(j) / double(g);
            while (k + 2 < cdf_.size() && cdf_[k + 1] <= uj) ++k;
            guide_[j] = uint32_t(k);
        }
    }
    hi_ = -Infinity;
    if (!grid_.empty()) {
        lo_ = grid_.front();
        hi_ = grid_.back();
    }
    for (double l : lines_) {
        lo_ = std::min(lo_, l);
        hi_ = std::max(hi_, l);
    }
    if (!(lo_ <= hi_)) {
        lo_ = FallbackLo;
        hi_ = FallbackHi;
    }
}

SampledWavelengths WavelengthSampler::Sample(double u) const {
    u = std::clamp(u, 0.0, std::nextafter(1.0, 0.0));
    if (!grid_.empty() && (u < continuousProb_ || lines_.empty()))
        return SampleContinuous(std::min(u / continuousProb_, std::nextafter(1.0, 0.0)));
    return SampleLine(u - (grid_.empty() ? 0.0 : continuousProb_));
}

SampledWavelengths WavelengthSampler::Sample(Vec2 u) const {
    // u.y picks the part as Sample(u.y) does; in the continuum, what is left of it picks which of
    // the N equal CDF strata holds the hero and u.x places all N wavelengths inside their strata.
    // Per sample this is Sample(u) with u uniform (hero at (j + u.x)/N, companions i/N on); across
    // a pixel's n samples with u.x stratified in n cells the n·N wavelengths fall one per 1/(n·N)
    // of the CDF, where Sample(u) would put N of them in each of n cells.
    const double uy = std::clamp(u.y, 0.0, std::nextafter(1.0, 0.0));
    if (grid_.empty() || (uy >= continuousProb_ && !lines_.empty()))
        return SampleLine(uy - (grid_.empty() ? 0.0 : continuousProb_));
    const double stratum = std::min(std::floor(uy / continuousProb_ * NumWavelengths), NumWavelengths - 1.0);
    const double v = std::clamp(u.x, 0.0, std::nextafter(1.0, 0.0));
    return SampleContinuous(std::min((stratum + v) / NumWavelengths, std::nextafter(1.0, 0.0)));
}

SampledWavelengths WavelengthSampler::SampleContinuous(double uc) const {
    SampledWavelengths wl;
    for (int i = 0; i < NumWavelengths; ++i) {
        double ui = uc + double(i) / NumWavelengths;  // stratified companions (theory §0 D10)
        if (ui >= 1) ui -= 1;
        // First cell whose upper CDF value exceeds ui (cells of zero mass are skipped).
        const std::size_t cells = cdf_.size() - 1;
        std::size_t k = guide_[std::min(cells - 1, std::size_t(ui * double(cells)))];
        while (k + 1 < cells && cdf_[k + 1] <= ui) ++k;
        const double c0 = cdf_[k], c1 = cdf_[k + 1], a = grid_[k], b = grid_[k + 1];
        const double t = c1 > c0 ? (ui - c0) / (c1 - c0) : 0.5;
        wl.lambda[i] = std::clamp(a + t * (b - a), a, b);
        wl.pdf[i] = continuousProb_ * (c1 - c0) / (b - a);
    }
    return wl;
}

SampledWavelengths WavelengthSampler::SampleLine(double ul) const {
    SampledWavelengths wl;
    std::size_t pick = lines_.size() - 1;
    for (std::size_t j = 0; j < lines_.size(); ++j) {
        if (ul < lineProb_[j]) {
            pick = j;
            break;
        }
        ul -= lineProb_[j];
    }
    wl.delta = true;
    wl.lambda.fill(lines_[pick]);
    wl.pdf[0] = lineProb_[pick];
    return wl;
}

double WavelengthSampler::Pdf(double lambda) const {
    if (grid_.size() < 2 || !(lambda >= grid_.front()) || !(lambda <= grid_.back())) return 0;
    auto it = std::upper_bound(grid_.begin(), grid_.end(), lambda);
    std::size_t k =
        std::size_t(std::clamp<std::ptrdiff_t>(it - grid_.begin(), 1, std::ptrdiff_t(grid_.size()) - 1)) - 1;
    return continuousProb_ * (cdf_[k + 1] - cdf_[k]) / (grid_[k + 1] - grid_[k]);
}

}  // namespace phasor
