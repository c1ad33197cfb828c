// SPDX-License-Identifier: Apache-2.0
// phasor — all-or-nothing output files (output_file.h): checked write(2), fsync(2), close(2), then
// rename(2) into place.

#include "core/image/output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/diagnostics.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void Fail(const std::string &path, const std::string &reason) {
    throw Error(FileLoc{path}, "cannot write '" + path + "': " + reason);
}

// Writes all of `bytes` to `fd`, retrying short writes and EINTR. Returns 0 or the errno.
int WriteAll(int fd, std::string_view bytes) {
    const char *p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        if (n == 0) return EIO;  // no progress and no error: treat as an I/O error
        p += n;
        left -= std::size_t(n);
    }
    return 0;
}

}  // namespace

OutputFiles::~OutputFiles() { Discard(); }

void OutputFiles::Discard() {
    for (const Pending &p : pending_) ::unlink(p.temp.c_str());
    pending_.clear();
}

void OutputFiles::Stage(const std::string &path, std::string_view bytes) {
    const fs::path target(path);
    if (target.filename().empty() || target.filename() == "." || target.filename() == "..") {
        Discard();
        Fail(path, "the path names a directory, not a file");
    }
    const fs::path dir = target.parent_path();
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec)) {
        Discard();
        Fail(path, "directory '" + dir.string() + "' does not exist");
    }
    if (fs::is_directory(target, ec)) {
        Discard();
        Fail(path, "it is a directory");
    }

    // A name unique within this process and across processes: pid + counter. O_EXCL never
    // follows or reuses an existing file.
    static std::atomic<unsigned long> counter{0};
    const fs::path temp = dir / ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                                 std::to_string(counter++));
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
        const int err = errno;
        Discard();
        Fail(path, std::strerror(err));
    }
    int err = WriteAll(fd, bytes);
    if (!err && ::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) err = errno;  // EINVAL: no fsync here (pipes)
    if (::close(fd) != 0 && !err && errno != EINTR) err = errno;
    if (err) {
        ::unlink(temp.c_str());
        Discard();
        Fail(path, std::strerror(err));
    }
    pending_.push_back({path, temp.string()});
}

void OutputFiles::Commit() {
    for (std::size_t i = 0; i < pending_.size(); ++i) {
        if (::rename(pending_[i].temp.c_str(), pending_[i].target.c_str()) == 0) continue;
        const int err = errno;
        const std::string target = pending_[i].target;
        for (std::size_t k = 0; k < i; ++k) ::unlink(pending_[k].target.c_str());  // no partial set
        pending_.erase(pending_.begin(), pending_.begin() + std::ptrdiff_t(i));
        Discard();
        Fail(target, std::strerror(err));
    }
    pending_.clear();
}

void WriteFileAtomically(const std::string &path, std::string_view bytes) {
    OutputFiles files;
    files.Stage(path, bytes);
    files.Commit();
}

void MakeParentDirectory(const std::string &path) {
    const fs::path p(path);
    std::error_code ec;
    if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);
    if (ec) Fail(path, "cannot create directory '" + p.parent_path().string() + "': " + ec.message());
}

}  // namespace phasor
