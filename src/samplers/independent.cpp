// SPDX-License-Identifier: Apache-2.0
// `independent`: independent uniform samples from a PCG32 stream per (seed, pixel, sample). The
// sampler whose `variance` channel is an honest error estimate (docs/architecture.md, "Error
// estimates").
#include "core/render/registry.h"
#include "core/render/sampler.h"

namespace phasor {

class IndependentSampler final : public Sampler {
  public:
    static const Schema &GetSchema() {
        static const Schema s{"sampler", "independent",
                              "Independent uniform samples (PCG32 per pixel and sample): unbiased variance estimates.",
                              {}};
        return s;
    }
    static std::unique_ptr<Sampler> Create(const ParamDict &, BuildContext &) {
        return std::make_unique<IndependentSampler>();
    }

    void StartPixelSample(int x, int y, int index) override {
        rng_.SetSequence(Hash(seed_, PixelKey(x, y)), uint64_t(index));
    }
    double Get1D() override { return rng_.Uniform(); }
    Vec2 Get2D() override {
        double a = rng_.Uniform();
        return {a, rng_.Uniform()};
    }
    Vec2 GetPixel2D() override { return Get2D(); }
    std::unique_ptr<Sampler> Clone() const override { return std::make_unique<IndependentSampler>(*this); }
    std::string Name() const override { return "independent"; }

  private:
    Pcg32 rng_;
};

PHASOR_EXPORT_PLUGIN(Sampler, IndependentSampler)

}  // namespace phasor
