// SPDX-License-Identifier: Apache-2.0
#include "core/render/sampler.h"

#include "core/render/registry.h"

namespace phasor {

void Pcg32::SetSequence(uint64_t seed, uint64_t stream) {
    // PCG32 initialisation (O'Neill 2014).
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    NextU32();
    state_ += seed;
    NextU32();
}

uint32_t Pcg32::NextU32() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

double Pcg32::Uniform() {
    // 53 random bits → [0, 1).
    uint64_t hi = NextU32(), lo = NextU32();
    return double(((hi << 32) | lo) >> 11) * 0x1p-53;
}

std::unique_ptr<Sampler> MakeSampler(const std::string &name, uint64_t seed) {
    const PluginEntry<Sampler> *entry = Registry<Sampler>::Find(name);
    if (!entry) return nullptr;
    const SceneDesc none;
    Diagnostics diag;
    BuildContext ctx(none, diag);
    ParamDict params;
    params.Validate(entry->schema(), diag);
    std::unique_ptr<Sampler> s = entry->create(params, ctx);
    s->SetSeed(seed);
    return s;
}

}  // namespace phasor
