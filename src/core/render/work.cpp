// SPDX-License-Identifier: Apache-2.0
// phasor — the tiles of a sampling render and the batches of a deterministic one (work.h).
#include "core/render/work.h"

#include <algorithm>

namespace phasor {

TilePasses::TilePasses(Film &film, const std::atomic<bool> *cancel)
    : film_(film),
      cancel_(cancel),
      tilesX_((film.Width() + TileSize - 1) / TileSize),
      tilesY_((film.Height() + TileSize - 1) / TileSize),
      next_(tilesX_ * tilesY_) {}  // nothing is handed out before the first pass

void TilePasses::BeginPass(int sampleEnd) {
    std::lock_guard<std::mutex> lock(mutex_);
    sampleEnd_ = sampleEnd;
    next_ = 0;
}

bool TilePasses::Next(TileTask &task) {
    std::lock_guard<std::mutex> lock(mutex_);
    while (next_ < Tiles()) {
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) return false;
        const int t = next_++;
        task.tile = t;
        task.x0 = (t % tilesX_) * TileSize;
        task.y0 = (t / tilesX_) * TileSize;
        task.x1 = std::min(task.x0 + TileSize, film_.Width());
        task.y1 = std::min(task.y0 + TileSize, film_.Height());
        task.sampleEnd = sampleEnd_;
        task.rays = 0;
        task.counters = RenderCounters{};
        task.pixels.resize(std::size_t(task.x1 - task.x0) * std::size_t(task.y1 - task.y0));
        film_.GetPixels(task.x0, task.y0, task.x1, task.y1, task.pixels.data());
        // A tile whose pixels all have the pass's samples (a resumed render) is not handed out.
        if (std::all_of(task.pixels.begin(), task.pixels.end(),
                        [&](const Film::PixelState &p) { return p.n >= sampleEnd_; }))
            continue;
        ++out_;
        return true;
    }
    return false;
}

void TilePasses::Done(TileTask &task) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        film_.SetPixels(task.x0, task.y0, task.x1, task.y1, task.pixels.data());
        rays_ += task.rays;
        counters_ += task.counters;
        --out_;
        ++done_;
    }
    returned_.notify_all();
}

void TilePasses::EndPass() {
    std::unique_lock<std::mutex> lock(mutex_);
    returned_.wait(lock, [&] { return out_ == 0; });
}

void TilePasses::Snapshot(std::vector<Film::PixelState> &pixels, long long *rays, RenderCounters *counters) const {
    std::lock_guard<std::mutex> lock(mutex_);
    pixels.resize(std::size_t(film_.Width()) * std::size_t(film_.Height()));
    film_.GetPixels(0, 0, film_.Width(), film_.Height(), pixels.data());
    if (rays) *rays = rays_;
    if (counters) *counters = counters_;
}

long long TilePasses::TilesDone() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return done_;
}

long long TilePasses::Rays() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return rays_;
}

RenderCounters TilePasses::Counters() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counters_;
}

bool RunBatchesLocally(std::vector<double> &values, int units, const BatchFunction &compute,
                       const std::function<bool(int)> &done, const std::atomic<bool> *cancel) {
    const std::size_t n = values.size();
    for (int u = 0; u < units; ++u) {
        compute(BatchBegin(n, units, u), BatchBegin(n, units, u + 1));
        if ((cancel && cancel->load(std::memory_order_relaxed)) || (done && !done(u + 1))) return false;
    }
    return true;
}

bool WorkShare::Batches(std::vector<double> &values, int units, const BatchFunction &compute,
                        const std::function<bool(int)> &done, const std::atomic<bool> *cancel) {
    return RunBatchesLocally(values, units, compute, done, cancel);
}

}  // namespace phasor
