// SPDX-License-Identifier: Apache-2.0
// phasor — the processes of one run (docs/distributed.md). Without MPI, or when the program was not
// started by an MPI launcher (mpirun, srun), there is one process and everything here is trivial.
// Under MPI every rank runs the same command with the same arguments: each loads the scene, the
// render's work is shared (WorkShare: tiles handed out dynamically by rank 0, which renders too),
// and rank 0 alone talks to the user and writes the outputs; every rank ends with rank 0's status.
// The other ranks' standard output and error go to /dev/null (Start), so messages appear once.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/render/work.h"

namespace phasor::dist {

/// Starts MPI when the environment says an MPI launcher started the program (Open MPI's
/// OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK, PMI's PMI_RANK/PMI_SIZE; PHASOR_MPI=0 never, =1 always);
/// else one process. Call first thing in main. Returns false (with a message on stderr) when MPI
/// cannot give what phasor needs.
bool Start(int &argc, char **&argv);
/// Ends MPI (every rank must call it); harmless without.
void Finish();
/// Whether this build has MPI (PHASOR_MPI).
bool Available();

int Rank();
int Size();
inline bool Root() { return Rank() == 0; }
/// Ranks on this node (1 without MPI).
int RanksOnNode();
/// Threads each rank renders with when --threads is not given: the cores this rank may run on,
/// divided among the ranks of this node bound to the same cores (so ranks × threads never
/// oversubscribe a node); 0 (= all cores, TBB's default) with one process.
int DefaultThreads();

/// Rank 0's `status` on every rank (every rank calls it).
int Agree(int status);
/// Whether every rank's `ok` is true (every rank calls it). When not, and rank 0's is, rank 0 learns
/// the first failing rank's message in `failure` ("rank N: message").
bool AllOk(bool ok, const std::string &message, std::string *failure);
/// Rank 0's `text` on every rank.
void Broadcast(std::string &text);

/// A WorkShare spreading one render over every rank (rank 0 coordinates; core/render/work.h);
/// null with one process. Its Stop() flag is set when `cancel` is set on any rank (a signal, a
/// time budget on rank 0), and the render must poll it (RenderOptions::cancel = Stop()).
class Share : public WorkShare {
  public:
    virtual const std::atomic<bool> *Stop() const = 0;
    /// The signal a rank stopped for (0 if none): rank 0 exits with 128 + it after a signal
    /// another rank received.
    virtual int Signal() const = 0;
    /// On rank 0: the units of work (tiles of a pass, rs's batches) each rank did, by rank.
    virtual std::vector<long long> WorkByRank() const = 0;
};
std::unique_ptr<Share> MakeShare(const std::atomic<bool> *cancel);

/// The largest image whose whole render (its film's accumulators, or compare's images and
/// snapshots) travels in one MPI message to rank 0 (MPI counts bytes in an int: < 2 GB); larger
/// renders of a sweep or compare share their tiles instead.
inline constexpr double MaxWholeRenderPixels = 4e6;

/// Whole units of work (a sweep's renders, compare's runs) spread over the ranks, handed out one at a
/// time by rank 0, which computes units too. `compute(u)` runs on the rank that takes unit u and
/// returns its result as bytes; `collect(u, bytes)` runs on rank 0, on the calling thread, for every
/// unit, in the order they finish (rank 0's own right after computing them, the others' between
/// its units and at the end). `stop`, when set on rank 0, hands out no further unit. Every rank
/// calls it. With one process: compute and collect each unit in order.
void ForEachUnit(int units, const std::function<std::string(int)> &compute,
                 const std::function<void(int, std::string &&)> &collect, const std::atomic<bool> *stop);

}  // namespace phasor::dist
