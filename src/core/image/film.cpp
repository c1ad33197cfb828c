// SPDX-License-Identifier: Apache-2.0
// phasor — the film (film.h): per-pixel running means of the sensor channels and of the
// monochrome intensity, and the variance of the intensity mean.

#include "core/image/film.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/diagnostics.h"
#include "core/polarization.h"

namespace phasor {

int Image::ChannelIndex(const std::string &name) const {
    for (std::size_t i = 0; i < channels.size(); ++i)
        if (channels[i] == name) return int(i);
    return -1;
}

Film::Film(int width, int height, SensorResponse response)
    : width_(width), height_(height), response_(response) {
    if (width <= 0 || height <= 0)
        throw Error("film resolution must be positive, got " + std::to_string(width) + "x" +
                    std::to_string(height));
    pixels_.resize(std::size_t(width) * std::size_t(height));
}

bool Film::AddSample(int x, int y, const SampledSpectrum &L, const SampledWavelengths &wl) {
    // Monte Carlo estimate of ∫ L(λ) w(λ) dλ from the carried wavelengths: the average over the
    // Count() entries of L·w/pdf (hero wavelength sampling, theory §0 D10). An entry with pdf 0
    // (a terminated companion) contributes nothing; a delta sample uses only entry 0, whose pdf
    // is the probability of having picked that line.
    const int count = wl.Count();
    Vec3 channels;
    double intensity = 0;
    for (int i = 0; i < count; ++i) {
        if (wl.pdf[i] == 0) continue;
        const double f = L[i] / wl.pdf[i];
        const SensorResponse::Weights w = response_.At(wl.lambda[i]);
        channels += w.channels * f;
        intensity += w.intensity * f;
    }
    return AddReduced(x, y, channels / count, intensity / count);
}

namespace {

// The largest value the float EXR can hold (3.4e38): beyond it a value would be written as Inf.
constexpr double FloatMax = std::numeric_limits<float>::max();

bool Representable(double v) { return std::abs(v) <= FloatMax; }  // false also for NaN

}  // namespace

bool Film::AddReduced(int x, int y, const Vec3 &channels, double intensity) {
    // NaN, Inf, negative, or too large for the float image: an invalid sample.
    auto bad = [](double v) { return !(v >= 0) || !Representable(v); };
    if (bad(channels.x) || bad(channels.y) || bad(channels.z) || bad(intensity)) {
        AddInvalidSample(x, y);
        return false;
    }
    assert(x >= 0 && x < width_ && y >= 0 && y < height_);
    Pixel &p = pixels_[std::size_t(y) * width_ + x];
    // Welford's online update of mean and M2 = Σ(x − mean)² (Welford 1962).
    ++p.n;
    double invN = 1.0 / double(p.n);
    p.mean += (channels - p.mean) * invN;
    double delta = intensity - p.meanI;
    p.meanI += delta * invN;
    p.m2I += delta * (intensity - p.meanI);
    return true;
}

void Film::EnableStokes() {
    stokes_ = true;
    stokesMeans_.assign(pixels_.size(), StokesMean{});
}

void Film::AddStokesSample(int x, int y, const std::array<SampledSpectrum, 4> &S, const SampledWavelengths &wl) {
    // The same reduction as AddSample's `intensity`, per Stokes parameter.
    const int count = wl.Count();
    std::array<double, 4> r{};
    for (int i = 0; i < count; ++i) {
        if (wl.pdf[i] == 0) continue;
        const double w = response_.Intensity(wl.lambda[i]) / wl.pdf[i];
        for (int c = 0; c < 4; ++c) r[std::size_t(c)] += S[std::size_t(c)][i] * w;
    }
    for (double &v : r) v /= count;
    bool ok = std::isfinite(r[1]) && std::isfinite(r[2]) && std::isfinite(r[3]) && Representable(r[1]) &&
              Representable(r[2]) && Representable(r[3]);
    if (ok) ok = AddSample(x, y, S[0], wl);
    else AddInvalidSample(x, y);
    if (!stokes_) return;
    StokesMean &m = stokesMeans_[std::size_t(y) * width_ + x];
    ++m.n;
    const double invN = 1.0 / double(m.n);
    for (int c = 0; c < 4; ++c) m.mean[std::size_t(c)] += ((ok ? r[std::size_t(c)] : 0.0) - m.mean[std::size_t(c)]) * invN;
}

void Film::AddInvalidSample(int x, int y) {
    assert(x >= 0 && x < width_ && y >= 0 && y < height_);
    Pixel &p = pixels_[std::size_t(y) * width_ + x];
    ++p.invalid;
    // An invalid sample counts as a zero-valued sample (keeps the estimator's normalisation).
    ++p.n;
    double invN = 1.0 / double(p.n);
    p.mean -= p.mean * invN;
    double delta = -p.meanI;
    p.meanI += delta * invN;
    p.m2I += delta * (0 - p.meanI);
}

void Film::GetPixels(int x0, int y0, int x1, int y1, PixelState *out) const {
    assert(0 <= x0 && x0 <= x1 && x1 <= width_ && 0 <= y0 && y0 <= y1 && y1 <= height_);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++out) {
            const std::size_t i = std::size_t(y) * width_ + x;
            const Pixel &p = pixels_[i];
            *out = PixelState{};
            out->mean[0] = p.mean.x;
            out->mean[1] = p.mean.y;
            out->mean[2] = p.mean.z;
            out->meanI = p.meanI;
            out->m2I = p.m2I;
            out->n = p.n;
            out->invalid = p.invalid;
            if (stokes_) {
                for (int c = 0; c < 4; ++c) out->stokes[c] = stokesMeans_[i].mean[std::size_t(c)];
                out->stokesN = stokesMeans_[i].n;
            }
        }
}

