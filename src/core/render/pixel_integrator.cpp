// SPDX-License-Identifier: Apache-2.0
#include "core/render/pixel_integrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

namespace phasor {

void PixelIntegrator::EstimateWork(const Scene &scene, int w, int h, const RenderOptions &opt,
                                   const Sampler &prototype) const {
    // A pilot of up to 256 samples spread over the image (at most ~0.5 s, at least one sample),
    // extrapolated to every pixel and sample on all threads; the film is not touched.
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<Sampler> sampler = prototype.Clone();
    PathStats ps;
    int n = 0;
    double elapsed = 0;
    for (; n < 256 && (n == 0 || elapsed < 0.5); ++n) {
        const int x = int((n * 0.618034 - std::floor(n * 0.618034)) * w), y = (n * h) / 256;
        // Samples spread over the pixel's set (a sample's cost depends on its direction).
        const int index = int((uint64_t(n) * 2654435761u + 7) % uint64_t(opt.spp));
        sampler->StartPixelSample(x, y, index);
        ps.sample = PixelSampleIndex{index, opt.spp, opt.seed};
        SampledWavelengths wl = scene.Wavelengths().Sample(sampler->Get1D());
        EstimatePixel(scene, x, y, wl, *sampler, ps);
        elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    const int threads = opt.threads > 0 ? opt.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    const double perSample = elapsed / n, samples = double(w) * h * opt.spp;
    char what[160];
    std::snprintf(what, sizeof what, "%d spp x %dx%d pixels at %.3g ms per sample on %d threads", opt.spp, w, h,
                  perSample * 1e3, threads);
    const std::string msg = WorkWarning(perSample * samples / threads, what,
                                        "lower the spp (--spp) or the detector's resolution; a sample's cost "
                                        "grows as the wavelength shrinks against the scene (openings many "
                                        "wavelengths wide), so check the light's spectrum");
    if (!msg.empty()) opt.warn(msg);
}

std::array<SampledSpectrum, 4> PixelIntegrator::EstimatePixelStokes(const Scene &, int, int, SampledWavelengths &,
                                                                    Sampler &, PathStats &) const {
    throw Error("integrator '" + name + "' carries no polarisation and cannot write Stokes channels");
}

RenderStats PixelIntegrator::Render(const Scene &scene, Film &film, const RenderOptions &opt) const {
    auto start = std::chrono::steady_clock::now();
    std::unique_ptr<tbb::global_control> threads;
    if (opt.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, opt.threads);
    std::unique_ptr<Sampler> prototype = scene.NewSampler(opt.sampler, opt.seed);
    if (!prototype) throw Error("unknown sampler '" + opt.sampler + "' (see 'phasor list sampler')");

    RenderStats stats;
    const int w = film.Width(), h = film.Height();
    if (opt.warn) EstimateWork(scene, w, h, opt, *prototype);
    constexpr int Tile = 16;
    auto cancelled = [&] { return opt.cancel && opt.cancel->load(std::memory_order_relaxed); };
    int done = 0;
    int batch = 1;
    while (done < opt.spp && !cancelled()) {
        int end = std::min(opt.spp, done + batch);
        tbb::combinable<PathStats> local;
        tbb::parallel_for(
            tbb::blocked_range2d<int>(0, h, Tile, 0, w, Tile),
            [&](const tbb::blocked_range2d<int> &r) {
                std::unique_ptr<Sampler> sampler = prototype->Clone();
                PathStats &ps = local.local();
                for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                    for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                        // Cancellation is checked per pixel, so a stop request is honoured within
                        // one pixel's batch of samples. A pixel gets all of the batch or none of
                        // it, so every pixel's mean and variance stay those of its own n samples.
                        if (cancelled()) return;
                        for (int s = done; s < end; ++s) {
                            sampler->StartPixelSample(x, y, s);
                            ps.sample = PixelSampleIndex{s, opt.spp, opt.seed};
                            // Wavelengths first, so they are stratified across the pixel's samples.
                            SampledWavelengths wl = scene.Wavelengths().Sample(sampler->Get1D());
                            if (film.HasStokes()) {
                                film.AddStokesSample(x, y, EstimatePixelStokes(scene, x, y, wl, *sampler, ps), wl);
                            } else {
                                SampledSpectrum L = EstimatePixel(scene, x, y, wl, *sampler, ps);
                                film.AddSample(x, y, L, wl);
                            }
                        }
                    }
            },
            tbb::simple_partitioner());
        local.combine_each([&](const PathStats &p) {
            stats.rays += p.rays;
            stats.counters += p.counters;
        });
        if (cancelled()) break;  // the pass may be incomplete: `done` stays the count every pixel has
        done = end;
        batch = std::min(batch * 2, 16);
        if (opt.progress) opt.progress(done, opt.spp);
    }
    for (std::size_t i = 0; i < stats.counters.n.size(); ++i)
        if (stats.counters.n[i] > 0)
            stats.metadata[std::string("phasor:count:") + Describe(RenderEvent(i)).key] =
                std::to_string(stats.counters.n[i]);
    stats.cancelled = done < opt.spp;
    // Pixels finished during an interrupted pass hold more samples than the others.
    long long fewest = film.SampleCount(0, 0), most = fewest;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            fewest = std::min(fewest, film.SampleCount(x, y));
            most = std::max(most, film.SampleCount(x, y));
        }
    stats.sppReached = int(fewest);
    stats.sppMax = int(most);
    stats.invalidSamples = film.InvalidSampleCount();
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

}  // namespace phasor
