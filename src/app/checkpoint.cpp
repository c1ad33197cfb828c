// SPDX-License-Identifier: Apache-2.0
// phasor — checkpoints of a sampling render (checkpoint.h).
#include "app/checkpoint.h"

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "core/hash.h"
#include "core/image/output_file.h"
#include "core/render/sampler.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;

constexpr char Magic[8] = {'P', 'H', 'A', 'S', 'O', 'R', 'C', 'K'};
constexpr uint32_t Format = 1;

// A 64-bit hash of a byte stream, eight bytes at a time through the splitmix64 finaliser: not
// cryptographic, but any corruption changes it with probability 1 − 2⁻⁶⁴.
std::string Hex(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
    return buf;
}

void HashValue(ContentHasher &h, const Value &v) {
    h.AddValue(uint8_t(v.kind));
    switch (v.kind) {
        case Value::Kind::Number:
            h.AddValue(v.number);
            h.AddValue(v.dim);
            break;
        case Value::Kind::Bool: h.AddValue(uint8_t(v.boolean)); break;
        case Value::Kind::Complex:
            h.AddValue(v.complex.real());
            h.AddValue(v.complex.imag());
            break;
        case Value::Kind::String:
        case Value::Kind::Ref: h.AddString(v.text); break;
        case Value::Kind::List:
        case Value::Kind::Call:
            h.AddString(v.text);
            h.AddValue(uint64_t(v.items.size()));
            for (std::size_t i = 0; i < v.items.size(); ++i) {
                h.AddString(i < v.argNames.size() ? v.argNames[i] : "");
                HashValue(h, v.items[i]);
            }
            break;
    }
}

// The contents of a file a parameter names (a mesh, a texture), resolved as BuildContext does.
void HashFile(ContentHasher &h, const SceneDesc &desc, const Param &p) {
    fs::path path(p.value.text);
    if (path.is_relative()) {
        const std::string base = p.loc.file.empty() ? desc.sourceFile : p.loc.file;
        if (!base.empty()) path = fs::path(base).parent_path() / path;
    }
    h.AddFile(path.string());  // an unreadable file adds nothing (the scene's load reports it)
}

// Header lines "key=value"; values are single-line.
std::string HeaderLine(const std::string &key, const std::string &value) { return key + "=" + value + "\n"; }

std::string Number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

[[noreturn]] void Bad(const std::string &path, const std::string &why) {
    throw Error("checkpoint '" + path + "': " + why);
}

}  // namespace

std::string SceneFingerprint(const SceneDesc &desc) {
    ContentHasher h;
    for (const SceneEntity &e : desc.entities) {
        h.AddString(e.keyword);
        h.AddString(e.type);
        h.AddString(e.name);
        const Schema *schema = e.keyword == "Render" ? nullptr : FindSchema(e.keyword, e.type);
        for (const Param &p : e.params.All()) {
            if (e.keyword == "Render" && (p.name == "spp" || p.name == "seed" || p.name == "sampler" || p.name == "output"))
                continue;
            h.AddString(p.name);
            HashValue(h, p.value);
            const ParamSpec *spec = schema ? schema->Find(p.name) : nullptr;
            if (spec && spec->kind == ParamKind::File && p.value.kind == Value::Kind::String) HashFile(h, desc, p);
        }
    }
    return Hex(h.Digest());
}

std::string CheckpointPath(const std::string &exr) {
    fs::path p(exr);
    p.replace_extension(".ckpt");
    return p.string();
}

