// SPDX-License-Identifier: Apache-2.0
// phasor — plots through matplotlib (plot.h): runs python/phasor_plot.py with posix_spawn, its
// data in private temporary files, its output at the staged temporary path of OutputFiles.

#include "app/plot.h"
#include "app/text.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "core/diagnostics.h"
#include "core/image/output_file.h"

extern char **environ;

namespace phasor {
namespace {

namespace fs = std::filesystem;

// The exit status with which phasor_plot.py says that matplotlib or numpy is missing.
constexpr int MissingLibrary = 3;

// A private temporary file holding `text`, removed with the object.
class TempData {
  public:
    explicit TempData(const std::string &text) {
        std::error_code ec;
        fs::path dir = fs::temp_directory_path(ec);
        if (ec) dir = "/tmp";
        std::string name = (dir / "phasor-plot-XXXXXX.csv").string();
        const int fd = ::mkstemps(name.data(), 4);
        if (fd < 0) throw Error("cannot create a temporary file in '" + dir.string() + "': " + std::strerror(errno));
        path_ = name;
        const char *p = text.data();
        std::size_t left = text.size();
        while (left > 0) {
            const ssize_t n = ::write(fd, p, left);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                const int err = n < 0 ? errno : EIO;
                ::close(fd);
                throw Error("cannot write the temporary file '" + path_ + "': " + std::strerror(err));
            }
            p += n;
            left -= std::size_t(n);
        }
        ::close(fd);
    }
    ~TempData() {
        if (!path_.empty()) ::unlink(path_.c_str());
    }
    TempData(const TempData &) = delete;
    TempData &operator=(const TempData &) = delete;
    const std::string &Path() const { return path_; }

  private:
    std::string path_;
};

struct RunResult {
    bool started = false;  // false: the interpreter could not be executed
    int status = -1;       // exit status, or -1 when killed by a signal
    int signal = 0;
    std::string output;  // stdout and stderr together
};

// Runs argv[0] (looked up in PATH when it has no '/') with stdin from /dev/null and stdout +
// stderr collected, in its own process group; waits for it.
RunResult Run(const std::vector<std::string> &args) {
    RunResult r;
    int pipeFds[2];
    if (::pipe2(pipeFds, O_CLOEXEC) != 0) throw Error(std::string("cannot create a pipe: ") + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, pipeFds[1], 1);
    posix_spawn_file_actions_adddup2(&actions, pipeFds[1], 2);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    std::vector<char *> argv;
    for (const std::string &a : args) argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int err = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    ::close(pipeFds[1]);
    if (err != 0) {
        ::close(pipeFds[0]);
        r.output = std::strerror(err);
        return r;
    }
    r.started = true;
    char buf[4096];
    for (;;) {
        const ssize_t n = ::read(pipeFds[0], buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        if (r.output.size() < (1u << 20)) r.output.append(buf, std::size_t(n));
    }
    ::close(pipeFds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status))
        r.status = WEXITSTATUS(status);
    else if (WIFSIGNALED(status))
        r.signal = WTERMSIG(status);
    return r;
}

// The last non-empty line of `text`, without a leading "error: ".
std::string LastLine(const std::string &text) {
    std::size_t end = text.find_last_not_of("\n\r ");
    if (end == std::string::npos) return "";
    std::size_t begin = text.rfind('\n', end);
    std::string line =
        text.substr(begin == std::string::npos ? 0 : begin + 1, end + 1 - (begin == std::string::npos ? 0 : begin + 1));
    if (line.rfind("error: ", 0) == 0) line = line.substr(7);
    return line;
}

std::mutex gMutex;
// Per module: the interpreter that runs it, looked for once per value of $PHASOR_PYTHON.
struct ModuleState {
    std::string key;                         // $PHASOR_PYTHON when the interpreter was looked for
    std::optional<std::string> interpreter;  // the one that works; "" when none does
    std::string missing;                     // why none works
};
std::map<std::string, ModuleState> gModules;

std::string PythonVariable() {
    const char *p = std::getenv("PHASOR_PYTHON");
    return p ? p : "";
}

std::vector<std::string> Candidates() {
    if (const std::string p = PythonVariable(); !p.empty()) return {p};
    return {"python3", "/usr/bin/python3"};
}

// The library a module needs and the Debian package that has it.
std::pair<std::string, std::string> Needs(const std::string &module) {
    if (module == "phasor_report.py") return {"jinja2", "python3-jinja2"};
    return {"matplotlib", "python3-matplotlib"};
}

// The module's file: share/phasor/<module> beside the directory of the phasor executable
// ($PHASOR_PLOT_MODULE overrides the plot module; $PHASOR_MODULE_DIR the directory of every module:
// the Python package ships its own copies, as its executable is the Python interpreter).
std::string ModulePath(const std::string &module) {
    std::error_code ec;
    fs::path path;
    if (const char *p = std::getenv("PHASOR_PLOT_MODULE"); p && *p && module == "phasor_plot.py") {
        path = p;
    } else if (const char *d = std::getenv("PHASOR_MODULE_DIR"); d && *d) {
        path = fs::path(d) / module;
    } else {
        const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
        if (ec) return "";
        path = exe.parent_path().parent_path() / "share" / "phasor" / module;
    }
    return fs::is_regular_file(path, ec) ? path.string() : "";
}

}  // namespace

