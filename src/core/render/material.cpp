// SPDX-License-Identifier: Apache-2.0
// phasor — the non-virtual part of the kernel interface (core/render/material.h): the lobe mask is
// applied here, once, for every kernel.
#include "core/render/material.h"

#include "core/diagnostics.h"
#include "core/render/genray.h"

namespace phasor {

double ScatterQuery::Beta2(int i) const { return gr ? gr->beta2[i] : 0; }
double ScatterQuery::Rho(int i) const { return gr ? gr->rho[i] : 0; }

NearDeltaLobe &NearDeltaLobes::Add() {
    if (count >= Capacity)
        throw Error("a kernel listed more than " + std::to_string(Capacity) + " near-delta lobes");
    lobe[count] = NearDeltaLobe{};
    return lobe[count++];
}

void ContinuousLobeIds::Add(int lobeId) {
    if (count >= Capacity)
        throw Error("a kernel listed more than " + std::to_string(Capacity) + " continuous lobes");
    id[std::size_t(count++)] = lobeId;
}

Vec3 LobeSAxis(const Vec3 &wi, const Vec3 &wo) {
    const Vec3 c = Cross(wi, wo);
    const double l = Length(c);
    if (l > 1e-9) return c / l;
    const Vec3 n = Cross(Vec3(0, 0, 1), wi);
    const double ln = Length(n);
    if (ln > 1e-9) return n / ln;
    return Vec3(0, 1, 0);
}

SampledSpectrum Material::LobeWeight(const ScatterQuery &q, int lobe) const {
    NearDeltaLobes lobes;
    ListNearDelta(q, lobes);
    for (const NearDeltaLobe &l : lobes)
        if (l.id == lobe) return l.weight;
    return SampledSpectrum(0.0);
}

std::optional<LobeResponse> Material::EvalContinuousLobes(const ScatterQuery &q, const Vec3 &wo) const {
    ContinuousLobeIds ids;
    ContinuousLobes(q, ids);
    std::optional<LobeResponse> sum;
    for (int id : ids) {
        auto r = EvalLobe(q, id, wo);
        if (!r) continue;
        if (!sum) {
            sum = *r;
            continue;
        }
        sum->hasJones = false;
        for (int i = 0; i < q.wl->Count(); ++i) sum->mueller[i] = sum->mueller[i] + r->mueller[i];
    }
    // Continuous lobes have no interference terms (LobeCoherence is for near-delta lobes).
    if (sum) sum->coherence = LobeCoherence{};
    return sum;
}

namespace {
unsigned MaskOf(unsigned scatterFlags) {
    return (scatterFlags & ScatterNearDelta) ? LobeNearDelta : LobeContinuous;
}
}  // namespace

std::optional<ScatterSample> Material::Sample(const ScatterQuery &q, double u0, const Vec2 &u) const {
    auto s = SampleLobes(q, u0, u);
    if (s && !(q.lobes & MaskOf(s->flags))) return std::nullopt;  // outside the mask: unbiased for the rest
    return s;
}

SampledSpectrum Material::Eval(const ScatterQuery &q, const Vec3 &wo) const {
    return (q.lobes & LobeContinuous) ? EvalContinuous(q, wo) : SampledSpectrum(0.0);
}

SampledSpectrum Material::EvalFrom(const ScatterQuery &q, const Vec3 &wo, const IncidentWave &w) const {
    return (q.lobes & LobeContinuous) ? EvalContinuousFrom(q, wo, w) : SampledSpectrum(0.0);
}

double Material::Pdf(const ScatterQuery &q, const Vec3 &wo) const {
    return (q.lobes & LobeContinuous) ? PdfContinuous(q, wo) : 0;
}

bool Material::IsFootprintAware() const {
    static const SpectralGenRay gr;  // a generalized-ray query (Capabilities reads no geometry)
    ScatterQuery q;
    q.wi = Vec3(0, 0, 1);
    q.rayOptics = false;
    q.gr = &gr;
    return (Capabilities(q) & CapFootprintAware) != 0;
}

std::optional<ScatterSample> Material::SampleLobes(const ScatterQuery &q, double u0, const Vec2 &) const {
    NearDeltaLobes lobes;
    ListNearDelta(q, lobes);
    return SampleListedLobe(lobes, u0);
}

std::optional<ScatterSample> SampleListedLobe(const NearDeltaLobes &lobes, double u0) {
    return SampleListedLobe(std::span<const NearDeltaLobe>(lobes.begin(), lobes.end()), u0);
}

std::optional<ScatterSample> SampleListedLobe(std::span<const NearDeltaLobe> lobes, double u0) {
    double c = 0;
    for (const NearDeltaLobe &l : lobes) {
        c += l.prob;
        if (u0 >= c && &l != &lobes.back()) continue;  // the last lobe takes rounding's remainder
        if (!(l.prob > 0)) return std::nullopt;
        ScatterSample s;
        s.wo = l.wo[0];
        s.weight = l.weight / l.prob;
        s.pdf = l.prob;
        s.lobe = l.id;
        s.flags = l.flags;
        s.eta = l.Eta(0);
        return s;
    }
    return std::nullopt;
}

EnergySense EnergySenseOf(const Material &m) {
    if (m.IsReciprocal()) return EnergySense::Reciprocal;
    return m.ConservesEnergyPerIncidentDirection() ? EnergySense::PerIncidentDirection : EnergySense::PerQuery;
}

std::optional<EnergySense> CombinedEnergySense(std::span<const Material *const> children) {
    bool perQuery = false, perIncident = false;
    for (const Material *m : children) {
        const EnergySense s = EnergySenseOf(*m);
        perQuery = perQuery || s == EnergySense::PerQuery;
        perIncident = perIncident || s == EnergySense::PerIncidentDirection;
    }
    if (perQuery && perIncident) return std::nullopt;
    return perQuery ? EnergySense::PerQuery : perIncident ? EnergySense::PerIncidentDirection : EnergySense::Reciprocal;
}

const char *Describe(EnergySense s) {
    switch (s) {
        case EnergySense::Reciprocal:
            return "reciprocal";
        case EnergySense::PerQuery:
            return "conserves energy per query";
        case EnergySense::PerIncidentDirection:
            return "conserves energy per incident direction";
    }
    return "";
}

bool NearDeltaDirection(const Vec3 &wi, double nIn, double nOut, const Vec2 &shift, double lambda,
                        bool transmission, Vec3 *wo) {
    // theory §4.2 (vector grating equation): the tangential wave vector of the incident wave
    // (travelling along −wi) plus the lobe's shift is the outgoing one.
    const double s = lambda / (2 * Pi);
    const double tx = (-nIn * wi.x + shift.x * s) / nOut, ty = (-nIn * wi.y + shift.y * s) / nOut;
    const double t2 = tx * tx + ty * ty;
    if (!(t2 < 1)) return false;  // evanescent
    const double z = std::sqrt(1 - t2);
    const double side = wi.z >= 0 ? 1.0 : -1.0;  // wi's side
    *wo = Vec3(tx, ty, transmission ? -side * z : side * z);
    return true;
}

}  // namespace phasor
