// SPDX-License-Identifier: Apache-2.0
// `sobol`: low-discrepancy samples, the default. Every pair of dimensions is an Owen-scrambled
// (0,2)-sequence (Sobol' dimensions 0 and 1; hashed nested scrambling, Laine–Karras / Burley 2020)
// whose sample order is shuffled per pixel and per pair, so consecutive pairs are decorrelated and
// every prefix of 2^k samples of a pixel is stratified ("padded" Sobol').
#include "core/render/registry.h"
#include "core/render/sampler.h"

namespace phasor {

namespace {

uint32_t ReverseBits(uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
}

// Sobol' dimension 0 (van der Corput) and dimension 1 (primitive polynomial x + 1).
uint32_t Sobol0(uint32_t i) { return ReverseBits(i); }
// Its generator matrix is applied a byte at a time through four 256-entry tables (the XOR of the
// columns selected by each byte), instead of a loop over the 32 bits of the index.
struct Sobol1Tables {
    uint32_t t[4][256];
    Sobol1Tables() {
        uint32_t column[32];
        uint32_t v = 1u << 31;
        for (int b = 0; b < 32; ++b, v ^= v >> 1) column[b] = v;
        for (int k = 0; k < 4; ++k)
            for (int byte = 0; byte < 256; ++byte) {
                uint32_t r = 0;
                for (int bit = 0; bit < 8; ++bit)
                    if (byte & (1 << bit)) r ^= column[8 * k + bit];
                t[k][byte] = r;
            }
    }
};
const Sobol1Tables kSobol1;
uint32_t Sobol1(uint32_t i) {
    return kSobol1.t[0][i & 0xff] ^ kSobol1.t[1][(i >> 8) & 0xff] ^ kSobol1.t[2][(i >> 16) & 0xff] ^
           kSobol1.t[3][i >> 24];
}

// Hash-based approximation of a nested uniform (Owen) scramble: a permutation of the bits
// that only lets each bit depend on the bits above it (Laine–Karras style hash, Burley 2020).
uint32_t OwenScramble(uint32_t v, uint32_t seed) {
    v = ReverseBits(v);
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return ReverseBits(v);
}

double ToUnit(uint32_t v) { return std::min(double(v) * 0x1p-32, 0x1.fffffffffffffp-1); }

}  // namespace

class SobolSampler final : public Sampler {
  public:
    static const Schema &GetSchema() {
        static const Schema s{"sampler", "sobol",
                              "Owen-scrambled Sobol' (0,2)-sequences per pair of dimensions (the default; its "
                              "`variance` channel overstates the error, see --sampler independent).",
                              {}};
        return s;
    }
    static std::unique_ptr<Sampler> Create(const ParamDict &, BuildContext &) { return std::make_unique<SobolSampler>(); }
    /// The sampler of a scene that names none (Render.sampler's default).
    static constexpr bool IsDefault = true;

    void StartPixelSample(int x, int y, int index) override {
        pixelHash_ = Hash(seed_, PixelKey(x, y));
        index_ = uint32_t(index);
        dim_ = 0;
    }
    double Get1D() override {
        uint64_t h = DimensionHash();
        uint32_t i = OwenScramble(index_, uint32_t(h));
        return ToUnit(OwenScramble(Sobol0(i), uint32_t(h >> 32)));
    }
    Vec2 Get2D() override {
        uint64_t h = DimensionHash();
        uint32_t h2 = uint32_t(MixBits(h));
        uint32_t i = OwenScramble(index_, uint32_t(h));
        return {ToUnit(OwenScramble(Sobol0(i), uint32_t(h >> 32))), ToUnit(OwenScramble(Sobol1(i), h2))};
    }
    Vec2 GetPixel2D() override { return Get2D(); }
    std::unique_ptr<Sampler> Clone() const override { return std::make_unique<SobolSampler>(*this); }
    std::string Name() const override { return "sobol"; }

  private:
    // One well-mixed 64-bit value per (pixel, dimension): seeds the index shuffle and the scrambles.
    uint64_t DimensionHash() { return MixBits(pixelHash_ ^ (0x9e3779b97f4a7c15ULL * ++dim_)); }

    uint64_t pixelHash_ = 0;
    uint32_t index_ = 0;
    uint64_t dim_ = 0;
};

PHASOR_EXPORT_PLUGIN(Sampler, SobolSampler)

}  // namespace phasor