std::string PlotModulePath() { return ModulePath("phasor_plot.py"); }

std::string ModuleMissing(const std::string &module) {
    std::lock_guard<std::mutex> lock(gMutex);
    const auto [library, package] = Needs(module);
    const auto it = gModules.find(module);
    const std::string why = it == gModules.end() || it->second.missing.empty() ? library + " is not available"
                                                                                : it->second.missing;
    return why + " (install it with: apt-get install " + package + ")";
}

std::string MatplotlibMissing() { return ModuleMissing("phasor_plot.py"); }

bool StagePlot(OutputFiles &files, const std::string &path, const PlotRequest &request) {
    std::lock_guard<std::mutex> lock(gMutex);
    ModuleState &state = gModules[request.module];
    if (PythonVariable() != state.key) {  // look again for another $PHASOR_PYTHON
        state.key = PythonVariable();
        state.interpreter.reset();
        state.missing.clear();
    }
    if (state.interpreter && state.interpreter->empty()) return false;  // known to be missing
    const std::string module = ModulePath(request.module);
    if (module.empty()) {
        // Not a missing optional library: the installation is broken.
        throw Error(FileLoc{path}, "cannot write '" + path + "': the module " + request.module +
                                       " is missing (expected in share/phasor/ beside the directory of the phasor "
                                       "program" +
                                       (request.module == "phasor_plot.py" ? "; $PHASOR_PLOT_MODULE overrides)" : ")"));
    }
    const std::string ext = fs::path(path).extension().string();
    const std::string format = ext == ".svg" ? "svg" : ext == ".pdf" ? "pdf" : ext == ".html" ? "html" : "png";

    auto fail = [&](const std::string &reason) -> Error {
        return Error(FileLoc{path}, "cannot write '" + path + "': " + reason);
    };
    std::optional<TempData> data;
    std::vector<std::unique_ptr<TempData>> extra;
    try {
        data.emplace(request.data);
        for (const auto &[option, text] : request.extraData) extra.push_back(std::make_unique<TempData>(text));
    } catch (const Error &e) {
        throw fail(e.Message());
    }

    return files.StageWritten(path, [&](const std::string &temp) {
        std::vector<std::string> candidates =
            state.interpreter ? std::vector<std::string>{*state.interpreter} : Candidates();
        std::string missing;
        for (const std::string &python : candidates) {
            std::vector<std::string> args = {python,       "-B",    module, request.command, "--data",
                                             data->Path(), "--out", temp,   "--format",      format};
            for (std::size_t k = 0; k < extra.size(); ++k) {
                args.push_back(request.extraData[k].first);
                args.push_back(extra[k]->Path());
            }
            args.insert(args.end(), request.args.begin(), request.args.end());
            const RunResult r = Run(args);
            if (!r.started || r.status == MissingLibrary) {
                missing += (missing.empty() ? "" : ", ") + python;
                continue;
            }
            state.interpreter = python;
            if (r.signal) throw fail("the module " + request.module + " was killed by signal " + std::to_string(r.signal));
            if (r.status != 0) {
                const std::string reason = LastLine(r.output);
                throw fail(reason.empty() ? "the module " + request.module + " failed (exit status " +
                                                std::to_string(r.status) + ")"
                                          : reason);
            }
            return true;
        }
        state.interpreter = "";
        state.missing = "no Python with " + Needs(request.module).first + " found (tried " + missing + ")";
        return false;
    });
}

