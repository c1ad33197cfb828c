// SPDX-License-Identifier: Apache-2.0
// phasor — image I/O (OpenImageIO for every read/write) and display transforms (OpenColorIO).
// OIIO and OCIO headers stay inside image_io.cpp / color.cpp.
#pragma once

#include <string>

#include "core/image/film.h"
#include "core/image/output_file.h"
#include "core/image/sheet.h"

namespace phasor {

// Every writer below encodes in memory and writes through OutputFiles (core/image/output_file.h): a
// temporary file in the target's directory, every write/fsync/close checked, then renamed; a
// failed write leaves nothing behind and throws phasor::Error ("cannot write 'PATH': reason").
// The form taking `OutputFiles &` only stages the file: it appears when files.Commit() renames
// the whole set (e.g. a render's EXR and PNG, all or nothing).

/// Writes all channels of `img` (float) and its metadata to an EXR file.
void WriteExr(const std::string &path, const Image &img);
void WriteExr(OutputFiles &files, const std::string &path, const Image &img);
/// Reads any image OIIO can read into float channels (EXR channel names kept; others R,G,B,A).
Image ReadImage(const std::string &path);

/// Display-referred 8-bit RGB through an OpenColorIO display/view transform.
struct DisplayOptions {
    std::string display = "sRGB";
    std::string view = "Standard";
    double exposure = 0;  // stops, applied in scene-linear before the transform
};
/// The display transform of the R,G,B channels of `img` (scene-linear Rec.709; a monochrome
/// image's intensity or Y as grey) as 8-bit sRGB. Throws phasor::Error (no FileLoc).
Rgb8Image ToDisplay(const Image &img, const DisplayOptions &opt = {});
/// Applies the display transform to the R,G,B channels of `img` (scene-linear Rec.709) and writes
/// an 8-bit PNG through OIIO. Uses $OCIO if set, else the config shipped with phasor.
void WritePng(const std::string &path, const Image &img, const DisplayOptions &opt = {});
void WritePng(OutputFiles &files, const std::string &path, const Image &img, const DisplayOptions &opt = {});
/// The display transform on one linear RGB triple (for tests): returns display-referred values.
Vec3 ApplyDisplayTransform(const Vec3 &linearRgb, const DisplayOptions &opt = {});
/// Name of the OCIO config in use ("$OCIO: <path>" or "built-in").
std::string ColorConfigDescription();

/// One channel's values, as double (throws phasor::Error when there is no such channel).
std::vector<double> ChannelValues(const Image &img, const std::string &channel);
/// The largest finite value (0 if none is positive).
double FiniteMax(const std::vector<double> &values);

/// The false colour of sensor images: one power-like channel (intensity, irradiance) in dB
/// against `zeroDb` (≤ 0: the channel's largest finite value), `rangeDb` shown, through viridis
/// (sheet.h DecibelLevels); `bar`, when given, receives the matching colour bar, its title naming
/// the channel and the value of 0 dB. Throws phasor::Error (no FileLoc).
Rgb8Image ToFalseColourDb(const Image &img, const std::string &channel, double rangeDb = 40, double zeroDb = 0,
                          ColourBar *bar = nullptr);
/// Writes ToFalseColourDb with its colour bar to the right (sheet.h StageSheetPng) — the PNG of
/// radiometric detectors. A missing font is not an error: the result says so (no text drawn).
SheetResult WriteFalseColorPng(const std::string &path, const Image &img, const std::string &channel,
                               double rangeDb = 40, double zeroDb = 0);
SheetResult WriteFalseColorPng(OutputFiles &files, const std::string &path, const Image &img,
                               const std::string &channel, double rangeDb = 40, double zeroDb = 0);

}  // namespace phasor
