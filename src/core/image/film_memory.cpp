// SPDX-License-Identifier: Apache-2.0
// phasor — how much memory a render needs and how much is available (film.h), so that a huge
// resolution is refused with the numbers before anything is allocated.
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "core/image/film.h"

namespace phasor {

double Film::MemoryNeeded(int width, int height) {
    // Per pixel: the film's accumulator; the resolved image (R G B intensity variance, float)
    // and the writers' copy of it; the PNG's float RGB and its 8-bit pixels; and an integrator's
    // per-pixel buffers (rs keeps channels, intensity and flux as doubles).
    const double perPixel = double(sizeof(Pixel)) + 2 * 5 * sizeof(float) + 3 * sizeof(float) + 4 +
                            (3 + 1 + 1) * sizeof(double);
    return perPixel * double(width) * double(height);
}

double AvailableMemory() {
    double avail = -1;
    std::ifstream in("/proc/meminfo");
    for (std::string line; std::getline(in, line);) {
        std::istringstream ls(line);
        std::string key;
        double kb;
        if (ls >> key >> kb && key == "MemAvailable:") avail = kb * 1024;
    }
    if (avail < 0) {
        const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
        avail = pages > 0 && page > 0 ? double(pages) * double(page) : 1e300;
    }
    if (const char *cap = std::getenv("PHASOR_MEMORY_LIMIT")) {
        char *end = nullptr;
        double v = std::strtod(cap, &end);
        if (end && (*end == 'K' || *end == 'k')) v *= 1024;
        else if (end && (*end == 'M' || *end == 'm')) v *= 1024.0 * 1024;
        else if (end && (*end == 'G' || *end == 'g')) v *= 1024.0 * 1024 * 1024;
        if (v > 0 && v < avail) avail = v;
    }
    return avail;
}

}  // namespace phasor
