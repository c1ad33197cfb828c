// SPDX-License-Identifier: Apache-2.0
// phasor — `bitmap` texture: an image file over the surface's uv, bilinearly interpolated.
//
// Any format OpenImageIO reads (PNG, JPEG, TIFF, OpenEXR, HDR …; core/image/image_io.h).
// Mapping: s = uscale·u + udelta, t = vscale·v + vdelta; the image covers [0, 1]² of (s, t) with
// t = 0 at its bottom row (image rows run top to bottom; pbrt-v4's convention), so the texel of
// column i and row j (row 0 at the top) of a W × H image has its centre at
// ((i + ½)/W, 1 − (j + ½)/H). A value is the bilinear interpolation of the four texels whose
// centres surround (s, t); texels outside the image follow `wrap` (OpenImageIO's names): repeat
// (periodic), clamp (the edge texels extend), mirror (every other copy reflected) or black (0).
// Point-sampled: no mip-mapping (a generalized ray's footprint is not used yet).
//
// Colour: on load the pixels' colour (R, G, B, or a grey image's Y as R = G = B) is converted to
// phasor's linear Rec.709 through OpenColorIO (ConvertToSceneLinear) from `colorspace`; "raw"
// leaves data (heights, thicknesses) as stored. "auto" (the default) decides by what reads the
// texture: a colour — a spectral texture, or a scalar one read where a spectrum is expected (a
// reflectance; Texture::AsColour) — is decoded from the file's own colour space if it names one
// (OIIO's oiio:ColorSpace: PNG and JPEG say sRGB, EXR linear), else sRGB for integer pixels and
// linear for half/float ones, the decoding pbrt-v4 and Mitsuba 3 apply to 8-bit images; data — a
// scalar texture read as a thickness, an angle or a weight — keeps the stored values (raw), so that
// a grey PNG's 128 is 0.502 of its scale, not 0.216. Integer pixels are normalised to [0, 1] first
// (8-bit 255 → 1).
//
// Two kinds, chosen by the parameters:
//   * spectral (an RGB image, no `channel`, `scale` or `offset`): a reflectance or albedo. The
//     linear RGB, which must lie in [0, 1], is interpolated and then uplifted to a spectrum by
//     Smits' method, as the `rgb` spectrum does (core/spectrum/rgb_uplift.h).
//   * scalar (a one-channel image, or `channel`, `scale` or `offset` given): offset + scale·c with
//     c the interpolated channel — R, G or B of the linear colour, Y its Rec.709 luminance
//     (0.2126 R + 0.7152 G + 0.0722 B; a grey image's own value), A or any other channel of the
//     file as stored. Its dimension is that of `scale` and `offset` (`scale = 400 nm` makes a
//     thickness map); a dimensionless one also serves where a spectrum is expected.
// Bounds (MinValue/MaxValue): scalar — exact, from the smallest and largest texel (bilinear
// weights are convex; 0 joins them under wrap = black); spectral — 0 and
// SmitsSpectrum::UpperBound of the largest linear component.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

#include "core/image/image_io.h"
#include "core/render/registry.h"
#include "core/render/texture.h"
#include "core/spectrum/rgb_uplift.h"
#include "textures/texture_common.h"

namespace phasor {

namespace {

enum class Wrap { Repeat, Clamp, Mirror, Black };

/// A W × H grid of texels with `stride` floats each (row 0 at the top), its uv mapping and wrap
/// mode: the bilinear look-up both texture kinds share.
class TexelGrid {
  public:
    struct Mapping {
        double uscale = 1, vscale = 1, udelta = 0, vdelta = 0;
        Wrap wrap = Wrap::Repeat;
    };
    TexelGrid(int width, int height, int stride, std::vector<float> texels, const Mapping &m)
        : w_(width), h_(height), stride_(stride), texels_(std::move(texels)), m_(m) {}

