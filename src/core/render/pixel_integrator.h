// SPDX-License-Identifier: Apache-2.0
// phasor — the shared render loop of integrators that estimate each pixel independently
// (`ray`, `grt`): TBB over 16×16 tiles, sample passes in growing batches (1, 2, 4, … 16 spp),
// deterministic per (pixel, sample). Cancellation is checked before each pixel's batch, so a stop
// request is honoured within about one pixel's batch; a partial image is valid pixel by pixel
// (each pixel's mean and variance are those of its own sample count; the pixels finished in the
// interrupted pass have one batch more than the rest).
#pragma once

#include "core/render/detector.h"
#include "core/scratch_buffer.h"
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
    /// (wl.TerminateSecondary()) when a dispersive lobe is taken. `scratch` is the calling
    /// thread's buffer for what the estimate prepares (kernels: Material::Prepare); the caller
    /// resets it after each estimate.
    /// Times a few samples before the first pass and reports through opt.warn when the whole
    /// render would take far longer than usual (WorkWarning).
    void EstimateWork(const Scene &scene, int w, int h, const RenderOptions &opt, const Sampler &prototype) const;
    virtual SampledSpectrum EstimatePixel(const Scene &scene, int x, int y, SampledWavelengths &wl,
                                          Sampler &sampler, ScratchBuffer &scratch, PathStats &stats) const = 0;
    /// The same estimate as a Stokes vector per carried wavelength (S[0] = EstimatePixel's value),
    /// for a film with Stokes output (Film::EnableStokes). Integrators that carry no polarisation
    /// throw phasor::Error (the scene check refuses such pairs before rendering).
    virtual std::array<SampledSpectrum, 4> EstimatePixelStokes(const Scene &scene, int x, int y,
                                                               SampledWavelengths &wl, Sampler &sampler,
                                                               ScratchBuffer &scratch, PathStats &stats) const;
};

}  // namespace phasor
