// SPDX-License-Identifier: Apache-2.0
// phasor — the processes of one run in a build without MPI (PHASOR_MPI=OFF): always one process
// (distributed.h), so every render keeps its work to itself.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "app/distributed.h"

namespace phasor::dist {

bool Available() { return false; }

bool Start(int &, char **&) {
    if (const char *force = std::getenv("PHASOR_MPI"); force && std::strcmp(force, "1") == 0) {
        std::fprintf(stderr, "error: PHASOR_MPI=1 but this phasor was built without MPI (-DPHASOR_MPI=OFF)\n");
        return false;
    }
    return true;
}
void Finish() {}
int Rank() { return 0; }
int Size() { return 1; }
int RanksOnNode() { return 1; }
int DefaultThreads() { return 0; }
int Agree(int status) { return status; }
bool AllOk(bool ok, const std::string &, std::string *) { return ok; }
void Broadcast(std::string &) {}
std::unique_ptr<Share> MakeShare(const std::atomic<bool> *) { return nullptr; }

void ForEachUnit(int units, const std::function<std::string(int)> &compute,
                 const std::function<void(int, std::string &&)> &collect, const std::atomic<bool> *stop) {
    for (int u = 0; u < units && !(stop && stop->load()); ++u) collect(u, compute(u));
}

}  // namespace phasor::dist
