// SPDX-License-Identifier: Apache-2.0
// phasor — every file the program writes (EXR, PNG, CSV, plots) goes through here: all-or-nothing
// output through temporary files in the target's directory and rename(2). Implemented in the image
// module (src/core/image/output_file.cpp); no third-party types.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace phasor {

/// A set of output files written together, all or nothing.
///
/// Stage() writes a file's bytes to a temporary file beside the target (".NAME.tmp-PID-N" in the
/// same directory, so that the rename cannot cross file systems), checking every write(2) — a full
/// disk (ENOSPC) or a file-size limit (EFBIG, RLIMIT_FSIZE) is an error — and then fsync(2) and
/// close(2), which report delayed write errors. Commit() renames every staged file into place.
/// If a Stage() fails, or the set is destroyed without Commit(), every temporary is removed and
/// no target is touched (files of those names from an earlier run stay as they were). If a
/// rename fails inside Commit() (rare: the directory became unwritable), the targets already
/// renamed by this Commit() are removed too, so no run leaves only part of its outputs.
///
/// Errors are phasor::Error with FileLoc{path} and the message "cannot write 'PATH': reason".
/// The target's directory must exist (callers create it).
class OutputFiles {
  public:
    OutputFiles() = default;
    OutputFiles(const OutputFiles &) = delete;
    OutputFiles &operator=(const OutputFiles &) = delete;
    ~OutputFiles();

    /// Writes `bytes` to a new temporary file for `path`. On failure the temporary is removed,
    /// every other staged temporary too, and the set is empty.
    void Stage(const std::string &path, std::string_view bytes);
    /// Renames every staged file into place (in staging order); the set is then empty.
    void Commit();
    /// Removes every staged temporary (also done by the destructor).
    void Discard();

  private:
    struct Pending {
        std::string target, temp;
    };
    std::vector<Pending> pending_;
};

/// Writes one file all or nothing: OutputFiles::Stage + Commit.
void WriteFileAtomically(const std::string &path, std::string_view bytes);

/// Creates the directory `path` is to be written in (and its parents) if missing; throws
/// phasor::Error("cannot write 'PATH': cannot create directory …") on failure.
void MakeParentDirectory(const std::string &path);

}  // namespace phasor
