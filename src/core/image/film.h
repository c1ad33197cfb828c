// SPDX-License-Identifier: Apache-2.0
// phasor — the film: per-pixel spectral accumulation → RGB + monochrome intensity + variance of
// the pixel mean; written as EXR through OpenImageIO and PNG through an OpenColorIO display
// transform (image_io.h). Thread-safe for distinct pixels (tiles never share pixels).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/spectrum/spectrum.h"

namespace phasor {

/// One finished image with named float channels, row-major, top row first.
struct Image {
    int width = 0, height = 0;
    std::vector<std::string> channels;  // e.g. R G B intensity variance
    std::vector<float> data;            // width*height*channels.size(), interleaved
    std::map<std::string, std::string> metadata;  // written as EXR string attributes
    int ChannelIndex(const std::string &name) const;  // -1 if absent
    float At(int x, int y, int c) const { return data[(std::size_t(y) * width + x) * channels.size() + c]; }
    float &At(int x, int y, int c) { return data[(std::size_t(y) * width + x) * channels.size() + c]; }
};

class Film {
  public:
    Film(int width, int height, SensorResponse response);

    int Width() const { return width_; }
    int Height() const { return height_; }
    const SensorResponse &Response() const { return response_; }

    /// Adds one sample's estimate for pixel (x, y): `L` holds the per-wavelength values
    /// (radiance, or irradiance for sensor planes), already divided by nothing; the film divides
    /// by the wavelength pdfs and averages over the carried wavelengths.
    /// Returns false if the sample was invalid (counted as a zero, AddInvalidSample).
    bool AddSample(int x, int y, const SampledSpectrum &L, const SampledWavelengths &wl);
    /// Adds a sample already reduced to (channels, intensity), e.g. from an integrator that
    /// computes its own spectral integral. Returns false if the sample was invalid (then counted
    /// by AddInvalidSample as a zero).
    bool AddReduced(int x, int y, const Vec3 &channels, double intensity);

    /// Polarisation output (a detector with `stokes = true`; `sample_solve`): keeps, besides the
    /// usual channels, the running means of the Stokes parameters S0..S3, each reduced over the
    /// carried wavelengths like `intensity` (the response's Intensity weight, divided by the
    /// wavelength pdfs). Call before the first sample.
    void EnableStokes();
    bool HasStokes() const { return stokes_; }
    /// One sample's Stokes vector per carried wavelength (S[0] = the value AddSample takes, in the
    /// same units; S[1..3] may be negative). S[0] goes through AddSample; an invalid sample (or a
    /// non-finite S1..S3) adds zeros to every Stokes mean.
    void AddStokesSample(int x, int y, const std::array<SampledSpectrum, 4> &S, const SampledWavelengths &wl);
    /// Records a sample that was discarded because of numerical trouble (NaN/Inf/negative, or a
    /// value the float image cannot hold). AddSample/AddReduced call it for such samples.
    void AddInvalidSample(int x, int y);

    /// Number of samples added to a pixel (including invalid ones, which count as zero).
    long long SampleCount(int x, int y) const;
    /// Samples discarded as invalid, plus every sample of a pixel whose resolved mean or variance
    /// is beyond the float range (> 3.4e38; such a pixel is written as 0, never as Inf).
    long long InvalidSampleCount() const;

    /// One pixel's accumulators, exactly as Resolve reads them, in a plain form for moving pixels
    /// between processes and into checkpoints (docs/distributed.md): the running (Welford) means of
    /// the channels and of `intensity`, the sum of squared deviations of `intensity`, the sample
    /// count (invalid samples included, as zeros) and the invalid count; with Stokes output the
    /// Stokes means and their count (zeros otherwise). Copying a pixel out and back in changes no bit.
    struct PixelState {
        double mean[3] = {0, 0, 0};
        double meanI = 0, m2I = 0;
        int64_t n = 0, invalid = 0;
        double stokes[4] = {0, 0, 0, 0};
        int64_t stokesN = 0;
    };
    /// The accumulators of the pixels [x0, x1) × [y0, y1), row-major, into `out` (that many entries).
    void GetPixels(int x0, int y0, int x1, int y1, PixelState *out) const;
    /// Replaces the accumulators of [x0, x1) × [y0, y1) by `in` (row-major). Thread-safe for
    /// distinct pixels, as AddSample.
    void SetPixels(int x0, int y0, int x1, int y1, const PixelState *in);

    /// Bytes a render of width × height holds at its peak (film, resolved image, the copies the
    /// EXR and PNG writers make, an integrator's per-pixel buffers); film_memory.cpp.
    static double MemoryNeeded(int width, int height);

    /// Final image: R, G, B (linear Rec.709 for CIE sensors; equal to intensity for radiometric
    /// ones), intensity, variance (the sample variance of the *mean* of `intensity`: s²/n, the i.i.d.
    /// estimate — exact in expectation for independent samples only; for Owen-scrambled Sobol'
    /// samples the real error is usually far smaller: docs/architecture.md, "Error estimates").
    /// Every value is finite: pixels that would overflow float are 0 (see InvalidSampleCount).
    /// With Stokes output (EnableStokes) five channels follow: S0, S1, S2, S3 (S0 equals
    /// intensity; the frame is the detector's, docs/sample_solve.md) and DoP, the degree of
    /// polarisation √(S1² + S2² + S3²)/S0 of the pixel's mean (0 where S0 = 0). When pixels hold different
    /// numbers of samples (a render stopped during a pass) a last channel, `samples`, holds each
    /// pixel's count (a pixel with 0 has no estimate: all 0).
    /// Metadata: phasor:samples_per_pixel (the fewest any pixel has), invalid_samples, sensor.
    Image Resolve() const;

  private:
    struct Pixel {
        // Running means and sum of squared deviations (Welford), robust against cancellation.
        Vec3 mean;          // channel means
        double meanI = 0, m2I = 0;
        long long n = 0;
        long long invalid = 0;
    };
    /// Running means of S0..S3 (EnableStokes), over the same samples as the pixel's.
    struct StokesMean {
        std::array<double, 4> mean{};
        long long n = 0;
    };
    /// A pixel's channels as written, in double, and whether all of them fit in a float.
    struct Resolved {
        Vec3 rgb;
        double intensity = 0, varianceOfMean = 0;
        bool representable = true;
    };
    Resolved ResolvePixel(const Pixel &p) const;

    int width_, height_;
    SensorResponse response_;
    std::vector<Pixel> pixels_;
    bool stokes_ = false;
    std::vector<StokesMean> stokesMeans_;
};

/// Memory this process may still allocate [bytes]: MemAvailable from /proc/meminfo (else free
/// physical pages from sysconf), capped by the environment variable PHASOR_MEMORY_LIMIT (bytes,
/// or with a K, M or G suffix) when it is set. film_memory.cpp.
double AvailableMemory();

}  // namespace phasor
