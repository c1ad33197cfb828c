// SPDX-License-Identifier: Apache-2.0
// phasor — checkpoints of a sampling render (`render --checkpoint SECONDS`, `render --resume FILE`;
// docs/distributed.md "Checkpoints"): the film's accumulators (every pixel's running means, sum of
// squared deviations and sample count — which samples are done), the render's counters, the
// command that made it, and what determines the image (phasor's version, the scene's fingerprint,
// resolution, integrator, sampler, seed), so that a resumed render continues bit for bit and a
// checkpoint of another render is refused, naming what differs.
//
// File: "PHASORCK", u32 format (1), u32 header length, the header (UTF-8 "key=value" lines), u64
// pixel count, u32 bytes per pixel, the pixels (Film::PixelState, little-endian IEEE 754 as in
// memory), u64 checksum of every byte before it. Written to a temporary file and renamed over the
// previous checkpoint (core/image/output_file.h), so a crash while writing never harms it.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image/film.h"
#include "core/render/integrator.h"
#include "core/render/registry.h"

namespace phasor {

class Scene;

/// What must be equal for a checkpoint to continue a render, and the command that started it.
struct CheckpointRender {
    // Determines the image (compared on resume).
    std::string version;      // phasor's
    std::string fingerprint;  // SceneFingerprint (hex)
    int width = 0, height = 0;
    std::string integrator;  // Integrator::ToString()
    std::string sampler;
    uint64_t seed = 0;
    bool stokes = false;
    // The command (a resume without a scene on its command line repeats it).
    std::string scene;   // absolute path of the scene file
    std::string output;  // absolute path of the EXR
    std::vector<std::pair<std::string, std::string>> defines;
    std::string integratorName;  // --integrator ("" = the scene's)
    int spp = 0;                 // samples per pixel asked for
    double checkpointSeconds = 0;
};

struct Checkpoint {
    CheckpointRender render;
    std::vector<Film::PixelState> pixels;  // width × height, row-major
    long long rays = 0;
    RenderCounters counters;
    double seconds = 0;  // render time so far, over every run that continued it
};

/// The fingerprint of a resolved scene: every entity's keyword, type, name and parameters (values as
/// resolved: Defines and -D substituted, units in SI) and the contents of the files they name
/// (meshes, textures); the Render block's spp, seed, sampler and output are left out (compared on
/// their own, or free to change). 16 hex digits.
std::string SceneFingerprint(const SceneDesc &desc);

/// The checkpoint file of an output: OUT.ckpt beside OUT.exr.
std::string CheckpointPath(const std::string &exr);

/// Writes `c` to `path` all or nothing (temporary + rename). Throws phasor::Error. With the
/// environment variable PHASOR_TEST_CHECKPOINT_PAUSE=SECONDS (tests only) it says so on stderr and
/// sleeps that long between writing the temporary and renaming it over an existing checkpoint.
void WriteCheckpoint(const std::string &path, const Checkpoint &c);
/// Reads and checks a checkpoint: missing, truncated, corrupt (checksum) or not a checkpoint is a
/// phasor::Error saying which.
Checkpoint ReadCheckpoint(const std::string &path);
/// What differs between the render a checkpoint was made for and `now` ("" if nothing), e.g.
/// "its seed is 0, this render's is 3".
std::string CheckpointMismatch(const CheckpointRender &file, const CheckpointRender &now);

}  // namespace phasor
