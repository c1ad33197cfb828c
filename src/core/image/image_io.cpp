// SPDX-License-Identifier: Apache-2.0
// phasor — image files through OpenImageIO (image_io.h): float EXR with named channels and
// string metadata, 8-bit PNG through the OCIO display transform (color.cpp), false-colour dB
// PNGs. Every write goes to a temporary file in the target directory and is renamed into place.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "core/diagnostics.h"
#include "core/image/color.h"
#include "core/image/oiio_write.h"
#include "core/image_io.h"
#include "core/plot.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void WriteError(const std::string &path, const std::string &reason) {
    throw Error(FileLoc{path}, "cannot write '" + path + "': " + reason);
}

std::string Trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s.empty() ? std::string("unknown OpenImageIO error") : s;
}

void CheckShape(const std::string &path, const Image &img) {
    if (img.width <= 0 || img.height <= 0)
        WriteError(path, "the image is empty (" + std::to_string(img.width) + "x" +
                             std::to_string(img.height) + ")");
    if (img.channels.empty()) WriteError(path, "the image has no channels");
    const std::size_t expected = std::size_t(img.width) * img.height * img.channels.size();
    if (img.data.size() != expected)
        WriteError(path, "the image is " + std::to_string(img.width) + "x" +
                             std::to_string(img.height) + " with " +
                             std::to_string(img.channels.size()) + " channels but holds " +
                             std::to_string(img.data.size()) + " values");
}

// Display-referred [0,1] value → 8-bit code, round to nearest.
uint8_t Quantize8(float v) {
    if (!(v > 0)) return 0;  // also NaN
    if (v >= 1) return 255;
    return uint8_t(std::lround(double(v) * 255.0));
}

// Viridis (van der Walt & Smith 2015, matplotlib's default colour map): the published sRGB colours
// at t = 0, 1/9, …, 1; interpolated linearly in between.
constexpr uint8_t Viridis[10][3] = {
    {0x44, 0x01, 0x54}, {0x48, 0x28, 0x78}, {0x3E, 0x4A, 0x89}, {0x31, 0x68, 0x8E},
    {0x26, 0x82, 0x8E}, {0x1F, 0x9E, 0x89}, {0x35, 0xB7, 0x79}, {0x6D, 0xCD, 0x59},
    {0xB4, 0xDE, 0x2C}, {0xFD, 0xE7, 0x25}};

void ViridisColor(double t, uint8_t rgb[3]) {
    t = Clamp(t, 0, 1) * 9;
    int i = std::min(int(t), 8);
    double f = t - i;
    for (int c = 0; c < 3; ++c)
        rgb[c] = uint8_t(std::lround(Lerp(f, Viridis[i][c], Viridis[i + 1][c])));
}
Vec3 ViridisDisplay(double t) {  // the same colour in [0, 1] (the colour bar)
    uint8_t c[3];
    ViridisColor(t, c);
    return Vec3(c[0], c[1], c[2]) / 255.0;
}

}  // namespace

namespace detail {

void WriteAtomically(const std::string &path, const char *format, const OIIO::ImageSpec &spec,
                     OIIO::TypeDesc type, const void *pixels) {
    const fs::path target(path);
    fs::path dir = target.parent_path();
    if (target.filename().empty()) WriteError(path, "the path names a directory, not a file");
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec))
        WriteError(path, "directory '" + dir.string() + "' does not exist");

    // A name unique within this process and across processes: pid + counter.
    static std::atomic<unsigned long> counter{0};
    std::string tmpName(".");
    tmpName += target.filename().string();
    tmpName += ".tmp-";
    tmpName += std::to_string(getpid());
    tmpName += '-';
    tmpName += std::to_string(counter++);
    const fs::path tmp = dir / tmpName;
    auto fail = [&](const std::string &reason) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        WriteError(path, reason);
    };

    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format);
    if (!out) WriteError(path, "no OpenImageIO writer for " + std::string(format) + ": " +
                                   Trimmed(OIIO::geterror()));
    if (!out->open(tmp.string(), spec)) {
        std::string reason = Trimmed(out->geterror());
        out.reset();
        fail(reason);
    }
    if (!out->write_image(type, pixels)) {
        std::string reason = Trimmed(out->geterror());
        out->close();
        out.reset();
        fail(reason);
    }
    if (!out->close()) {
        std::string reason = Trimmed(out->geterror());
        out.reset();
        fail(reason);
    }
    out.reset();
    fs::rename(tmp, target, ec);
    if (ec) fail(ec.message());
}

}  // namespace detail

