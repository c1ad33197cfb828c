// SPDX-License-Identifier: Apache-2.0
// phasor — image files through OpenImageIO (image_io.h): float EXR with named channels and
// string metadata, 8-bit PNG through the OCIO display transform (color.cpp), false-colour dB
// PNGs. Images are encoded in memory and written through OutputFiles (core/image/output_file.h):
// checked writes to a temporary file in the target directory, renamed into place.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/diagnostics.h"
#include "core/image/color.h"
#include "core/image/oiio_write.h"
#include "core/image/image_io.h"
#include "core/image/sheet.h"

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

}  // namespace

namespace detail {

void StageImage(OutputFiles &files, const std::string &path, const char *format, const OIIO::ImageSpec &spec,
                OIIO::TypeDesc type, const void *pixels) {
    // Encode in memory (OIIO's writers do not all report a failed write(2), e.g. libpng's PNG
    // writer on a full disk); OutputFiles then checks every write, fsync and close.
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format);
    if (!out) WriteError(path, "no OpenImageIO writer for " + std::string(format) + ": " +
                                   Trimmed(OIIO::geterror()));
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    const std::string name = fs::path(path).filename().string();  // the extension picks nothing: `format` did
    if (!out->set_ioproxy(&memory) || !out->open(name, spec)) WriteError(path, Trimmed(out->geterror()));
    if (!out->write_image(type, pixels)) {
        const std::string reason = Trimmed(out->geterror());
        out->close();
        WriteError(path, reason);
    }
    if (!out->close()) WriteError(path, Trimmed(out->geterror()));
    out.reset();
    files.Stage(path, std::string_view(reinterpret_cast<const char *>(bytes.data()), bytes.size()));
}

}  // namespace detail

void WriteExr(OutputFiles &files, const std::string &path, const Image &img) {
    CheckShape(path, img);
    OIIO::ImageSpec spec(img.width, img.height, int(img.channels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = img.channels;
    spec.alpha_channel = img.ChannelIndex("A");
    spec.z_channel = img.ChannelIndex("Z");
    for (const auto &[key, value] : img.metadata) spec.attribute(key, value);
    spec.attribute("compression", "zip");  // lossless
    detail::StageImage(files, path, "exr", spec, OIIO::TypeDesc::FLOAT, img.data.data());
}

void WriteExr(const std::string &path, const Image &img) {
    OutputFiles files;
    WriteExr(files, path, img);
    files.Commit();
}

namespace {

// libpng prints its errors and warnings straight to stderr ("libpng error: IDAT: …"), and OIIO
// then reports the same error again. While OIIO reads, stderr (file descriptor 2) is redirected
// to a temporary file: on failure its text is dropped (OIIO's error carries it), on success it
// is passed on unchanged, so every message appears once. Reads happen while nothing else prints.
class StderrCapture {
  public:
    StderrCapture() {
        std::fflush(stderr);
        file_ = std::tmpfile();
        if (file_) saved_ = ::dup(2);
        if (saved_ >= 0 && ::dup2(::fileno(file_), 2) < 0) {
            ::close(saved_);
            saved_ = -1;
        }
    }
    ~StderrCapture() { Finish(true); }
    /// Restores stderr; writes what was captured to it when `passOn`.
    void Finish(bool passOn) {
        if (saved_ >= 0) {
            std::fflush(stderr);
            ::dup2(saved_, 2);
            ::close(saved_);
            saved_ = -1;
            if (passOn) {
                std::rewind(file_);
                char buf[4096];
                for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;)
                    std::fwrite(buf, 1, n, stderr);
            }
        }
        if (file_) std::fclose(file_);
        file_ = nullptr;
    }

  private:
    std::FILE *file_ = nullptr;
    int saved_ = -1;
};

// OIIO's error text for a failed read, first line only: the rest repeats libpng's message.
std::string ReadErrorReason(std::string text) {
    text = Trimmed(std::move(text));
    return text.substr(0, text.find('\n'));
}

}  // namespace

Image ReadImage(const std::string &path, std::string *pixelFormat) {
    StderrCapture libpngMessages;
    auto fail = [&](const std::string &oiioError) {
        libpngMessages.Finish(false);
        throw Error(FileLoc{path}, "cannot read '" + path + "': " + ReadErrorReason(oiioError));
    };
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    if (!in) fail(OIIO::geterror());
    const OIIO::ImageSpec &spec = in->spec();
    if (pixelFormat) *pixelFormat = spec.format.c_str();
    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels.assign(spec.channelnames.begin(), spec.channelnames.end());
    for (int c = int(img.channels.size()); c < spec.nchannels; ++c)
        img.channels.push_back("channel" + std::to_string(c));
    img.data.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.data.data())) fail(in->geterror());
    for (const OIIO::ParamValue &p : spec.extra_attribs)
        img.metadata[p.name().string()] = p.get_string(1 << 20);
    in->close();
    return img;
}

