// SPDX-License-Identifier: Apache-2.0
// phasor — command-line parsing (kept apart from main.cpp so it can be unit-tested).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace phasor {

enum class Command { Help, Version, Render, Check, Format, List, Describe, Profile, Probe, Compare };

struct CliOptions {
    Command command = Command::Help;
    std::string scene, output, integrator, sampler, family, name;
    int spp = -1, threads = 0;
    long long seed = -1;
    bool quiet = false, markdown = false;
    bool strict = false;      // --strict: every warning is an error
    bool permissive = false;  // --permissive: unknown parameters and unused -D are warnings
    std::vector<std::pair<std::string, std::string>> defines;  // -D name=value, in order

    // `profile`: one image row (or column) of each input as CSV and/or a line plot.
    struct ProfileOptions {
        std::vector<std::string> inputs;  // EXR files
        int row = -1;                     // -1: each image's middle row
        int column = -1;                  // ≥ 0: this column instead of a row
        std::string channel = "intensity";
        std::string csv, plot;            // output paths ("" = not written; csv "-" = stdout)
        std::vector<std::string> labels;  // one per input, or empty
        bool hasX0 = false, hasPitch = false;
        double x0 = 0, pitch = 0;         // metres: x of pixel 0's centre, pixel pitch
        double diffScale = 1;             // |a − b| is drawn magnified by this factor
        std::string title;
    } profile;

    // `probe`: one kernel of a scene at one incidence and wavelength (app/probe.h). Quantities are
    // kept as written ("550nm", "30deg") and parsed with the scene language's units by the command.
    struct ProbeOptions {
        std::string material;            // the material's scene name (with or without '@')
        std::string theta, phi, lambda;  // quantity texts; phi "" = 0
        bool hasUv = false;
        double u = 0.5, v = 0.5;         // texture context (--uv)
        long long samples = 100000;      // Monte-Carlo samples for the continuous lobes
        bool rayOptics = false;          // --ray: ScatterQuery::rayOptics
        std::string csv, plot;           // output paths ("" = not written; csv "-" = stdout)
    } probe;

    // `compare`: render a scene with several integrators and compare them (app/compare.h); the
    // output directory is `output`, spp/seed/threads/sampler/defines as for `render`.
    struct CompareOptions {
        std::vector<std::string> integrators;  // --integrators a,b,c (in order, distinct)
        double seconds = 0;                    // --time: the budget of each integrator (0: equal spp)
        std::string reference;                 // --reference FILE.exr
        std::string referenceIntegrator;       // --reference-integrator NAME
        int referenceSpp = 0;                  // --reference-spp N (0: the scene's spp)
        int row = -1, column = -1;             // --row / --column: a profile plot
    } compare;

    // `render` at scale (docs/distributed.md): parameter sweeps, checkpoints and resume.
    struct RunOptions {
        /// --sweep NAME=v1,v2,…: one render per value (per combination when repeated), in order.
        std::vector<std::pair<std::string, std::vector<std::string>>> sweeps;
        double checkpoint = 0;  // --checkpoint SECONDS: OUT.ckpt every SECONDS (0: none)
        std::string resume;     // --resume FILE.ckpt: continue that render
    } run;
};

/// Fills `o` from argv; on a usage error returns false with a message in `err`.
bool ParseCommandLine(int argc, char **argv, CliOptions &o, std::string &err);

}  // namespace phasor
