// SPDX-License-Identifier: Apache-2.0
// phasor — the shared render loop of integrators that estimate each pixel independently
// (`ray`, `grt`, `sample_solve`): sample passes in growing batches (1, 2, 4, … 16 spp), each over
// 16×16 tiles that every thread (and, under MPI, every process) takes one by one from TilePasses
// (core/render/work.h); deterministic per (pixel, sample), and each pixel's samples are added in
// index order, so the image is the same for any number of threads and processes, and a film that
// already holds samples (a resumed checkpoint) continues bit for bit. Cancellation is checked before
// each pixel's batch, so a stop request is honoured within about one pixel's batch; a partial image is valid pixel by pixel
// (each pixel's mean and variance are those of its own sample count; the pixels finished in the
// interrupted pass have one batch more than the rest).
#pragma once

#include "core/render/detector.h"
#include "core/render/integrator.h"
#include "core/render/scene.h"

namespace phasor {

/// Per-thread counters merged after each batch, plus the render loop's position for the current
/// call (which sample of how many, and the seed — detectors stratify directions across a pixel's
/// samples with it, theory §0 D4b).
struct PathStats {
    long long rays = 0;
    RenderCounters counters;  // render-time events (RenderEvent)
    PixelSampleIndex sample;
};

class PixelIntegrator : public Integrator {
  public:
    RenderStats Render(const Scene &scene, Film &film, const RenderOptions &opt) const override;

    /// One estimate for pixel (x, y), sample `index`: the per-wavelength value the pixel reports
    /// (radiance for cameras), not divided by the wavelength pdfs (the film does that).
    /// The sampler is positioned after the wavelength dimension. May drop companion wavelengths
    /// (wl.TerminateSecondary()) when a dispersive lobe is taken.
    /// Times a few samples before the first pass and reports through opt.warn when the whole
    /// render would take far longer than usual (WorkWarning).
    void EstimateWork(const Scene &scene, int w, int h, const RenderOptions &opt, const Sampler &prototype) const;
    virtual SampledSpectrum EstimatePixel(const Scene &scene, int x, int y, SampledWavelengths &wl,
                                          Sampler &sampler, PathStats &stats) const = 0;
    /// The same estimate as a Stokes vector per carried wavelength (S[0] = EstimatePixel's value),
    /// for a film with Stokes output (Film::EnableStokes). Integrators that carry no polarisation
    /// throw phasor::Error (the scene check refuses such pairs before rendering).
    virtual std::array<SampledSpectrum, 4> EstimatePixelStokes(const Scene &scene, int x, int y,
                                                               SampledWavelengths &wl, Sampler &sampler,
                                                               PathStats &stats) const;
};

}  // namespace phasor
