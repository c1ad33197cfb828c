// SPDX-License-Identifier: Apache-2.0
// phasor — what an integrator can render (issue 26 §2), declared once by each integrator
// (Integrator::Support) and read in two places: the scene checks at load (Integrator::Validate →
// ValidateSupport: `phasor check`, `render`, `compare` and every program that builds a Scene say
// the same thing, at the object's file:line:col) and the table of docs/plugins.md ("What each
// integrator renders", SupportMarkdown, printed by `phasor describe --markdown`).
#pragma once

#include <array>
#include <string>

#include "core/render/light.h"
#include "core/render/material.h"

namespace phasor {

class Diagnostics;
class Integrator;
class Scene;

/// How an integrator reaches the lights of one LightType.
enum class LightReach {
    /// It cannot render such a light: a load error at the light.
    Refused,
    /// Paths hit it (its emission, L or Le) and next-event estimation samples it, weighted by
    /// multiple importance sampling.
    HitAndSampled,
    /// Only next-event estimation from a path vertex with a continuous lobe reaches it: a classical
    /// path never hits a delta light, and neither the detector nor a specular (near-delta) lobe sees
    /// one (`ray`). When no kernel of the scene has a continuous lobe, the light is unreachable (a
    /// warning at load; a black image says so).
    SampledOnly,
    /// Measured in closed form (Eq. 24, theory §2.4) by the detector's generalized rays (D4a) and
    /// through every near-delta lobe (D14), and reached by next-event estimation; continuous
    /// sources of the type are also hit.
    ClosedForm,
    /// Propagated as a coherent field (Light::Coherent(), a line spectrum).
    Field,
};

/// What detector an integrator needs.
enum class DetectorNeed {
    Rays,              // any detector (Detector::Generate)
    GeneralizedRays,   // one that generates generalized rays (Detector::SupportsGR)
    SensorPlane,       // a sensor plane (Detector::SensorPlane: `virtual_plane`)
};

/// How an integrator treats one kernel capability (KernelCaps).
enum class KernelReach {
    Refused,          // a load error at the shape
    RayOpticsLimit,   // queried in the ray-optics limit (ScatterQuery::rayOptics: deltas, geometric shadows)
    Full,             // as a generalized ray sees it (footprints, every listed lobe)
    OpeningsOnly,     // footprint-aware kernels with openings (Material::Openings) only: one planar plate
};

/// An integrator's declarations (Integrator::Support).
struct IntegratorSupport {
    /// Per LightType (indexed by its value).
    std::array<LightReach, NumLightTypes> lights{};
    DetectorNeed detector = DetectorNeed::Rays;
    /// Per capability, in the order of KernelCapOrder: continuous lobes, near-delta lobes,
    /// footprint-aware. A footprint-aware kernel is judged by that entry alone.
    std::array<KernelReach, 3> kernels{};
    /// Carries polarisation: honours a detector's `polarizer` and `stokes`.
    bool polarization = false;

    LightReach Reach(LightType t) const { return lights[std::size_t(t)]; }
};

/// The kernel capabilities IntegratorSupport::kernels describes, in its order.
inline constexpr unsigned KernelCapOrder[3] = {CapContinuous, CapNearDelta, CapFootprintAware};

/// The checks every integrator's Validate starts with: the detector it needs, a detector's
/// polarisation options, each light's type (and a coherent field with a line spectrum where it
/// needs one), each shape's kernel capabilities, and delta lights that a SampledOnly integrator
/// cannot reach (a warning). Reports at the objects' locations.
void ValidateSupport(const Integrator &integrator, const Scene &scene, Diagnostics &diag);

/// Why a SampledOnly integrator reaches none of the scene's delta lights (no kernel of the scene
/// has a continuous lobe in the integrator's regime), naming them; "" if it reaches them or the
/// integrator is not SampledOnly. For the load warning and the black-image cause.
std::string UnreachableDeltaLights(const Integrator &integrator, const Scene &scene);

/// "What each integrator renders": every registered integrator's declarations as Markdown tables
/// (lights by plug-in, detectors by plug-in, kernel capabilities, polarisation), for docs/plugins.md.
std::string SupportMarkdown();

}  // namespace phasor
