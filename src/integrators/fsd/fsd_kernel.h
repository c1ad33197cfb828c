// SPDX-License-Identifier: Apache-2.0
// phasor — a free-space diffraction event as a scattering vertex of the generalized-ray path
// (docs/fsd.md §8, theory §4.8): the FSD lobe (fsd_lobe.h) behind the PreparedKernel interface, so
// that next-event estimation, sampling, MIS and the footprint-aware re-weighting of gr_path.h treat
// it like an `aperture` plate (theory §9) whose mask is made of the scene's edges.
//
// The vertex stands on the GR's axis at the event's far side: p_v = p + d·beyond, past the
// geometry the mask already accounts for (Event::beyond), so that shadow rays and the ray that
// leaves the event are not stopped by the very edges they diffracted at. Its shading frame is the
// event plane's (n = d, the traced direction): light arrives from the far side (wo·d > 0) only.
// EvalFrom refers a spherical wave measured from p_v back to the event plane exactly (the source's
// distance and direction from p, and the 1/r² and cosine the caller applied at p_v).
#pragma once

#include <optional>

#include "integrators/fsd/fsd_lobe.h"

namespace phasor::fsd {

class EventKernel final : public PreparedKernel {
  public:
    /// `g`: the GR at its segment's origin (traced direction d); `ev`: the event FindEvent found on
    /// that segment. `wl` must outlive the kernel.
    EventKernel(Event ev, const SpectralGenRay &g, const SampledWavelengths &wl, const Settings &s);
    EventKernel(const EventKernel &) = delete;
    EventKernel &operator=(const EventKernel &) = delete;

    /// The vertex: p_v, n = shading.n = d, no shape and no material.
    const SurfaceInteraction &Interaction() const { return si_; }
    /// The GR at the event plane (propagated by ev.t, origin p).
    const SpectralGenRay &Gr() const { return gr_; }
    const Event &GetEvent() const { return ev_; }

    /// Scalar diffraction keeps the polarisation (as the aperture kernel): lobe 0 is the FSD lobe.
    std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override;

  private:
    std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const override;
    SampledSpectrum EvalContinuous(const Vec3 &wo) const override { return EvalContinuousFrom(wo, IncidentWave{}); }
    SampledSpectrum EvalContinuousFrom(const Vec3 &wo, const IncidentWave &w) const override;
    double PdfContinuous(const Vec3 &wo) const override;

    Event ev_;
    SpectralGenRay gr_;
    SurfaceInteraction si_;
    Lobe lobe_;  // refers to ev_ (declared before it)
};

/// The distance past the event plane at which rays leave an event (the vertex's p_v − p along d):
/// the gathered geometry's reach plus a margin far above Embree's float rounding there [m].
double LeaveDistance(const Event &ev);

/// What an event lets through of a wave `w` arriving along −wo (world) at the GR `g` (at the event
/// plane, aimed along ev.frame.n): |A_mask|²/|A_free|² per carried wavelength, the masked lobe's
/// amplitude against the same GR's with nothing in the box (0 where the free one vanishes). This
/// scales a closed-form measurement of that wave (theory §2.4, D4a) made by a GR aimed at its
/// source; for a sensor plane's integral over directions it is the mode-overlap approximation of
/// docs/fsd.md §5.
SampledSpectrum Transmission(const Event &ev, const SpectralGenRay &g, const SampledWavelengths &wl,
                             const Settings &s, const Vec3 &wo, const IncidentWave &w);

}  // namespace phasor::fsd
