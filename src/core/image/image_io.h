// SPDX-License-Identifier: Apache-2.0
// phasor — image I/O (OpenImageIO for every read/write) and display transforms (OpenColorIO).
// OIIO and OCIO headers stay inside image_io.cpp / color.cpp.
#pragma once

#include <cstddef>
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
/// Reads any image OIIO can read into float channels (EXR channel names kept; others R,G,B,A, a
/// grey image Y). Integer pixels are normalised to [0, 1] and not decoded: an sRGB PNG's values are
/// its encoded values (see ConvertToSceneLinear); the file's colour space, if it names one, is in
/// metadata["oiio:ColorSpace"]. `pixelFormat`, if given, receives the file's pixel type as OIIO
/// names it ("uint8", "uint16", "half", "float" …). Throws phasor::Error ("cannot read 'PATH': …").
Image ReadImage(const std::string &path, std::string *pixelFormat = nullptr);

/// Display-referred 8-bit RGB through an OpenColorIO display/view transform.
struct DisplayOptions {
    std::string display = "sRGB";
    std::string view = "Standard";
    double exposure = 0;  // stops, applied in scene-linear before the transform
};
/// The display transform of the R,G,B channels of `img` (scene-linear Rec.709; a monochrome
/// image's intensity or Y as grey) as 8-bit sRGB. Throws phasor::Error (no FileLoc).
Rgb8Image ToDisplay(const Image &img, const DisplayOptions &opt = {});
/// The automatic exposure of a camera image [stops], from its `intensity` (or Y) channel: the
/// log-average of the lit pixels, exp(mean ln Y over Y > 0), brought to middle grey 0.18, and
/// lowered if needed so that at most the brightest 5 % of the pixels pass the display's white
/// (scale = min(0.18 / log-average, 1 / 95th percentile of Y): a lamp in view may clip, the
/// image may not); 0 for an image without a lit pixel. The display transform then shows 2^stops × the image (DisplayOptions::exposure).
double AutoExposureStops(const Image &img);
/// Applies the display transform to the R,G,B channels of `img` (scene-linear Rec.709) and writes
/// an 8-bit PNG through OIIO. Uses $OCIO if set, else the config shipped with phasor.
void WritePng(const std::string &path, const Image &img, const DisplayOptions &opt = {});
void WritePng(OutputFiles &files, const std::string &path, const Image &img, const DisplayOptions &opt = {});
/// The display transform on one linear RGB triple (for tests): returns display-referred values.
Vec3 ApplyDisplayTransform(const Vec3 &linearRgb, const DisplayOptions &opt = {});
/// Converts `numPixels` packed RGB float triples in place from the colour space `colorspace` of the
/// OpenColorIO config in use ($OCIO if set, else phasor's built-in one, whose colour spaces are
/// "sRGB" (IEC 61966-2-1 encoded), "linear" (linear Rec.709), "cie_xyz_d65" and "raw", with
/// their aliases) to the config's scene_linear role — phasor's linear Rec.709, the film's R,G,B.
/// A data colour space ("raw") leaves the values unchanged. Thread-safe. Throws phasor::Error for
/// an unknown colour space, listing the config's.
void ConvertToSceneLinear(float *rgb, std::size_t numPixels, const std::string &colorspace);

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

/// The degree of polarisation (channel `DoP`, in [0, 1]) through viridis on a linear scale with its
/// colour bar (0 at the bottom, 1 at the top): the PNG `phasor render` writes beside an image with
/// Stokes channels. A missing font is not an error (the result says so).
SheetResult StageDegreeOfPolarizationPng(OutputFiles &files, const std::string &path, const Image &img);

}  // namespace phasor
