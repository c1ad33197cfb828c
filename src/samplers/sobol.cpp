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
    v = __builtin_bswap32(v);  // the bytes reversed; then the nibbles, pairs and bits within each
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    return ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
}

// Sobol' dimension 0 (van der Corput: the index's bits reversed) and dimension 1 (primitive
// polynomial x + 1), the latter bit-reversed: Sobol1Reversed(i) = ReverseBits(Sobol1(i)). Its
// generator matrix is applied a byte at a time through four 256-entry tables (the XOR of the
// reversed columns selected by each byte; reversal is linear over XOR), instead of a loop over the
// 32 bits of the index.
struct Sobol1Tables {
    uint32_t t[4][256];
    Sobol1Tables() {
        uint32_t column[32];
        uint32_t v = 1u << 31;
        for (int b = 0; b < 32; ++b, v ^= v >> 1) column[b] = ReverseBits(v);
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
uint32_t Sobol1Reversed(uint32_t i) {
    return kSobol1.t[0][i & 0xff] ^ kSobol1.t[1][(i >> 8) & 0xff] ^ kSobol1.t[2][(i >> 16) & 0xff] ^
           kSobol1.t[3][i >> 24];
}

// Hash-based approximation of a nested uniform (Owen) scramble (Laine–Karras style hash, Burley
// 2020), in the bit-reversed domain: each output bit depends only on the input bits below it, so
// ReverseBits(ReversedScramble(ReverseBits(v), seed)) lets each bit of v depend only on the bits
// above it — the Owen scramble of v. Callers keep values reversed between scrambles, so that a
// sample costs one reversal per coordinate (Sobol' dimension 0 is itself a reversal).
uint32_t ReversedScramble(uint32_t v, uint32_t seed) {
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return v;
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
        reversedIndex_ = ReverseBits(uint32_t(index));
        dim_ = 0;
    }
    // With Owen(v, s) = Reverse(ReversedScramble(Reverse(v), s)): the pair's index i is the
    // Owen-scrambled sample index (the per-pixel, per-pair shuffle), and the coordinates are
    // Owen(Sobol0(i)) = Reverse(ReversedScramble(i)) and Owen(Sobol1(i)) =
    // Reverse(ReversedScramble(Sobol1Reversed(i))).
    double Get1D() override {
        const uint64_t h = DimensionHash();
        const uint32_t i = ReverseBits(ReversedScramble(reversedIndex_, uint32_t(h)));
        return ToUnit(ReverseBits(ReversedScramble(i, uint32_t(h >> 32))));
    }
    Vec2 Get2D() override {
        const uint64_t h = DimensionHash();
        const uint32_t h2 = uint32_t(MixBits(h));
        const uint32_t i = ReverseBits(ReversedScramble(reversedIndex_, uint32_t(h)));
        return {ToUnit(ReverseBits(ReversedScramble(i, uint32_t(h >> 32)))),
                ToUnit(ReverseBits(ReversedScramble(Sobol1Reversed(i), h2)))};
    }
    Vec2 GetPixel2D() override { return Get2D(); }
    std::unique_ptr<Sampler> Clone() const override { return std::make_unique<SobolSampler>(*this); }
    std::string Name() const override { return "sobol"; }

  private:
    // One well-mixed 64-bit value per (pixel, dimension): seeds the index shuffle and the scrambles.
    uint64_t DimensionHash() { return MixBits(pixelHash_ ^ (0x9e3779b97f4a7c15ULL * ++dim_)); }

    uint64_t pixelHash_ = 0;
    uint32_t reversedIndex_ = 0;  // the pixel sample's index, bit-reversed
    uint64_t dim_ = 0;
};

PHASOR_EXPORT_PLUGIN(Sampler, SobolSampler)

}  // namespace phasor
