// SPDX-License-Identifier: Apache-2.0
// phasor — command-line parsing (kept apart from main.cpp so it can be unit-tested).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace phasor {

enum class Command { Help, Version, Render, Check, Format, List, Describe };

struct CliOptions {
    Command command = Command::Help;
    std::string scene, output, integrator, sampler, family, name;
    int spp = -1, threads = 0;
    long long seed = -1;
    bool quiet = false, strict = false, markdown = false;
    std::vector<std::pair<std::string, std::string>> defines;  // -D name=value, in order
};

/// Fills `o` from argv; on a usage error returns false with a message in `err`.
bool ParseCommandLine(int argc, char **argv, CliOptions &o, std::string &err);

}  // namespace phasor