void WriteCheckpoint(const std::string &path, const Checkpoint &c) {
    const CheckpointRender &r = c.render;
    std::string header;
    header += HeaderLine("phasor_version", r.version);
    header += HeaderLine("scene_fingerprint", r.fingerprint);
    header += HeaderLine("width", std::to_string(r.width));
    header += HeaderLine("height", std::to_string(r.height));
    header += HeaderLine("integrator", r.integrator);
    header += HeaderLine("sampler", r.sampler);
    header += HeaderLine("seed", std::to_string(r.seed));
    header += HeaderLine("stokes", r.stokes ? "true" : "false");
    header += HeaderLine("scene", r.scene);
    header += HeaderLine("output", r.output);
    for (const auto &[name, value] : r.defines) header += HeaderLine("define", name + "=" + value);
    header += HeaderLine("integrator_name", r.integratorName);
    header += HeaderLine("spp", std::to_string(r.spp));
    header += HeaderLine("checkpoint_seconds", Number(r.checkpointSeconds));
    header += HeaderLine("rays", std::to_string(c.rays));
    for (std::size_t i = 0; i < c.counters.n.size(); ++i)
        header += HeaderLine(std::string("count:") + Describe(RenderEvent(i)).key, std::to_string(c.counters.n[i]));
    header += HeaderLine("seconds", Number(c.seconds));

    std::string bytes(Magic, sizeof Magic);
    auto put = [&](const auto &v) { bytes.append(reinterpret_cast<const char *>(&v), sizeof v); };
    put(Format);
    put(uint32_t(header.size()));
    bytes += header;
    put(uint64_t(c.pixels.size()));
    put(uint32_t(sizeof(Film::PixelState)));
    bytes.append(reinterpret_cast<const char *>(c.pixels.data()), c.pixels.size() * sizeof(Film::PixelState));
    ContentHasher h;
    h.Add(bytes.data(), bytes.size());
    put(h.Digest());

    OutputFiles files;
    files.Stage(path, bytes);
    if (const char *pause = std::getenv("PHASOR_TEST_CHECKPOINT_PAUSE"); pause && fs::exists(path)) {
        std::cerr << "checkpoint: paused before replacing '" << path << "' (PHASOR_TEST_CHECKPOINT_PAUSE)" << std::endl;
        std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(pause)));
    }
    files.Commit();
}

