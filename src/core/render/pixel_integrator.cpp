// SPDX-License-Identifier: Apache-2.0
#include "core/render/pixel_integrator.h"

#include "core/render/work.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include <time.h>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

namespace phasor {

double PixelIntegrator::EstimateWork(const Scene &scene, int w, int h, const RenderOptions &opt,
                                     const Sampler &prototype) const {
    // A pilot spread over the image by the R2 sequence (any prefix covers the whole image, so a
    // pilot stopped early by its time limit is not confined to the top rows) and over the pixel's
    // samples. The first samples fill caches and tables built on first use (a grating's order
    // listing, Gauss–Legendre rules): they are not timed. Then up to 1024 samples or 0.5 s, and at
    // most 1/64 of the render's samples (so a tiny render does not pay for more than it renders),
    // extrapolated to every pixel and sample on all threads; the film is not touched.
    const double samples = double(w) * h * opt.spp;
    const int pilot = int(std::clamp(samples / 64, 1.0, 1024.0));
    std::unique_ptr<Sampler> sampler = prototype.Clone();
    PathStats ps;
    ScratchBuffer buffer;  // what a sample prepares (kernels), reset after each
    auto sample = [&](int n) {
        const double fx = n * 0.7548776662466927, fy = n * 0.5698402909980532;  // R2 (plastic number)
        const int x = std::min(w - 1, int((fx - std::floor(fx)) * w)), y = std::min(h - 1, int((fy - std::floor(fy)) * h));
        // Samples spread over the pixel's set (a sample's cost depends on its direction).
        const int index = int((uint64_t(n) * 2654435761u + 7) % uint64_t(opt.spp));
        sampler->StartPixelSample(x, y, index);
        ps.sample = PixelSampleIndex{index, opt.spp, opt.seed};
        SampledWavelengths wl = scene.Wavelengths().Sample(sampler->Get2D());
        EstimatePixel(scene, x, y, wl, *sampler, buffer, ps);
        buffer.Reset();
    };
    const int warmUp = std::min(8, pilot / 8);
    for (int n = 0; n < warmUp; ++n) sample(n);
    // Timed in this thread's CPU time: on a machine other processes share, wall time would count
    // their time too, and the estimate would change with the load (it is the render's time on the
    // threads' own cores).
    const auto cpuNow = [] {
        timespec ts{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
        return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
    };
    const double c0 = cpuNow();
    int n = 0;
    double elapsed = 0;
    for (; n < pilot - warmUp && (n == 0 || elapsed < 0.5); ++n) {
        sample(warmUp + n);
        elapsed = cpuNow() - c0;
    }
    const int threads = opt.threads > 0 ? opt.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    const double perSample = elapsed / n, seconds = perSample * samples / threads;
    char what[160];
    std::snprintf(what, sizeof what, "%d spp x %dx%d pixels at %.3g ms per sample on %d threads", opt.spp, w, h,
                  perSample * 1e3, threads);
    // Advice that fits the scene: an aperture's cost grows with its openings' size in wavelengths.
    std::string fix = "lower the spp (--spp) or the detector's resolution";
    for (const auto &shape : scene.Shapes())
        if (shape->material && shape->material->IsFootprintAware()) {
            fix += "; a sample through an aperture costs more the more wavelengths its openings span, so check "
                   "the light's spectrum against the openings of '" + shape->name + "'";
            break;
        }
    const std::string msg = WorkWarning(seconds, what, fix);
    if (!msg.empty() && opt.warn) opt.warn(msg);
    return seconds;
}

std::array<SampledSpectrum, 4> PixelIntegrator::EstimatePixelStokes(const Scene &, int, int, SampledWavelengths &,
                                                                    Sampler &, ScratchBuffer &, PathStats &) const {
    throw Error("integrator '" + name + "' carries no polarisation and cannot write Stokes channels");
}

RenderStats PixelIntegrator::Render(const Scene &scene, Film &film, const RenderOptions &opt) const {
    auto start = std::chrono::steady_clock::now();
    std::unique_ptr<tbb::global_control> threads;
    if (opt.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, opt.threads);
    std::unique_ptr<Sampler> prototype = scene.NewSampler(opt.sampler, opt.seed);
    if (!prototype) throw Error("unknown sampler '" + opt.sampler + "' (see 'phasor list sampler')");

    auto cancelled = [&] { return opt.cancel && opt.cancel->load(std::memory_order_relaxed); };
    // Renders one tile: each pixel from its own sample count to the task's end, into a scratch film
    // holding the tile's accumulators (the film itself changes only when TilePasses takes it back).
    // `buffer` is the thread's own, for what a sample prepares (kernels: Material::Prepare).
    auto renderTile = [&](TileTask &task, Film &scratch, Sampler &sampler, ScratchBuffer &buffer) {
        const int tw = task.x1 - task.x0, th = task.y1 - task.y0;
        scratch.SetPixels(0, 0, tw, th, task.pixels.data());
        PathStats ps;
        for (int y = task.y0; y < task.y1; ++y)
            for (int x = task.x0; x < task.x1; ++x) {
                // Cancellation is checked per pixel, so a stop request is honoured within one
                // pixel's batch of samples. A pixel gets all of the batch or none of it, so every
                // pixel's mean and variance stay those of its own n samples.
                if (cancelled()) break;
                const int lx = x - task.x0, ly = y - task.y0;
                // Samples are added in index order from the pixel's count: who renders them, and in
                // which passes, changes no bit of its accumulator (work.h).
                for (int s = int(scratch.SampleCount(lx, ly)); s < task.sampleEnd; ++s) {
                    sampler.StartPixelSample(x, y, s);
                    ps.sample = PixelSampleIndex{s, opt.spp, opt.seed};
                    // Wavelengths first, from a 2-D sample: the pixel's n samples carry n·N wavelengths, one
                    // per 1/(n·N) of the CDF (theory §4.10).
                    SampledWavelengths wl = scene.Wavelengths().Sample(sampler.Get2D());
                    if (scratch.HasStokes()) {
                        scratch.AddStokesSample(lx, ly, EstimatePixelStokes(scene, x, y, wl, sampler, buffer, ps), wl);
                    } else {
                        SampledSpectrum L = EstimatePixel(scene, x, y, wl, sampler, buffer, ps);
                        scratch.AddSample(lx, ly, L, wl);
                    }
                    buffer.Reset();
                }
            }
        scratch.GetPixels(0, 0, tw, th, task.pixels.data());
        task.rays = ps.rays;
        task.counters = ps.counters;
    };
    // Every thread of this process takes tiles from `source` until it has none left.
    auto renderTiles = [&](TileSource &source) {
        const int workers = std::max(1, int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
        tbb::parallel_for(
            0, workers,
            [&](int) {
                Film scratch(TilePasses::TileSize, TilePasses::TileSize, film.Response());
                if (film.HasStokes()) scratch.EnableStokes();
                std::unique_ptr<Sampler> sampler = prototype->Clone();
                ScratchBuffer buffer;
                TileTask task;
                while (source.Next(task)) {
                    renderTile(task, scratch, *sampler, buffer);
                    source.Done(task);
                }
            },
            tbb::simple_partitioner());
    };

    RenderStats stats;
    if (opt.work && !opt.work->Coordinates()) {  // a helper process: its tiles, no image
        if (TileSource *tiles = opt.work->HelperTiles(film)) renderTiles(*tiles);
        stats.hasImage = false;
        stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return stats;
    }
    const int w = film.Width(), h = film.Height();
    if (opt.warn) {
        char estimate[32];
        std::snprintf(estimate, sizeof estimate, "%.4g", EstimateWork(scene, w, h, opt, *prototype));
        stats.metadata["phasor:work_estimate_seconds"] = estimate;  // (compared with the render's time)
    }
    TilePasses passes(film, opt.cancel);
    struct Serving {  // other processes and checkpoints see the passes while they run
        WorkShare *work;
        Serving(WorkShare *wk, TilePasses &p) : work(wk) {
            if (work) work->BeginTiles(p);
        }
        ~Serving() {
            if (work) work->EndTiles();
        }
    } serving(opt.work, passes);
    // Passes of 1, 2, 4, 8, then 16 samples per pixel. A film that already holds samples (a
    // resumed render) skips the passes its every pixel has.
    long long have = film.SampleCount(0, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) have = std::min(have, film.SampleCount(x, y));
    int done = 0;
    int batch = 1;
    while (done < opt.spp && !cancelled()) {
        const int end = std::min(opt.spp, done + batch);
        batch = std::min(batch * 2, 16);
        if (end > have) {
            passes.BeginPass(end);
            renderTiles(passes);
            passes.EndPass();
            if (cancelled()) break;  // the pass may be incomplete: `done` stays the count every pixel has
        }
        done = end;
        if (opt.progress && end > have) opt.progress(done, opt.spp);
    }
    stats.rays = passes.Rays();
    stats.counters = passes.Counters();
    stats.counters.ToMetadata(stats.metadata);
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