    /// The bilinear interpolation of the `stride` values at uv into out[0 … stride − 1].
    void Lookup(const Vec2 &uv, double *out) const {
        const double s = m_.uscale * uv.x + m_.udelta, t = m_.vscale * uv.y + m_.vdelta;
        // Continuous texel coordinates (texel centres at integers): x along s, y down the rows.
        const double x = Reduce(s) * w_ - 0.5, y = Reduce(1 - t) * h_ - 0.5;
        const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
        const int ix[2] = {Index((long long)x0, w_), Index((long long)x0 + 1, w_)};
        const int iy[2] = {Index((long long)y0, h_), Index((long long)y0 + 1, h_)};
        const double wx[2] = {1 - fx, fx}, wy[2] = {1 - fy, fy};
        for (int c = 0; c < stride_; ++c) out[c] = 0;
        for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
                if (ix[a] < 0 || iy[b] < 0) continue;  // black outside the image
                const double weight = wx[a] * wy[b];
                const float *texel = &texels_[(std::size_t(iy[b]) * w_ + ix[a]) * stride_];
                for (int c = 0; c < stride_; ++c) out[c] += weight * texel[c];
            }
    }

    const std::vector<float> &Texels() const { return texels_; }
    int Width() const { return w_; }
    int Height() const { return h_; }
    const Mapping &Map() const { return m_; }

  private:
    /// An image coordinate brought into a bounded range the wrap mode maps the same way (so that
    /// far-away or non-finite coordinates never overflow an index): one period for repeat, two
    /// for mirror, [0, 1] for clamp, [−1, 2] for black (all taps outside beyond it).
    double Reduce(double s) const {
        if (!std::isfinite(s)) return 0;
        switch (m_.wrap) {
            case Wrap::Repeat: return s - std::floor(s);
            case Wrap::Mirror: return s - 2 * std::floor(s / 2);
            case Wrap::Clamp: return std::clamp(s, 0.0, 1.0);
            case Wrap::Black: return std::clamp(s, -1.0, 2.0);
        }
        return 0;
    }
    /// The texel index of integer coordinate i along an axis of n texels; −1 outside (black).
    int Index(long long i, int n) const {
        switch (m_.wrap) {
            case Wrap::Repeat: {
                const long long k = i % n;
                return int(k < 0 ? k + n : k);
            }
            case Wrap::Mirror: {
                const long long p = 2LL * n;
                long long k = i % p;
                if (k < 0) k += p;
                return int(k < n ? k : p - 1 - k);
            }
            case Wrap::Clamp: return int(std::clamp<long long>(i, 0, n - 1));
            case Wrap::Black: return i >= 0 && i < n ? int(i) : -1;
        }
        return -1;
    }

    int w_, h_, stride_;
    std::vector<float> texels_;
    Mapping m_;
};

const char *WrapName(Wrap w) {
    switch (w) {
        case Wrap::Repeat: return "repeat";
        case Wrap::Clamp: return "clamp";
        case Wrap::Mirror: return "mirror";
        case Wrap::Black: return "black";
    }
    return "";
}

/// What ToString reports about the file.
struct Source {
    std::string filename, colorspace, channel;
};

std::string Describe(const Source &src, const TexelGrid &g) {
    std::ostringstream os;
    os << "filename = \"" << src.filename << "\" (" << g.Width() << "x" << g.Height()
       << "), colorspace = " << src.colorspace << (src.channel.empty() ? "" : ", channel = " + src.channel)
       << ", wrap = " << WrapName(g.Map().wrap) << ", uscale = " << g.Map().uscale << ", vscale = " << g.Map().vscale
       << ", udelta = " << g.Map().udelta << ", vdelta = " << g.Map().vdelta;
    return os.str();
}

class BitmapScalarTexture final : public ScalarTexture {
  public:
    /// `colour`: the same texture decoded as a colour, when colorspace = "auto" makes data and
    /// colour readings differ (AsColour); else nullptr.
    BitmapScalarTexture(Dim dim, TexelGrid grid, double scale, double offset, Source src,
                        std::shared_ptr<const BitmapScalarTexture> colour = nullptr)
        : ScalarTexture(dim),
          grid_(std::move(grid)),
          scale_(scale),
          offset_(offset),
          src_(std::move(src)),
          colour_(std::move(colour)) {
        const auto [lo, hi] = std::minmax_element(grid_.Texels().begin(), grid_.Texels().end());
        double cmin = *lo, cmax = *hi;
        if (grid_.Map().wrap == Wrap::Black) cmin = std::min(cmin, 0.0), cmax = std::max(cmax, 0.0);
        min_ = offset_ + std::min(scale_ * cmin, scale_ * cmax);
        max_ = offset_ + std::max(scale_ * cmin, scale_ * cmax);
    }
    double EvalScalar(const TextureEvalContext &ctx) const override {
        double c;
        grid_.Lookup(ctx.uv, &c);
        return offset_ + scale_ * c;
    }
    double MinValue() const override { return min_; }
    double MaxValue() const override { return max_; }
    std::shared_ptr<const Texture> AsColour() const override { return colour_; }
    std::string ToString() const override {
        return "BitmapTexture[ " + Describe(src_, grid_) + ", scale = " + Value::Number(scale_, GetDim()).ToString() +
               ", offset = " + Value::Number(offset_, GetDim()).ToString() + " ]";
    }

