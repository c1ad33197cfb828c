// SPDX-License-Identifier: Apache-2.0
// phasor — the numbers of `phasor compare` (compare_report.h): error metrics, the consistency
// test against the reference's noise, and the reference's noise floor.

#include <algorithm>
#include <cmath>

#include "app/compare_report.h"
#include "core/math.h"

namespace phasor {

CompareMetrics ErrorMetrics(const std::vector<double> &image, const std::vector<double> &reference) {
    CompareMetrics m;
    if (image.size() != reference.size() || image.empty()) return m;
    double sumSq = 0, sumRef = 0, peak = -Infinity, maxAbs = 0;
    long long n = 0;
    for (std::size_t i = 0; i < image.size(); ++i) {
        if (!std::isfinite(image[i]) || !std::isfinite(reference[i])) {
            ++m.skipped;
            continue;
        }
        const double d = image[i] - reference[i];
        sumSq += d * d;
        sumRef += reference[i];
        peak = std::max(peak, reference[i]);
        maxAbs = std::max(maxAbs, std::abs(d));
        ++n;
    }
    if (n == 0) return m;
    m.rmse = std::sqrt(sumSq / double(n));
    const double mean = sumRef / double(n), eps = 0.01 * mean * mean;
    if (eps > 0) {
        double rel = 0;
        for (std::size_t i = 0; i < image.size(); ++i)
            if (std::isfinite(image[i]) && std::isfinite(reference[i])) {
                const double d = image[i] - reference[i];
                rel += d * d / (reference[i] * reference[i] + eps);
            }
        m.relMse = rel / double(n);
    }
    if (peak > 0) m.maxError = maxAbs / peak;
    return m;
}

double RgbRmse(const Image &image, const Image &reference) {
    constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
    if (image.width != reference.width || image.height != reference.height) return NaN;
    int a[3], b[3];
    for (int c = 0; c < 3; ++c) {
        a[c] = image.ChannelIndex(std::string(1, "RGB"[c]));
        b[c] = reference.ChannelIndex(std::string(1, "RGB"[c]));
        if (a[c] < 0 || b[c] < 0) return NaN;
    }
    const std::size_t n = std::size_t(image.width) * image.height, na = image.channels.size(),
                      nb = reference.channels.size();
    double sum = 0;
    long long count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double d2 = 0;
        bool finite = true;
        for (int c = 0; c < 3; ++c) {
            const double d = double(image.data[i * na + a[c]]) - double(reference.data[i * nb + b[c]]);
            finite &= std::isfinite(d);
            d2 += d * d;
        }
        if (!finite) continue;
        sum += d2;
        count += 3;
    }
    return count > 0 ? std::sqrt(sum / double(count)) : NaN;
}

ConsistencyTest TestConsistency(const std::vector<double> &image, const std::vector<double> &imageVariance,
                                const std::vector<double> &reference, const std::vector<double> &referenceVariance,
                                int width, int height) {
    ConsistencyTest t;
    const std::size_t n = std::size_t(width) * height;
    if (width <= 0 || height <= 0 || image.size() != n || reference.size() != n || imageVariance.size() != n ||
        referenceVariance.size() != n)
        return t;
    // At most 16 × 16 blocks of whole pixels.
    const int bw = (width + 15) / 16, bh = (height + 15) / 16;
    const int nx = (width + bw - 1) / bw, ny = (height + bh - 1) / bh;
    std::vector<double> diff(std::size_t(nx) * ny, 0.0), var(diff.size(), 0.0), size(diff.size(), 0.0);
    std::vector<char> used(diff.size(), 0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x, b = std::size_t(y / bh) * nx + x / bw;
            const double d = image[i] - reference[i], v = imageVariance[i] + referenceVariance[i];
            if (!std::isfinite(d) || !std::isfinite(v) || v < 0) continue;
            diff[b] += d;
            var[b] += v;
            size[b] += std::abs(image[i]) + std::abs(reference[i]);
            used[b] = 1;
        }
    bool exactMismatch = false;
    for (std::size_t b = 0; b < diff.size(); ++b) {
        if (!used[b]) continue;
        if (var[b] > 0) {
            t.chi2 += diff[b] * diff[b] / var[b];
            ++t.dof;
        } else {
            exactMismatch |= std::abs(diff[b]) > 1e-9 * size[b];  // two noiseless blocks that differ
        }
    }
    if (t.dof == 0 && !exactMismatch) return t;  // nothing to test with
    t.tested = true;
    t.z = t.dof > 0 ? (t.chi2 - t.dof) / std::sqrt(2.0 * t.dof) : Infinity;
    if (exactMismatch) t.z = Infinity;
    t.consistent = t.z <= ConsistencyZ;
    return t;
}

void SetNoiseFloor(CompareReference &ref, std::vector<double> variance, const std::string &source) {
    double sum = 0;
    long long n = 0;
    for (double v : variance)
        if (std::isfinite(v) && v >= 0) {
            sum += v;
            ++n;
        }
    ref.noiseFloor = n > 0 ? std::sqrt(sum / double(n)) : std::numeric_limits<double>::quiet_NaN();
    ref.variance = std::move(variance);
    ref.noiseSource = source;
}

void ComputeErrors(std::vector<CompareRun> &runs, CompareReference &ref) {
    if (ref.kind != CompareReference::Kind::Image) {
        for (CompareRun &r : runs)
            if ((r.isReferenceRun || r.isReference) && r.image && r.status != CompareRun::Status::Failed) {
                r.isReference = true;
                ref.kind = CompareReference::Kind::Run;
                ref.image = &*r.image;
                ref.name = r.name;
                ref.waveOptical = r.waveOptical;
                ref.values = r.intensity;
                if (r.deterministic)
                    SetNoiseFloor(ref, std::vector<double>(r.intensity.size(), 0.0),
                                  "deterministic: no sampling noise");
                break;
            }
    }
    if (!ref.image) return;
    ref.peak = 0;
    for (double v : ref.values)
        if (std::isfinite(v)) ref.peak = std::max(ref.peak, v);
    const int w = ref.image->width, h = ref.image->height;
    for (CompareRun &r : runs) {
        if (r.isReference || !r.image) continue;
        r.comparable = !ref.waveOptical || *ref.waveOptical == r.waveOptical;
        CompareMetrics m = ErrorMetrics(r.intensity, ref.values);
        m.rgbRmse = RgbRmse(*r.image, *ref.image);
        r.metrics = m;
        // The test needs both variances: a sampling run's from its variance channel (one sample
        // has none), a deterministic run's is 0.
        const bool runVariance = r.deterministic || (r.sppReached >= 2 && r.variance.size() == r.intensity.size());
        if (r.comparable && runVariance && !ref.variance.empty())
            r.test = TestConsistency(r.intensity,
                                     r.deterministic ? std::vector<double>(r.intensity.size(), 0.0) : r.variance,
                                     ref.values, ref.variance, w, h);
        for (CompareSnapshot &s : r.snapshots)
            if (!s.metrics) {
                s.metrics = ErrorMetrics(std::vector<double>(s.intensity.begin(), s.intensity.end()), ref.values);
                s.intensity.clear();
                s.intensity.shrink_to_fit();
            }
    }
}

}  // namespace phasor
