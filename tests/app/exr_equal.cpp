// SPDX-License-Identifier: Apache-2.0
// Test helper for the distributed-render tests (mpi.sh, checkpoint.sh, sweep.sh): whether two EXRs
// hold the same image bit for bit — size, channel names in order, every value's bits.
//   exr_equal A.exr B.exr    exit 0 if equal; 1 with the first difference on stdout; 2 on error
#include <cstring>
#include <iostream>

#include "core/diagnostics.h"
#include "core/image/image_io.h"

int main(int argc, char **argv) {
    using namespace phasor;
    if (argc != 3) {
        std::cerr << "usage: exr_equal A.exr B.exr\n";
        return 2;
    }
    Image a, b;
    try {
        a = ReadImage(argv[1]);
        b = ReadImage(argv[2]);
    } catch (const Error &e) {
        std::cerr << e.Message() << "\n";
        return 2;
    }
    if (a.width != b.width || a.height != b.height) {
        std::cout << "sizes differ: " << a.width << "x" << a.height << " and " << b.width << "x" << b.height << "\n";
        return 1;
    }
    if (a.channels != b.channels) {
        std::cout << "channels differ:";
        for (const auto &c : a.channels) std::cout << " " << c;
        std::cout << " |";
        for (const auto &c : b.channels) std::cout << " " << c;
        std::cout << "\n";
        return 1;
    }
    const std::size_t nc = a.channels.size();
    for (std::size_t i = 0; i < a.data.size(); ++i)
        if (std::memcmp(&a.data[i], &b.data[i], sizeof(float)) != 0) {
            const std::size_t pixel = i / nc;
            std::cout << "pixel (" << pixel % std::size_t(a.width) << ", " << pixel / std::size_t(a.width) << ") channel "
                      << a.channels[i % nc] << ": " << a.data[i] << " and " << b.data[i] << "\n";
            return 1;
        }
    return 0;
}