  private:
    TexelGrid grid_;  // one channel
    double scale_, offset_;
    double min_ = 0, max_ = 0;
    Source src_;
    std::shared_ptr<const BitmapScalarTexture> colour_;
};

class BitmapSpectralTexture final : public Texture {
  public:
    BitmapSpectralTexture(TexelGrid grid, Source src) : grid_(std::move(grid)), src_(std::move(src)) {
        max_ = SmitsSpectrum::UpperBound(*std::max_element(grid_.Texels().begin(), grid_.Texels().end()));
    }
    std::optional<Dim> ScalarDim() const override { return std::nullopt; }
    SampledSpectrum Eval(const TextureEvalContext &ctx, const SampledWavelengths &wl) const override {
        double rgb[3];
        grid_.Lookup(ctx.uv, rgb);
        const SmitsSpectrum spectrum(Vec3(rgb[0], rgb[1], rgb[2]));
        SampledSpectrum r;
        for (int i = 0; i < wl.Count(); ++i) r[i] = spectrum.Eval(wl.lambda[i]);
        return r;
    }
    double MinValue() const override { return 0; }  // a lower bound: the uplift is never negative
    double MaxValue() const override { return max_; }
    std::string ToString() const override { return "BitmapTexture[ " + Describe(src_, grid_) + " ]"; }

  private:
    TexelGrid grid_;  // linear RGB in [0, 1]
    double max_ = 1;
    Source src_;
};

}  // namespace