void WriteExr(const std::string &path, const Image &img) {
    CheckShape(path, img);
    OIIO::ImageSpec spec(img.width, img.height, int(img.channels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = img.channels;
    spec.alpha_channel = img.ChannelIndex("A");
    spec.z_channel = img.ChannelIndex("Z");
    for (const auto &[key, value] : img.metadata) spec.attribute(key, value);
    spec.attribute("compression", "zip");  // lossless
    detail::WriteAtomically(path, "exr", spec, OIIO::TypeDesc::FLOAT, img.data.data());
}

Image ReadImage(const std::string &path) {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    if (!in) throw Error(FileLoc{path}, "cannot read '" + path + "': " + Trimmed(OIIO::geterror()));
    const OIIO::ImageSpec &spec = in->spec();
    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels.assign(spec.channelnames.begin(), spec.channelnames.end());
    for (int c = int(img.channels.size()); c < spec.nchannels; ++c)
        img.channels.push_back("channel" + std::to_string(c));
    img.data.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.data.data()))
        throw Error(FileLoc{path}, "cannot read '" + path + "': " + Trimmed(in->geterror()));
    for (const OIIO::ParamValue &p : spec.extra_attribs)
        img.metadata[p.name().string()] = p.get_string(1 << 20);
    in->close();
    return img;
}

void WritePng(const std::string &path, const Image &img, const DisplayOptions &opt) {
    CheckShape(path, img);
    int r = img.ChannelIndex("R"), g = img.ChannelIndex("G"), b = img.ChannelIndex("B");
    if (r < 0 || g < 0 || b < 0) {
        // A monochrome image: show its intensity (or Y) as grey.
        int mono = img.ChannelIndex("intensity");
        if (mono < 0) mono = img.ChannelIndex("Y");
        if (mono < 0)
            WriteError(path, "the image has no R, G, B (or intensity) channels to display");
        r = g = b = mono;
    }
    const std::size_t numPixels = std::size_t(img.width) * img.height;
    const std::size_t nc = img.channels.size();
    std::vector<float> rgb(3 * numPixels);
    for (std::size_t i = 0; i < numPixels; ++i) {
        rgb[3 * i + 0] = img.data[i * nc + r];
        rgb[3 * i + 1] = img.data[i * nc + g];
        rgb[3 * i + 2] = img.data[i * nc + b];
    }
    try {
        detail::ApplyDisplayTransformInPlace(rgb.data(), numPixels, opt);
    } catch (const Error &e) {
        WriteError(path, e.Message());
    }
    // Clamp to the display range and quantise to 8 bits.
    std::vector<uint8_t> bytes(rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i) bytes[i] = Quantize8(rgb[i]);
    OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    detail::WriteAtomically(path, "png", spec, OIIO::TypeDesc::UINT8, bytes.data());
}

void WriteFalseColorPng(const std::string &path, const Image &img, const std::string &channel,
                        double rangeDb) {
    CheckShape(path, img);
    const int c = img.ChannelIndex(channel);
    if (c < 0) WriteError(path, "the image has no channel '" + channel + "'");
    if (!(rangeDb > 0) || !std::isfinite(rangeDb))
        WriteError(path, "the dB range must be positive, got " + std::to_string(rangeDb));
    const std::size_t numPixels = std::size_t(img.width) * img.height;
    const std::size_t nc = img.channels.size();
    double maxValue = 0;
    for (std::size_t i = 0; i < numPixels; ++i) {
        double v = img.data[i * nc + c];
        if (std::isfinite(v)) maxValue = std::max(maxValue, v);
    }
    std::vector<uint8_t> bytes(3 * numPixels);
    for (std::size_t i = 0; i < numPixels; ++i) {
        double v = img.data[i * nc + c];
        // The channel is a power-like quantity (intensity, irradiance): level = 10·log10(v/max) dB,
        // mapped linearly from −rangeDb (t = 0) to 0 dB (t = 1). Non-positive values get t = 0.
        double t = 0;
        if (maxValue > 0 && v > 0 && std::isfinite(v))
            t = 1 + 10 * std::log10(v / maxValue) / rangeDb;
        else if (v == Infinity)
            t = 1;
        ViridisColor(t, &bytes[3 * i]);
    }
    // The colour bar: 0 dB (the maximum) at the top down to −rangeDb, labelled every 10 dB (5 dB
    // below a 20 dB range), its title naming the channel and the value that 0 dB stands for.
    std::vector<ColourBarTick> ticks;
    const double step = rangeDb >= 20 ? 10 : 5;
    for (double db = 0; db <= rangeDb * (1 + 1e-9); db += step) {
        char label[32];
        std::snprintf(label, sizeof label, "%g dB", db > 0 ? -db : 0.0);  // "0 dB", not "-0 dB"
        ticks.push_back(ColourBarTick{1 - db / rangeDb, label});
    }
    char title[96];
    std::snprintf(title, sizeof title, "%s, 0 dB = %.4g", channel.c_str(), maxValue);
    WriteImageWithColourBarPng(path, bytes, img.width, img.height, ViridisDisplay, ticks, title,
                               channel + " in dB, " + std::to_string(rangeDb) + " dB range, 0 dB = " +
                                   std::to_string(maxValue));
}

}  // namespace phasor
