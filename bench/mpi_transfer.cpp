// SPDX-License-Identifier: Apache-2.0
// What moving a film's accumulators costs in a distributed render (docs/distributed.md, "Scaling"):
// run under `mpirun -n N` (bench/mpi_scaling.sh does). No pixel is rendered; only the traffic is
// timed, on rank 0:
//   local  the passes of one process: every 16×16 tile copied out of the film and back (TilePasses)
//   tiles  rank 0 serves every tile of every pass to the other ranks, which give each back untouched
//          (what a distributed pass moves: the tile's accumulators out and back, 56 bytes a pixel
//          each way), keeping 18 tiles in hand as a rank of 16 threads does: time per pass per
//          megapixel, and tiles per second through rank 0's server (its capacity)
//   whole  every other rank sends whole films to rank 0 (a sweep's or compare's whole runs;
//          96 bytes a pixel): time per megapixel
//   mpi_transfer [--megapixels M] [--passes P]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include <tbb/global_control.h>

#include "app/distributed.h"
#include "core/image/film.h"
#include "core/render/work.h"

using namespace phasor;
using Clock = std::chrono::steady_clock;

namespace {

double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

int main(int argc, char **argv) {
    if (!dist::Start(argc, argv)) return 1;
    double megapixels = 1;
    int passes = 5;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--megapixels")) megapixels = std::atof(argv[i + 1]);
        if (!std::strcmp(argv[i], "--passes")) passes = std::atoi(argv[i + 1]);
    }
    const int width = 1000, height = std::max(1, int(megapixels * 1e6 / width + 0.5));
    const double mp = double(width) * height / 1e6;
    Film film(width, height, SensorResponse(SensorResponse::Kind::Radiometric));
    const bool root = dist::Root();

    if (root) {  // local: one process's passes
        TilePasses local(film, nullptr);
        const auto t0 = Clock::now();
        TileTask t;
        for (int p = 0; p < passes; ++p) {
            local.BeginPass(1);  // no pixel gets a sample, so every tile is handed out every pass
            while (local.Next(t)) local.Done(t);
            local.EndPass();
        }
        std::printf("| local: tiles copied out of the film and back, one thread | %.2f ms per pass per megapixel |\n",
                    Since(t0) / passes / mp * 1e3);
    }
    if (dist::Size() == 1) {
        std::printf("(run under mpirun -n 2 or more for the transfers between ranks)\n");
        dist::Finish();
        return 0;
    }

    // tiles: rank 0 serves, the others give every tile back untouched.
    {
        std::unique_ptr<dist::Share> share = dist::MakeShare(nullptr);
        if (root) {
            TilePasses served(film, nullptr);
            share->BeginTiles(served);
            const auto t0 = Clock::now();
            for (int p = 1; p <= passes; ++p) {
                served.BeginPass(1);
                while (served.TilesDone() < (long long)p * served.Tiles()) std::this_thread::sleep_for(std::chrono::microseconds(50));
                served.EndPass();
            }
            const double s = Since(t0);
            share->EndTiles();
            std::printf("| tiles: out to %d ranks and back (56 bytes a pixel each way) | %.2f ms per pass per megapixel "
                        "(%.0f tiles/s through rank 0) |\n",
                        dist::Size() - 1, s / passes / mp * 1e3, double(served.Tiles()) * passes / s);
        } else {
            // As a rank of 16 render threads would: 18 tiles in hand, so that the server's
            // throughput is measured, not the round trip.
            tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 16);
            TileSource *tiles = share->HelperTiles(film);
            TileTask t;
            while (tiles->Next(t)) tiles->Done(t);
        }
    }

    // whole: films of accumulators to rank 0, as a sweep's whole renders are.
    {
        std::string filmBytes(std::size_t(width) * height * sizeof(Film::PixelState), '\x01');
        long long remote = 0;
        const int units = 4 * (dist::Size() - 1);
        const auto t0 = Clock::now();
        dist::ForEachUnit(
            units, [&](int) { return root ? std::string("0|") : std::to_string(dist::Rank()) + "|" + filmBytes; },
            [&](int, std::string &&bytes) { remote += bytes.compare(0, 2, "0|") != 0; }, nullptr);
        if (root && remote > 0)
            std::printf("| whole: films sent to rank 0 (96 bytes a pixel) | %.2f ms per megapixel (%lld of %d films "
                        "from other ranks) |\n",
                        Since(t0) / double(remote) / mp * 1e3, remote, units);
    }
    dist::Finish();
    return 0;
}