Checkpoint ReadCheckpoint(const std::string &path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) Bad(path, fs::exists(path, ec) ? "not a regular file" : "no such file");
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.eof() && in.fail()) Bad(path, "cannot be read");
    if (bytes.size() < sizeof Magic || std::memcmp(bytes.data(), Magic, sizeof Magic) != 0)
        Bad(path, "not a phasor checkpoint (it does not start with PHASORCK)");
    std::size_t at = sizeof Magic;
    auto get = [&](auto &v) {
        if (bytes.size() - at < sizeof v)
            Bad(path, "truncated (" + std::to_string(bytes.size()) + " bytes): it was not written to the end");
        std::memcpy(&v, bytes.data() + at, sizeof v);
        at += sizeof v;
    };
    uint32_t format = 0, headerSize = 0, pixelBytes = 0;
    uint64_t pixels = 0, stored = 0;
    get(format);
    if (format != Format)
        Bad(path, "format " + std::to_string(format) + ", but this phasor reads format " + std::to_string(Format));
    get(headerSize);
    if (bytes.size() - at < headerSize) Bad(path, "truncated (" + std::to_string(bytes.size()) + " bytes): it was not written to the end");
    const std::string header = bytes.substr(at, headerSize);
    at += headerSize;
    get(pixels);
    get(pixelBytes);
    if (pixelBytes != sizeof(Film::PixelState))
        Bad(path, "corrupt (pixels of " + std::to_string(pixelBytes) + " bytes; this phasor's are " +
                      std::to_string(sizeof(Film::PixelState)) + ")");
    const uint64_t expected = at + pixels * pixelBytes + sizeof(uint64_t);
    if (pixels > (uint64_t(1) << 40) || bytes.size() != expected)
        Bad(path, bytes.size() < expected ? "truncated (" + std::to_string(bytes.size()) + " of " +
                                                std::to_string(expected) + " bytes): it was not written to the end"
                                          : "corrupt (" + std::to_string(bytes.size() - expected) +
                                                " bytes more than its header says)");
    ContentHasher h;
    h.Add(bytes.data(), bytes.size() - sizeof(uint64_t));
    std::memcpy(&stored, bytes.data() + bytes.size() - sizeof stored, sizeof stored);
    if (h.Digest() != stored) Bad(path, "corrupt (its checksum does not match its contents)");

    Checkpoint c;
    CheckpointRender &r = c.render;
    std::map<std::string, std::string> keys;
    std::istringstream lines(header);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t eq = line.find('=');
        if (eq == std::string::npos) continue;
        const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
        if (key == "define") {
            const std::size_t e2 = value.find('=');
            r.defines.emplace_back(value.substr(0, e2), e2 == std::string::npos ? "" : value.substr(e2 + 1));
        } else {
            keys[key] = value;
        }
    }
    auto need = [&](const char *key) -> const std::string & {
        auto it = keys.find(key);
        if (it == keys.end()) Bad(path, std::string("corrupt (no '") + key + "' in its header)");
        return it->second;
    };
    auto integer = [&](const char *key) {
        const std::string &v = need(key);
        char *end = nullptr;
        const long long n = std::strtoll(v.c_str(), &end, 10);
        if (v.empty() || *end) Bad(path, std::string("corrupt ('") + key + "' is '" + v + "')");
        return n;
    };
    r.version = need("phasor_version");
    r.fingerprint = need("scene_fingerprint");
    r.width = int(integer("width"));
    r.height = int(integer("height"));
    r.integrator = need("integrator");
    r.sampler = need("sampler");
    r.seed = uint64_t(integer("seed"));
    r.stokes = need("stokes") == "true";
    r.scene = need("scene");
    r.output = need("output");
    r.integratorName = need("integrator_name");
    r.spp = int(integer("spp"));
    r.checkpointSeconds = std::atof(need("checkpoint_seconds").c_str());
    c.rays = integer("rays");
    for (std::size_t i = 0; i < c.counters.n.size(); ++i) {
        const std::string key = std::string("count:") + Describe(RenderEvent(i)).key;
        if (keys.count(key)) c.counters.n[i] = integer(key.c_str());
    }
    c.seconds = std::atof(need("seconds").c_str());
    if (uint64_t(r.width) * uint64_t(r.height) != pixels || r.width <= 0 || r.height <= 0)
        Bad(path, "corrupt (" + std::to_string(pixels) + " pixels for " + std::to_string(r.width) + "x" +
                      std::to_string(r.height) + ")");
    c.pixels.resize(pixels);
    std::memcpy(c.pixels.data(), bytes.data() + at, pixels * pixelBytes);
    return c;
}

std::string CheckpointMismatch(const CheckpointRender &file, const CheckpointRender &now) {
    auto differ = [](const std::string &what, const std::string &a, const std::string &b) {
        return "its " + what + " is " + a + ", this render's is " + b;
    };
    if (file.version != now.version) return differ("phasor version", file.version, now.version);
    if (file.width != now.width || file.height != now.height)
        return differ("resolution", std::to_string(file.width) + "x" + std::to_string(file.height),
                      std::to_string(now.width) + "x" + std::to_string(now.height));
    if (file.integrator != now.integrator) return differ("integrator", file.integrator, now.integrator);
    if (file.sampler != now.sampler) return differ("sampler", file.sampler, now.sampler);
    if (file.seed != now.seed) return differ("seed", std::to_string(file.seed), std::to_string(now.seed));
    if (file.stokes != now.stokes)
        return differ("Stokes output", file.stokes ? "on" : "off", now.stokes ? "on" : "off");
    if (file.fingerprint != now.fingerprint)
        return "it was made from another scene: the scene's resolved content (Defines and -D values included, "
               "and the files it reads) differs from '" + file.scene + "' as it was then";
    return "";
}

}  // namespace phasor
