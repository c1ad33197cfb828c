// SPDX-License-Identifier: Apache-2.0
// phasor — `noise` texture: fractal Brownian motion (fBm) of gradient noise, in uv or world space.
//
// Gradient noise (Perlin 1985, with the quintic fade of Perlin 2002): at the 8 corners c of the
// lattice cell holding x, a pseudo-random unit gradient g_c (one of the 12 cube-edge directions,
// chosen by the integer hash of c and the seed in core/render/sampler.h) gives the linear function
// g_c·(x − c); they are blended with the fade weights w(t) = 6t⁵ − 15t⁴ + 10t³ per axis. The
// value is 0 at every lattice point, C² across cells, and |Σ w_c g_c·(x − c)| ≤ Σ w_c |x − c|
// ≤ √3/2 (the sum peaks at the cell centre), so n = (2/√3)·Σ … lies in [−1, 1].
// fBm: f(x) = Σ_o 2^−o n_o(2^o x / scale) / Σ_o 2^−o over `octaves` octaves (lacunarity 2,
// gain 1/2, each octave its own hash seed), also in [−1, 1], with mean 0 over the lattice (the
// gradients are symmetric). The texture is clamp(offset + amplitude·f, min, max); its dimension
// is that of offset, amplitude, min and max (e.g. `offset = 300 nm` makes a length texture).
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <sstream>

#include "core/render/registry.h"
#include "core/render/sampler.h"
#include "core/render/texture.h"
#include "textures/texture_common.h"