void Film::SetPixels(int x0, int y0, int x1, int y1, const PixelState *in) {
    assert(0 <= x0 && x0 <= x1 && x1 <= width_ && 0 <= y0 && y0 <= y1 && y1 <= height_);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++in) {
            const std::size_t i = std::size_t(y) * width_ + x;
            Pixel &p = pixels_[i];
            p.mean = Vec3(in->mean[0], in->mean[1], in->mean[2]);
            p.meanI = in->meanI;
            p.m2I = in->m2I;
            p.n = in->n;
            p.invalid = in->invalid;
            if (stokes_) {
                for (int c = 0; c < 4; ++c) stokesMeans_[i].mean[std::size_t(c)] = in->stokes[c];
                stokesMeans_[i].n = in->stokesN;
            }
        }
}

long long Film::SampleCount(int x, int y) const {
    return pixels_[std::size_t(y) * width_ + x].n;
}

Film::Resolved Film::ResolvePixel(const Pixel &p) const {
    Resolved r;
    r.rgb = response_.GetKind() == SensorResponse::Kind::CieXyz ? XyzToLinearSrgb(response_.WhiteBalance(p.mean))
                                                                 : Vec3(p.meanI, p.meanI, p.meanI);
    r.intensity = p.meanI;
    // Variance of the mean: unbiased sample variance s² = M2/(n−1), divided by n.
    r.varianceOfMean = p.n >= 2 ? std::max(p.m2I / double(p.n - 1) / double(p.n), 0.0) : 0.0;
    r.representable = Representable(r.rgb.x) && Representable(r.rgb.y) && Representable(r.rgb.z) &&
                      Representable(r.intensity) && Representable(r.varianceOfMean);
    return r;
}

long long Film::InvalidSampleCount() const {
    long long total = 0;
    for (const Pixel &p : pixels_) total += ResolvePixel(p).representable ? p.invalid : p.n;
    return total;
}

Image Film::Resolve() const {
    long long minSamples = pixels_[0].n, maxSamples = pixels_[0].n;
    for (const Pixel &p : pixels_) {
        minSamples = std::min(minSamples, p.n);
        maxSamples = std::max(maxSamples, p.n);
    }
    Image img;
    img.width = width_;
    img.height = height_;
    img.channels = {"R", "G", "B", "intensity", "variance"};
    if (stokes_)
        for (const char *c : {"S0", "S1", "S2", "S3", "DoP"}) img.channels.push_back(c);
    // Pixels with different sample counts (a render stopped during a pass): each pixel's count
    // goes into a last channel, so that every value can be weighed by its own n.
    const bool counts = minSamples != maxSamples;
    if (counts) img.channels.push_back("samples");
    const int samplesChannel = int(img.channels.size()) - 1;
    img.data.assign(std::size_t(width_) * height_ * img.channels.size(), 0.0f);
    for (int y = 0; y < height_; ++y) {
        for (int x = 0; x < width_; ++x) {
            const Pixel &p = pixels_[std::size_t(y) * width_ + x];
            if (counts) img.At(x, y, samplesChannel) = float(p.n);
            // A pixel whose mean or variance the float image cannot hold stays 0 (never Inf); its
            // samples are counted as invalid (InvalidSampleCount).
            const Resolved r = ResolvePixel(p);
            if (!r.representable) continue;
            img.At(x, y, 0) = float(r.rgb.x);
            img.At(x, y, 1) = float(r.rgb.y);
            img.At(x, y, 2) = float(r.rgb.z);
            img.At(x, y, 3) = float(r.intensity);
            img.At(x, y, 4) = float(r.varianceOfMean);
            if (stokes_) {
                const StokesMean &m = stokesMeans_[std::size_t(y) * width_ + x];
                bool fits = true;
                for (double v : m.mean) fits = fits && Representable(v);
                for (int c = 0; c < 4 && fits; ++c) img.At(x, y, 5 + c) = float(m.mean[std::size_t(c)]);
                // The degree of polarisation of the pixel's mean Stokes vector (0 where S0 = 0).
                const Stokes s{m.mean[0], m.mean[1], m.mean[2], m.mean[3]};
                if (fits) img.At(x, y, 9) = float(DegreeOfPolarization(s));
            }
        }
    }
    img.metadata["phasor:samples_per_pixel"] = std::to_string(minSamples);
    img.metadata["phasor:invalid_samples"] = std::to_string(InvalidSampleCount());
    img.metadata["phasor:sensor"] = response_.Name();
    return img;
}

}  // namespace phasor
