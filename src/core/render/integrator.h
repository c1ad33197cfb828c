// SPDX-License-Identifier: Apache-2.0
// phasor — integrators (docs/architecture.md). All render into the same Film from the same Scene.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/image/film.h"
#include "core/render/sampler.h"

namespace phasor {

class Scene;
class WorkShare;

struct RenderOptions {
    int spp = 16;
    uint64_t seed = 0;
    int threads = 0;  // 0 = all cores
    std::string sampler = "sobol";
    /// Set to true (e.g. from a SIGINT/SIGTERM handler) to stop soon: sampling integrators finish
    /// the pixels in progress (each pixel keeps a whole number of samples; RenderStats::sppReached
    /// is the count every pixel has), `rs` stops after the current batch of field nodes.
    const std::atomic<bool> *cancel = nullptr;
    /// Called from the calling thread with (units done, total units): sampling integrators count
    /// samples per pixel after each pass, deterministic ones (Integrator::Deterministic) their
    /// own steps (rs: batches of field nodes). May be empty.
    std::function<void(int, int)> progress;
    /// Called from the calling thread with a warning found while rendering (e.g. a work estimate
    /// far beyond the usual, before the first pass); may be empty.
    std::function<void(const std::string &)> warn;
    /// Other processes and checkpoints (core/render/work.h); null: this process alone.
    WorkShare *work = nullptr;
};

/// Render-time events an integrator counts and the user is told about once after the render (named
/// counters: an integrator adds one with RenderCounters::Add; the message lives in the table of
/// render.cpp's Describe, the CLI prints every non-zero counter).
enum class RenderEvent {
    /// A footprint-aware kernel (aperture) met a GR that had already left one: it acted
    /// geometrically (re-fitting the footprint after an aperture is future work; theory §9 item 5).
    FootprintAfterSpreadFree,
    /// Specular (delta) scattering of a spread-free GR in a scene with delta lights: a classical
    /// ray cannot reach those through a specular surface, so their light behind it is missing
    /// (theory §9 item 5).
    SpecularAfterSpreadFree,
    Count
};
struct RenderEventInfo {
    const char *key;      // stable name, e.g. "footprint_after_spread_free" (EXR metadata phasor:count:<key>)
    const char *message;  // what the count means, completing "N path vertices …"
};
const RenderEventInfo &Describe(RenderEvent e);

/// One counter per RenderEvent, merged across threads.
struct RenderCounters {
    std::array<long long, std::size_t(RenderEvent::Count)> n{};
    void Add(RenderEvent e, long long k = 1) { n[std::size_t(e)] += k; }
    long long operator[](RenderEvent e) const { return n[std::size_t(e)]; }
    RenderCounters &operator+=(const RenderCounters &o) {
        for (std::size_t i = 0; i < n.size(); ++i) n[i] += o.n[i];
        return *this;
    }
    /// "warning: N path vertices …" lines for every non-zero counter.
    std::vector<std::string> Warnings() const;
    /// EXR metadata "phasor:count:<key>" = N for every non-zero counter (others removed).
    void ToMetadata(std::map<std::string, std::string> &metadata) const;
};

/// The estimated run time [s] above which integrators warn before rendering (WorkWarning).
inline constexpr double LongRenderSeconds = 300;
/// "about 3h12m (…what…), far beyond the usual: …fix…", or "" if `seconds` ≤ LongRenderSeconds.
std::string WorkWarning(double seconds, const std::string &what, const std::string &fix);

struct RenderStats {
    int sppReached = 0;  // samples per pixel completed in every pixel (sampling integrators)
    int sppMax = 0;      // the most samples any pixel has (> sppReached after a cancellation)
    bool cancelled = false;
    /// False when the render was cancelled before it had anything honest to write (rs: its
    /// pixels need the whole field); the film is then empty and nothing may be written.
    bool hasImage = true;
    /// What a deterministic integrator did, in its own terms, for the user (rs: "solved 48
    /// pixels from 5210 field nodes"); empty for sampling integrators, which report spp.
    std::string work;
    /// Extra EXR metadata from the integrator ("phasor:…" keys), e.g. rs's node counts.
    std::map<std::string, std::string> metadata;
    double seconds = 0;
    long long invalidSamples = 0;  // NaN/Inf/negative estimates discarded (never written)
    long long rays = 0;            // rays traced (intersection + shadow)
    RenderCounters counters;  // render-time events (RenderEvent)
};

class Integrator {
  public:
    virtual ~Integrator() = default;
    /// Renders `scene` into `film` (whose size matches the scene's detector).
    virtual RenderStats Render(const Scene &scene, Film &film, const RenderOptions &opt) const = 0;
    virtual std::string ToString() const = 0;
    /// True for integrators that take no random samples (rs): no spp, seed or sampler applies;
    /// they report RenderStats::work and progress in their own steps.
    virtual bool Deterministic() const { return false; }
    /// True for integrators that carry polarisation (`sample_solve`): only they honour a detector's
    /// `polarizer` and `stokes` (Scene::Build refuses the others at those parameters).
    virtual bool SupportsPolarization() const { return false; }
    std::string name;
};

}  // namespace phasor