namespace phasor {

namespace {

double Fade(double t) { return t * t * t * (t * (6 * t - 15) + 10); }

// Gradient noise in [−1, 1] at x (lattice units).
double GradientNoise(const Vec3 &x, uint32_t seed) {
    static const double s = 1 / std::sqrt(2.0);
    static const std::array<Vec3, 12> grad = {Vec3(s, s, 0),  Vec3(-s, s, 0),  Vec3(s, -s, 0),  Vec3(-s, -s, 0),
                                              Vec3(s, 0, s),  Vec3(-s, 0, s),  Vec3(s, 0, -s),  Vec3(-s, 0, -s),
                                              Vec3(0, s, s),  Vec3(0, -s, s),  Vec3(0, s, -s),  Vec3(0, -s, -s)};
    // Beyond 2⁵³ cells (or at a non-finite point) there is no sub-cell position left: 0.
    if (!(MaxComponent(Vec3(std::abs(x.x), std::abs(x.y), std::abs(x.z))) < 0x1p53)) return 0;
    const double fx = std::floor(x.x), fy = std::floor(x.y), fz = std::floor(x.z);
    const int64_t ix = int64_t(fx), iy = int64_t(fy), iz = int64_t(fz);
    const Vec3 f(x.x - fx, x.y - fy, x.z - fz);
    const Vec3 w(Fade(f.x), Fade(f.y), Fade(f.z));
    // Hash(x, y, z, seed) of the corners, their common leading steps shared (HashNext).
    uint64_t hxy[2][2];
    for (int cx = 0; cx < 2; ++cx) {
        const uint64_t hx = HashFirst(uint64_t(ix + cx));
        for (int cy = 0; cy < 2; ++cy) hxy[cx][cy] = HashNext(hx, uint64_t(iy + cy));
    }
    double sum = 0;
    for (int c = 0; c < 8; ++c) {
        const int cx = c & 1, cy = (c >> 1) & 1, cz = (c >> 2) & 1;
        const Vec3 &g = grad[HashNext(HashNext(hxy[cx][cy], uint64_t(iz + cz)), seed) % 12];
        const double weight = (cx ? w.x : 1 - w.x) * (cy ? w.y : 1 - w.y) * (cz ? w.z : 1 - w.z);
        sum += weight * Dot(g, Vec3(f.x - cx, f.y - cy, f.z - cz));
    }
    return sum * (2 / std::sqrt(3.0));
}

}  // namespace

class NoiseTexture final : public ScalarTexture {
  public:
    struct Params {
        Dim dim;
        bool world = false;  // world position [m] instead of uv
        double scale = 0.1;  // cell size of the first octave: uv units, or m in world space
        int octaves = 4;
        uint32_t seed = 0;
        double offset = 0, amplitude = 0;
        double min = -Infinity, max = Infinity;  // clamps
    };
    explicit NoiseTexture(const Params &p) : ScalarTexture(p.dim), p_(p) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "texture",
            "noise",
            "fractal gradient noise: clamp(offset + amplitude·fBm, min, max), fBm in [−1, 1] with mean 0 (its "
            "dimension is its values')",
            {
                P::String("space", "coordinates the noise lives in: surface uv, or world position")
                    .Default(Value::String("uv"))
                    .Choices({"uv", "world"}),
                P::Number("scale", "size of a noise cell of the first octave: a plain number in uv space, a length "
                                   "in world space (required there)")
                    .Default(Value::Number(0.1))
                    .AnyDim(),
                P::Integer("octaves", "number of octaves (each half the size and half the amplitude of the last)")
                    .Default(Value::Integer(4))
                    .Min(1)
                    .Max(16),
                P::Number("offset", "mean value").Default(Value::Number(0)).AnyDim(),
                P::Number("amplitude", "largest deviation from 'offset' (before the clamps)").Required().AnyDim(),
                P::Number("min", "lower clamp (default: none)").AnyDim(),
                P::Number("max", "upper clamp (default: none)").AnyDim(),
                P::Integer("seed", "selects an independent pattern").Default(Value::Integer(0)).Min(0),
            }};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &dict, BuildContext &) {
        using texture_common::GivenDim;
        Params p;
        p.dim = texture_common::CommonDim(dict, {{"offset", GivenDim(dict, "offset")},
                                                 {"amplitude", GivenDim(dict, "amplitude")},
                                                 {"min", GivenDim(dict, "min")},
                                                 {"max", GivenDim(dict, "max")}});
        p.world = dict.GetString("space") == "world";
        const Dim scaleDim = p.world ? Dim::Length() : Dim::None();
        const std::optional<Dim> sd = GivenDim(dict, "scale");
        if (sd ? *sd != scaleDim : p.world)
            throw Error(dict.Loc(sd ? "scale" : "space"), "'scale' in " + dict.GetString("space") + " space must be " +
                                               scaleDim.Describe() + (sd ? "; got " + sd->Describe() : " (give it, e.g. 1 mm)"));
        p.scale = dict.GetNumber("scale");
        if (!(p.scale > 0)) throw Error(dict.Loc("scale"), "'scale' must be positive");
        p.octaves = dict.GetInt("octaves");
        p.seed = uint32_t(dict.GetInt("seed"));
        p.offset = dict.GetNumber("offset");
        p.amplitude = dict.GetNumber("amplitude");
        if (dict.Has("min")) p.min = dict.GetNumber("min");
        if (dict.Has("max")) p.max = dict.GetNumber("max");
        if (!(p.min <= p.max)) throw Error(dict.Loc("max"), "'max' must not be below 'min'");
        return std::make_unique<NoiseTexture>(p);
    }

    /// The unclamped, unscaled fBm in [−1, 1] at a point in the noise's own coordinates.
    double Fbm(const Vec3 &x) const {
        double sum = 0, norm = 0, gain = 1, freq = 1 / p_.scale;
        for (int o = 0; o < p_.octaves; ++o) {
            sum += gain * GradientNoise(freq * x, p_.seed * 16u + uint32_t(o));
            norm += gain;
            gain *= 0.5;
            freq *= 2;
        }
        return sum / norm;
    }

    double EvalScalar(const TextureEvalContext &ctx) const override {
        const Vec3 x = p_.world ? ctx.p : Vec3(ctx.uv.x, ctx.uv.y, 0);
        return Clamp(p_.offset + p_.amplitude * Fbm(x), p_.min, p_.max);
    }

    double MinValue() const override { return Clamp(p_.offset - std::abs(p_.amplitude), p_.min, p_.max); }
    double MaxValue() const override { return Clamp(p_.offset + std::abs(p_.amplitude), p_.min, p_.max); }

    std::string ToString() const override {
        const Dim sd = p_.world ? Dim::Length() : Dim::None();
        std::ostringstream os;
        os << "NoiseTexture[ space = " << (p_.world ? "world" : "uv") << ", scale = "
           << Value::Number(p_.scale, sd).ToString() << ", octaves = " << p_.octaves << ", seed = " << p_.seed
           << ", offset = " << Value::Number(p_.offset, GetDim()).ToString()
           << ", amplitude = " << Value::Number(p_.amplitude, GetDim()).ToString() << " ]";
        return os.str();
    }

  private:
    Params p_;
};

PHASOR_EXPORT_PLUGIN(Texture, NoiseTexture)

}  // namespace phasor
