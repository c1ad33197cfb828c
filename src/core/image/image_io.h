// SPDX-License-Identifier: Apache-2.0
// phasor — image I/O (OpenImageIO for every read/write) and display transforms (OpenColorIO).
// OIIO and OCIO headers stay inside image_io.cpp / color.cpp.
#pragma once

#include <cstddef>
#include <string>

#include "core/image/film.h"
#include "core/image/output_file.h"

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

/// The false-colour PNGs' colour map (viridis, 8-bit) at t ∈ [0, 1] (clamped) as a display-referred
/// sRGB colour in [0, 1] — e.g. for WriteImageWithColourBarPng (core/image/plot.h).
Vec3 ViridisDisplay(double t);

/// Writes a one-channel false-colour PNG (dB scale over `rangeDb` below the max, viridis-like
/// colour map) — for sensor-plane images.
void WriteFalseColorPng(const std::string &path, const Image &img, const std::string &channel,
                        double rangeDb = 40);
void WriteFalseColorPng(OutputFiles &files, const std::string &path, const Image &img,
                        const std::string &channel, double rangeDb = 40);

}  // namespace phasor