std::string DiscMapCsv(const DiscMap &map) {
    if (map.n <= 0 || map.discs.empty()) throw Error("the map has no disc or no cells");
    bool named = false;
    for (const DiscMap::Disc &d : map.discs) {
        if (d.values.size() != std::size_t(map.n) * std::size_t(map.n))
            throw Error("disc '" + d.name + "' has " + std::to_string(d.values.size()) + " values for " +
                        std::to_string(map.n) + "x" + std::to_string(map.n) + " cells");
        named |= !d.name.empty();
        if (map.discs.size() > 1 && (d.name.empty() || &d != &*std::find_if(map.discs.begin(), map.discs.end(),
                                                                             [&](const DiscMap::Disc &x) {
                                                                                 return x.name == d.name;
                                                                             })))
            throw Error("discs of one map need distinct names; '" + d.name + "' is empty or repeated");
    }
    for (const DiscMap::Marker &m : map.markers)
        if (m.disc < 0 || m.disc >= int(map.discs.size()) || (m.symbol != 'o' && m.symbol != 'x'))
            throw Error("a marker names disc " + std::to_string(m.disc) + " of " + std::to_string(map.discs.size()) +
                        " or a symbol other than 'o' and 'x'");
    std::string csv = named ? "disc,u,v,value\n" : "u,v,value\n";
    for (const DiscMap::Disc &d : map.discs)
        for (int j = 0; j < map.n; ++j)
            for (int i = 0; i < map.n; ++i)
                csv += (named ? CsvField(d.name) + "," : std::string()) + FormatNumber(-1 + (i + 0.5) * 2.0 / map.n, 9) +
                       "," + FormatNumber(-1 + (j + 0.5) * 2.0 / map.n, 9) + "," +
                       FormatNumber(d.values[std::size_t(j) * map.n + i], 9) + "\n";
    return csv;
}

bool StageDiscMap(OutputFiles &files, const std::string &path, const DiscMap &map) {
    PlotRequest request;
    request.command = "disc-map";
    try {
        request.data = DiscMapCsv(map);
    } catch (const Error &e) {
        throw Error(FileLoc{path}, "cannot write '" + path + "': " + e.Message());
    }
    const bool named = request.data.rfind("disc,", 0) == 0;
    if (!map.markers.empty()) {
        std::string points = named ? "disc,u,v,label,marker,size\n" : "u,v,label,marker,size\n";
        for (const DiscMap::Marker &m : map.markers)
            points += (named ? CsvField(map.discs[m.disc].name) + "," : std::string()) + FormatNumber(m.u, 9) + "," +
                      FormatNumber(m.v, 9) + "," + CsvField(m.label) + "," + std::string(1, m.symbol) + "," +
                      FormatNumber(m.size, 4) + "\n";
        request.extraData.push_back({"--points", points});
    }
    request.args = {"--title", map.title, "--value-label", map.valueLabel, "--scale", map.scale, "--db-range",
                    FormatNumber(map.rangeDb, 9)};
    return StagePlot(files, path, request);
}

}  // namespace phasor