/// The plug-in: reads the file and builds one of the two classes above.
class BitmapTexture {
  public:
    static const Schema &GetSchema() {
        static const Schema s{
            "texture",
            "bitmap",
            "an image file over uv, bilinear (OpenImageIO formats): a spectral reflectance (RGB, Smits uplift) "
            "or one channel as a scalar of any dimension",
            {
                P::File("filename", "the image: any format OpenImageIO reads (PNG, JPEG, TIFF, EXR, HDR …)").Required(),
                P::String("colorspace",
                          "OpenColorIO colour space of the pixels, converted to linear Rec.709: \"auto\" (data — "
                          "a thickness, angle or weight map — as stored; a colour — a reflectance — from the "
                          "file's own colour space, else sRGB for integer and linear for half/float pixels), "
                          "\"sRGB\", \"linear\", \"raw\" (data, unchanged) or any colour space of the $OCIO config")
                    .Default(Value::String("auto")),
                P::String("channel",
                          "makes a scalar texture of one channel: R, G, B (linear colour), Y (its luminance), A "
                          "or another channel of the file (default: a one-channel image's channel; an RGB image "
                          "without channel, scale or offset is a spectral texture)"),
                P::Number("scale", "scalar texture: value = offset + scale·channel; its unit gives the texture's "
                                   "dimension (e.g. 400 nm for a thickness map)")
                    .Default(Value::Number(1))
                    .AnyDim(),
                P::Number("offset", "scalar texture: added to scale·channel (the dimension of 'scale')")
                    .Default(Value::Number(0))
                    .AnyDim(),
                P::String("wrap", "outside the image: repeat, clamp (edge texels), mirror, or black (0)")
                    .Default(Value::String("repeat"))
                    .Choices({"repeat", "clamp", "mirror", "black"}),
                P::Number("uscale", "image repeats per unit of u (as checkerboard's scale): s = uscale·u + udelta")
                    .Default(Value::Number(1)),
                P::Number("vscale", "image repeats per unit of v: t = vscale·v + vdelta").Default(Value::Number(1)),
                P::Number("udelta", "shift of s (in image widths)").Default(Value::Number(0)),
                P::Number("vdelta", "shift of t (in image heights)").Default(Value::Number(0)),
            }};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &d, BuildContext &ctx) {
        using texture_common::GivenDim;
        const Dim dim = texture_common::CommonDim(d, {{"scale", GivenDim(d, "scale")}, {"offset", GivenDim(d, "offset")}});
        const std::string path = ctx.ResolveFile(d, "filename").string();
        Image img;
        std::string pixelFormat;
        try {
            img = ReadImage(path, &pixelFormat);
        } catch (const Error &e) {
            throw Error(d.Loc("filename"), e.Message());
        }
        if (img.width <= 0 || img.height <= 0 || img.channels.empty())
            throw Error(d.Loc("filename"), "'" + path + "' holds no pixels");
        const std::size_t n = std::size_t(img.width) * img.height, nc = img.channels.size();
        for (std::size_t i = 0; i < img.data.size(); ++i)
            if (!std::isfinite(img.data[i]))
                throw Error(d.Loc("filename"), "'" + path + "' holds a non-finite value (channel " +
                                                   img.channels[i % nc] + " of pixel " + std::to_string(i / nc) + ")");

        TexelGrid::Mapping map;
        const std::string wrap = d.GetString("wrap");
        map.wrap = wrap == "clamp" ? Wrap::Clamp : wrap == "mirror" ? Wrap::Mirror : wrap == "black" ? Wrap::Black : Wrap::Repeat;
        map.uscale = d.GetNumber("uscale");
        map.vscale = d.GetNumber("vscale");
        map.udelta = d.GetNumber("udelta");
        map.vdelta = d.GetNumber("vdelta");
        for (const char *p : {"uscale", "vscale"})
            if (!(d.GetNumber(p) != 0)) throw Error(d.Loc(p), std::string("'") + p + "' must not be 0");

        // The colour: R, G, B, or a one-channel (or Y, Y+A) image's grey.
        const int r = img.ChannelIndex("R"), g = img.ChannelIndex("G"), b = img.ChannelIndex("B");
        const bool rgb = r >= 0 && g >= 0 && b >= 0;
        const int grey = rgb ? -1 : img.ChannelIndex("Y") >= 0 ? img.ChannelIndex("Y") : nc == 1 ? 0 : -1;
        const bool hasColour = rgb || grey >= 0;

        const bool scalar = d.Has("channel") || d.Has("scale") || d.Has("offset") || !rgb;
        std::string channel;
        if (scalar) {
            if (d.Has("channel")) channel = d.GetString("channel");
            else if (grey >= 0) channel = "Y";
            else if (nc == 1) channel = img.channels[0];
            else
                throw Error(d.Has("scale") ? d.Loc("scale") : d.Has("offset") ? d.Loc("offset") : d.Loc("filename"),
                            "'" + path + "' has channels " + ChannelList(img) +
                                ": name the one the scalar texture reads with 'channel'");
        }
        const bool colourChannel = channel == "R" || channel == "G" || channel == "B" || channel == "Y";
        if (scalar && !(colourChannel && hasColour) && img.ChannelIndex(channel) < 0)
            throw Error(d.Loc("channel"), "'" + path + "' has no channel '" + channel + "'; it has " + ChannelList(img) +
                                              (hasColour ? " (and Y, the luminance of its colour)" : ""));
        if (scalar && colourChannel && !hasColour)
            throw Error(d.Loc("channel"), "'" + path + "' has no colour to take '" + channel + "' from; its channels are " +
                                              ChannelList(img));

        // Convert the colour to linear Rec.709 when it is used.
        std::string colorspace = d.GetString("colorspace");
        const bool useColour = !scalar || colourChannel;
        std::vector<float> colour;
        if (useColour) {
            bool fromFile = false;
            if (colorspace == "auto") {
                const auto it = img.metadata.find("oiio:ColorSpace");
                fromFile = it != img.metadata.end() && !it->second.empty();
                colorspace = fromFile ? it->second
                             : (pixelFormat == "half" || pixelFormat == "float" || pixelFormat == "double") ? "linear"
                                                                                                          : "sRGB";
            }
            colour.resize(3 * n);
            for (std::size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) colour[3 * i + c] = img.data[i * nc + (rgb ? (c == 0 ? r : c == 1 ? g : b) : grey)];
            try {
                ConvertToSceneLinear(colour.data(), n, colorspace);
            } catch (const Error &e) {
                if (fromFile)
                    throw Error(d.Loc("filename"), "'" + path + "' says its colour space is '" + colorspace + "': " +
                                                       e.Message() + "; give 'colorspace'");
                throw Error(d.Loc("colorspace"), e.Message());
            }
        } else if (colorspace != "auto" && colorspace != "raw") {
            throw Error(d.Loc("colorspace"), "channel '" + channel + "' is not a colour (R, G, B or Y): it is read as "
                                                 "stored; 'colorspace' does not apply");
        }

        const Source src{d.GetValue("filename").text, colorspace, channel};
        if (!scalar) {
            for (std::size_t i = 0; i < colour.size(); ++i) {
                // OCIO's float arithmetic may land a hair outside [0, 1] (sRGB 1.0 → 1.0000001).
                if (colour[i] > -1e-5f && colour[i] < 1 + 1e-5f) {
                    colour[i] = std::clamp(colour[i], 0.0f, 1.0f);
                    continue;
                }
                const std::size_t p = i / 3;
                throw Error(d.Loc("filename"),
                            "pixel (" + std::to_string(p % img.width) + ", " + std::to_string(p / img.width) +
                                ") of '" + path + "' has linear " + "RGB"[i % 3] + " = " + std::to_string(colour[i]) +
                                " in colour space '" + colorspace +
                                "': a spectral bitmap is a reflectance in [0, 1]; read other data with 'channel'");
            }
            return std::make_unique<BitmapSpectralTexture>(TexelGrid(img.width, img.height, 3, std::move(colour), map), src);
        }

        // The channel's values from colour triples `rgb` (R, G, B or their luminance Y), or as stored.
        const int stored = img.ChannelIndex(channel);
        auto channelOf = [&](const std::vector<float> &rgb) {
            std::vector<float> values(n);
            for (std::size_t i = 0; i < n; ++i) {
                if (channel == "Y" && hasColour)
                    values[i] = float(0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2]);
                else if (colourChannel && hasColour)
                    values[i] = rgb[3 * i + (channel == "R" ? 0 : channel == "G" ? 1 : 2)];
                else
                    values[i] = img.data[i * nc + stored];
            }
            return values;
        };
        auto make = [&](std::vector<float> values, const Source &s, std::shared_ptr<const BitmapScalarTexture> c) {
            return std::make_unique<BitmapScalarTexture>(dim, TexelGrid(img.width, img.height, 1, std::move(values), map),
                                                         d.GetNumber("scale"), d.GetNumber("offset"), s, std::move(c));
        };
        if (d.GetString("colorspace") != "auto" || !colourChannel || !hasColour) return make(channelOf(colour), src, nullptr);
        // "auto": data as stored (the primary reading), the colour decoded for a colour parameter.
        std::vector<float> stored3(3 * n);
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) stored3[3 * i + c] = img.data[i * nc + (rgb ? (c == 0 ? r : c == 1 ? g : b) : grey)];
        std::shared_ptr<const BitmapScalarTexture> asColour =
            make(channelOf(colour), Source{src.filename, "auto (as a colour: " + colorspace + ")", channel}, nullptr);
        return make(channelOf(stored3), Source{src.filename, "auto (as data: raw)", channel}, std::move(asColour));
    }

  private:
    static std::string ChannelList(const Image &img) {
        std::string s;
        for (const std::string &c : img.channels) s += (s.empty() ? "" : ", ") + c;
        return s;
    }
};

PHASOR_EXPORT_PLUGIN(Texture, BitmapTexture)

}  // namespace phasor
