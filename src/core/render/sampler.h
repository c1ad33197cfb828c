// SPDX-License-Identifier: Apache-2.0
// phasor — random numbers and the sampler interface. Samplers are a plug-in family (`sampler`,
// src/samplers/: `sobol`, the default, and `independent`). Every sample value is a pure function
// of (seed, pixel, sample index, dimension), so renders are deterministic for any thread count and
// any tile order.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/hash.h"  // MixBits
#include "core/math.h"

namespace phasor {

/// PCG32 (O'Neill 2014): 64-bit state, 32-bit output.
class Pcg32 {
  public:
    Pcg32() : Pcg32(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL) {}
    Pcg32(uint64_t seed, uint64_t stream) { SetSequence(seed, stream); }
    void SetSequence(uint64_t seed, uint64_t stream);
    uint32_t NextU32();
    /// Uniform in [0, 1).
    double Uniform();

  private:
    uint64_t state_ = 0, inc_ = 1;
};

/// Hash(a, b, c, d) = HashNext(HashNext(HashNext(HashFirst(a), b), c), d): keys that share
/// leading values (the corners of a lattice cell) can share the first steps.
inline uint64_t HashFirst(uint64_t a) { return MixBits(a + 0x9e3779b97f4a7c15ULL); }
inline uint64_t HashNext(uint64_t h, uint64_t v) { return MixBits(h ^ (v + 0x9e3779b97f4a7c15ULL)); }
inline uint64_t Hash(uint64_t a, uint64_t b, uint64_t c = 0, uint64_t d = 0) {
    return HashNext(HashNext(HashNext(HashFirst(a), b), c), d);
}
/// A pixel's coordinates as one 64-bit key (for hashing).
inline uint64_t PixelKey(int x, int y) { return (uint64_t(uint32_t(x)) << 32) | uint32_t(y); }

/// A sampler hands out the dimensions of one sample of one pixel. Not thread-safe; one per
/// thread (Clone()). A plug-in (`static const Schema &GetSchema()`, `static std::unique_ptr<Sampler>
/// Create(const ParamDict &, BuildContext &)`, PHASOR_EXPORT_PLUGIN(Sampler, Class), one CMake
/// line); the render loop seeds it (SetSeed) with the render's seed.
class Sampler {
  public:
    virtual ~Sampler() = default;
    /// The render's seed (--seed, Render.seed): every value depends on it.
    void SetSeed(uint64_t seed) { seed_ = seed; }
    uint64_t Seed() const { return seed_; }
    /// Starts sample `index` of pixel (x, y); resets the dimension counter.
    virtual void StartPixelSample(int x, int y, int index) = 0;
    virtual double Get1D() = 0;
    virtual Vec2 Get2D() = 0;
    /// The 2-D sample used for the position inside the pixel (first dimensions, stratified best).
    virtual Vec2 GetPixel2D() = 0;
    /// A copy with the same seed (its per-sample state is reset by StartPixelSample).
    virtual std::unique_ptr<Sampler> Clone() const = 0;
    virtual std::string Name() const = 0;

  protected:
    uint64_t seed_ = 0;
};

/// A plug-in of the sampler family by name (Registry<Sampler>), seeded; nullptr if unknown. (A
/// scene's own Sampler blocks are found by name through Scene::NewSampler.)
std::unique_ptr<Sampler> MakeSampler(const std::string &name, uint64_t seed);
/// Shorthands for tests and benchmarks.
inline std::unique_ptr<Sampler> MakeSobolSampler(uint64_t seed) { return MakeSampler("sobol", seed); }
inline std::unique_ptr<Sampler> MakeIndependentSampler(uint64_t seed) { return MakeSampler("independent", seed); }

}  // namespace phasor
