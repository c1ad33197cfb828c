// SPDX-License-Identifier: Apache-2.0
// phasor — how a render's work is shared out among threads and processes (docs/distributed.md).
// The render loops take their work from here instead of walking the image themselves:
//  * a sampling render (PixelIntegrator) runs in passes, each bringing every pixel to a sample
//    count, tile by tile. TilePasses hands a pass's tiles to this process's threads (and, through a
//    WorkShare, to other processes) with the tiles' accumulators, and takes them back with the new
//    ones: it is the only place where the film changes during a render, so it can copy a consistent
//    film at any moment (a checkpoint) while the render runs;
//  * a deterministic integrator (`rs`) computes independent batches of values (its field nodes).
// Each pixel's samples are a pure function of (pixel, sample index, seed) and are added to its
// accumulator in index order, whoever renders them, so the image does not depend on who rendered
// which tile. Without a WorkShare (RenderOptions::work) everything runs in this process; the program
// supplies one for MPI and for checkpoints (app/distributed.h).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

#include "core/image/film.h"
#include "core/render/integrator.h"

namespace phasor {

/// One unit of a sampling render: the pixels [x0, x1) × [y0, y1) brought to `sampleEnd` samples
/// each, every pixel from its own count (a pixel that already has them is left alone).
struct TileTask {
    int tile = -1;  // index in the film's tile order (row-major tiles of TilePasses::TileSize)
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int sampleEnd = 0;
    /// The rectangle's accumulators, row-major: as handed out, and as rendered once done.
    std::vector<Film::PixelState> pixels;
    /// Filled by whoever renders the tile: rays traced and render-time events counted.
    long long rays = 0;
    RenderCounters counters;
};

/// Hands out tiles to the threads of this process and takes them back. Thread-safe.
class TileSource {
  public:
    virtual ~TileSource() = default;
    /// The next tile for this process; false when there is none left for it (the pass's tiles are
    /// all handed out, the render is stopping, or — on a helper process — the render is over).
    virtual bool Next(TileTask &task) = 0;
    /// A tile rendered (or stopped part-way: each pixel's count says how far it got).
    virtual void Done(TileTask &task) = 0;
};

/// The tiles of the film on the process that holds it (the only process without MPI): passes over
/// every tile, the film's accumulators moved in and out of tiles under one lock. Thread-safe.
class TilePasses final : public TileSource {
  public:
    static constexpr int TileSize = 16;
    /// `cancel` (may be null): when set, Next hands out nothing more.
    TilePasses(Film &film, const std::atomic<bool> *cancel);

    int Tiles() const { return tilesX_ * tilesY_; }
    const Film &GetFilm() const { return film_; }
    /// Starts a pass: every pixel is to reach `sampleEnd` samples.
    void BeginPass(int sampleEnd);
    /// Hands out the pass's next tile that has work left (a tile whose pixels all have
    /// `sampleEnd` samples is skipped).
    bool Next(TileTask &task) override;
    void Done(TileTask &task) override;
    /// Waits until every tile handed out in this pass is back (from any process).
    void EndPass();

    /// A consistent copy of the film's accumulators (every pixel, row-major) with the rays and
    /// events of the tiles taken back so far. Safe while a pass runs: tiles out for rendering are
    /// copied as they were handed out.
    void Snapshot(std::vector<Film::PixelState> &pixels, long long *rays, RenderCounters *counters) const;
    /// Tiles taken back so far (over every pass).
    long long TilesDone() const;
    /// Rays traced and events counted by every tile taken back.
    long long Rays() const;
    RenderCounters Counters() const;

  private:
    Film &film_;
    const std::atomic<bool> *cancel_;
    int tilesX_, tilesY_;
    int next_;  // the next tile of the pass to look at
    mutable std::mutex mutex_;
    std::condition_variable returned_;
    int sampleEnd_ = 0, out_ = 0;
    long long done_ = 0, rays_ = 0;
    RenderCounters counters_;
};

/// Fills values[begin, end) of a deterministic integrator's batch (may use threads).
using BatchFunction = std::function<void(std::size_t begin, std::size_t end)>;

/// Where a render's work goes beyond this process's threads (RenderOptions::work): other processes
/// (MPI), and a periodic copy of the film (checkpoints). The render loops call it; the default
/// of every member is "this process alone".
class WorkShare {
  public:
    virtual ~WorkShare() = default;
    /// False on a process that only helps (an MPI rank other than 0): its render loop renders the
    /// tiles HelperTiles hands it and returns without an image (RenderStats::hasImage false).
    virtual bool Coordinates() const { return true; }
    /// On the coordinating process, around the passes of a sampling render: from BeginTiles to
    /// EndTiles, `passes` may be served to other processes and copied (Snapshot).
    virtual void BeginTiles(TilePasses &passes) { (void)passes; }
    virtual void EndTiles() {}
    /// On a helper process: where its tiles come from (the render's film gives their size).
    virtual TileSource *HelperTiles(Film &film) {
        (void)film;
        return nullptr;
    }
    /// Deterministic work: values[i] for every i, in `units` batches of consecutive indices (batch u
    /// is [n·u/units, n·(u+1)/units) for n = values.size()), each computed by `compute`. `done(k)`
    /// is called on the coordinating process, from the calling thread, after k batches (returning
    /// false stops); `cancel`, when set, stops it too. Returns true when every value is in place on
    /// the coordinating process; false when stopped, and on helper processes (whose `values` then
    /// hold only their own batches).
    virtual bool Batches(std::vector<double> &values, int units, const BatchFunction &compute,
                         const std::function<bool(int)> &done, const std::atomic<bool> *cancel);
};

/// Batch u of n values in `units` batches: [n·u/units, n·(u+1)/units).
inline std::size_t BatchBegin(std::size_t n, int units, int u) { return n * std::size_t(u) / std::size_t(units); }

/// WorkShare::Batches in this process alone: the batches in order.
bool RunBatchesLocally(std::vector<double> &values, int units, const BatchFunction &compute,
                       const std::function<bool(int)> &done, const std::atomic<bool> *cancel);

}  // namespace phasor
