// SPDX-License-Identifier: Apache-2.0
// Test helper for tests/app/profile.sh: writes a small EXR like a sensor render (channels R G B
// intensity variance) whose chosen row holds the given values.
//   write_test_exr OUT.exr WIDTH HEIGHT [--row R] [--meta KEY=VALUE]... V0 V1 … V(WIDTH-1)
// Row R (default HEIGHT/2) gets the values in every channel but variance (0); every other row y
// gets 1000 + y, so reading the wrong row shows.
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/image/image_io.h"

int main(int argc, char **argv) {
    using namespace phasor;
    if (argc < 4) {
        std::cerr << "usage: write_test_exr OUT.exr WIDTH HEIGHT [--row R] [--meta K=V]... VALUES...\n";
        return 2;
    }
    Image img;
    img.width = std::atoi(argv[2]);
    img.height = std::atoi(argv[3]);
    img.channels = {"R", "G", "B", "intensity", "variance"};
    int row = img.height / 2;
    std::vector<float> values;
    for (int i = 4; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--row" && i + 1 < argc) {
            row = std::atoi(argv[++i]);
        } else if (a == "--meta" && i + 1 < argc) {
            std::string kv = argv[++i];
            auto eq = kv.find('=');
            img.metadata[kv.substr(0, eq)] = kv.substr(eq + 1);
        } else {
            values.push_back(std::strtof(a.c_str(), nullptr));
        }
    }
    if (int(values.size()) != img.width || row < 0 || row >= img.height) {
        std::cerr << "write_test_exr: need WIDTH values and a row inside the image\n";
        return 2;
    }
    img.data.assign(std::size_t(img.width) * img.height * img.channels.size(), 0.0f);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 4; ++c) img.At(x, y, c) = y == row ? values[x] : float(1000 + y);
    try {
        WriteExr(argv[1], img);
    } catch (const Error &e) {
        std::cerr << "write_test_exr: " << e.Message() << "\n";
        return 1;
    }
    return 0;
}