Rgb8Image ToDisplay(const Image &img, const DisplayOptions &opt) {
    if (img.width <= 0 || img.height <= 0 || img.channels.empty() ||
        img.data.size() != std::size_t(img.width) * img.height * img.channels.size())
        throw Error("the image is empty or its size is inconsistent");
    int r = img.ChannelIndex("R"), g = img.ChannelIndex("G"), b = img.ChannelIndex("B");
    if (r < 0 || g < 0 || b < 0) {
        // A monochrome image: show its intensity (or Y) as grey.
        int mono = img.ChannelIndex("intensity");
        if (mono < 0) mono = img.ChannelIndex("Y");
        if (mono < 0) throw Error("the image has no R, G, B (or intensity) channels to display");
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
    detail::ApplyDisplayTransformInPlace(rgb.data(), numPixels, opt);
    // Clamp to the display range and quantise to 8 bits.
    Rgb8Image out;
    out.width = img.width;
    out.height = img.height;
    out.rgb.resize(rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i) out.rgb[i] = Quantize8(rgb[i]);
    return out;
}

double AutoExposureStops(const Image &img) {
    int c = img.ChannelIndex("intensity");
    if (c < 0) c = img.ChannelIndex("Y");
    if (c < 0 || img.width <= 0 || img.height <= 0) return 0;
    const std::size_t n = std::size_t(img.width) * img.height, nc = img.channels.size();
    std::vector<double> y;
    y.reserve(n);
    double logSum = 0;
    std::size_t lit = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double v = img.data[i * nc + c];
        if (!std::isfinite(v)) continue;
        y.push_back(std::max(v, 0.0));
        if (v > 0) {
            logSum += std::log(v);
            ++lit;
        }
    }
    if (lit == 0) return 0;
    double scale = 0.18 / std::exp(logSum / double(lit));
    const std::size_t at = std::min(y.size() - 1, std::size_t(std::floor(0.95 * double(y.size() - 1))));
    std::nth_element(y.begin(), y.begin() + std::ptrdiff_t(at), y.end());
    if (y[at] > 0) scale = std::min(scale, 1 / y[at]);
    return std::isfinite(scale) && scale > 0 ? std::log2(scale) : 0;
}

void WritePng(OutputFiles &files, const std::string &path, const Image &img, const DisplayOptions &opt) {
    CheckShape(path, img);
    Rgb8Image display;
    try {
        display = ToDisplay(img, opt);
    } catch (const Error &e) {
        WriteError(path, e.Message());
    }
    OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    detail::StageImage(files, path, "png", spec, OIIO::TypeDesc::UINT8, display.rgb.data());
}

void WritePng(const std::string &path, const Image &img, const DisplayOptions &opt) {
    OutputFiles files;
    WritePng(files, path, img, opt);
    files.Commit();
}

std::vector<double> ChannelValues(const Image &img, const std::string &channel) {
    const int c = img.ChannelIndex(channel);
    if (c < 0) throw Error("the image has no channel '" + channel + "'");
    const std::size_t numPixels = std::size_t(img.width) * img.height, nc = img.channels.size();
    std::vector<double> v(numPixels);
    for (std::size_t i = 0; i < numPixels; ++i) v[i] = img.data[i * nc + c];
    return v;
}

double FiniteMax(const std::vector<double> &values) {
    double m = 0;
    for (double v : values)
        if (std::isfinite(v)) m = std::max(m, v);
    return m;
}

Rgb8Image ToFalseColourDb(const Image &img, const std::string &channel, double rangeDb, double zeroDb,
                          ColourBar *bar) {
    if (!(rangeDb > 0) || !std::isfinite(rangeDb))
        throw Error("the dB range must be positive, got " + std::to_string(rangeDb));
    const std::vector<double> v = ChannelValues(img, channel);
    if (!(zeroDb > 0)) zeroDb = FiniteMax(v);
    if (bar) {
        char title[96];
        std::snprintf(title, sizeof title, "%s, 0 dB = %.4g", channel.c_str(), zeroDb);
        *bar = DecibelBar(rangeDb, title);
    }
    return MapColours(DecibelLevels(v, zeroDb, rangeDb), img.width, img.height, ColourMap::Viridis, -rangeDb, 0);
}

SheetResult WriteFalseColorPng(OutputFiles &files, const std::string &path, const Image &img,
                               const std::string &channel, double rangeDb, double zeroDb) {
    CheckShape(path, img);
    ColourBar bar;
    Rgb8Image map;
    try {
        map = ToFalseColourDb(img, channel, rangeDb, zeroDb, &bar);
    } catch (const Error &e) {
        WriteError(path, e.Message());
    }
    return StageSheetPng(files, path, {SheetTile{std::move(map), ""}}, &bar,
                         channel + " in dB, " + std::to_string(rangeDb) + " dB range, " + bar.title);
}

SheetResult StageDegreeOfPolarizationPng(OutputFiles &files, const std::string &path, const Image &img) {
    CheckShape(path, img);
    Rgb8Image map;
    try {
        map = MapColours(ChannelValues(img, "DoP"), img.width, img.height, ColourMap::Viridis, 0, 1);
    } catch (const Error &e) {
        WriteError(path, e.Message());
    }
    ColourBar bar;
    bar.map = ColourMap::Viridis;
    bar.title = "degree of polarisation";
    for (int i = 0; i <= 4; ++i) {
        char label[16];
        std::snprintf(label, sizeof label, "%g", i / 4.0);
        bar.ticks.push_back({i / 4.0, label});
    }
    return StageSheetPng(files, path, {SheetTile{std::move(map), ""}}, &bar, "degree of polarisation (0 to 1)");
}

SheetResult WriteFalseColorPng(const std::string &path, const Image &img, const std::string &channel,
                               double rangeDb, double zeroDb) {
    OutputFiles files;
    SheetResult r = WriteFalseColorPng(files, path, img, channel, rangeDb, zeroDb);
    files.Commit();
    return r;
}

}  // namespace phasor
