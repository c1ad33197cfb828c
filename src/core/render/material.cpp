// SPDX-License-Identifier: Apache-2.0
// phasor — the non-virtual part of the kernel interface (core/render/material.h): the lobe mask is
// applied here (PreparedKernel::Sample and the inline Eval, EvalFrom, Pdf, EvalPdf), once, for every
// kernel.
#include "core/render/material.h"

#include <algorithm>
#include <cmath>

#include "core/diagnostics.h"
#include "core/render/genray.h"

namespace phasor {

double ScatterQuery::Beta2(int i) const { return gr ? gr->beta2[i] : 0; }
double ScatterQuery::Rho(int i) const { return gr ? gr->rho[i] : 0; }

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

bool IsStraightThrough(const NearDeltaLobe &lobe, const Vec3 &wi, int count) {
    if (!(lobe.flags & ScatterTransmission) || lobe.shift.x != 0 || lobe.shift.y != 0) return false;
    for (int i = 0; i < count; ++i)
        if (lobe.nIn[i] != lobe.nOut[i] || !(Dot(lobe.wo[i], wi) < -1 + 1e-12)) return false;
    return true;
}

bool PassesStraight(const Material &mat, const NearDeltaLobe &lobe, const Vec3 &wi, int count) {
    return mat.MayPassStraight() && IsStraightThrough(lobe, wi, count);
}

bool PassesStraight(const Material &mat, const PreparedKernel &k, int lobeId) {
    const NearDeltaLobe *l = mat.MayPassStraight() ? k.FindLobe(lobeId) : nullptr;
    return l && PassesStraight(mat, *l, k.Query().wi, k.Query().wl ? k.Query().wl->Count() : 1);
}

NearDeltaLobe &LobeList::Add() {
    if (count_ >= capacity_)
        throw Error("a kernel listed more than the " + std::to_string(capacity_) + " near-delta lobes it made room for");
    return *::new (lobe_ + count_++) NearDeltaLobe{};
}

namespace {
unsigned MaskOf(unsigned scatterFlags) {
    return (scatterFlags & ScatterNearDelta) ? LobeNearDelta : LobeContinuous;
}
}  // namespace

void NearDeltaLobe::DeferWeights(unsigned slots, const PreparedKernel &kernel) {
    if (slots & 1u) throw Error("a kernel deferred the hero's weight of lobe " + std::to_string(id) + " (a kernel bug)");
    pending_ = slots ? Pending{&kernel, id, slots} : Pending{};
}

void NearDeltaLobe::Complete(unsigned slots) const {
    const std::optional<SampledSpectrum> w = pending_.kernel->LobeWeightAt(pending_.id, pending_.kernel->Query().wi, slots);
    if (!w) throw Error("a kernel deferred lobe weights it does not answer in LobeWeightAt (a kernel bug)");
    for (int i = 0; i < NumWavelengths; ++i)
        if ((slots >> i) & 1u) weight_[i] = (*w)[i];
    pending_.slots &= ~slots;
    if (!pending_.slots) pending_ = {};
}

const NearDeltaLobe *PreparedKernel::FindLobe(int id) const {
    for (const NearDeltaLobe &l : lobes_)
        if (l.id == id) return &l;
    return nullptr;
}

std::optional<ScatterSample> PreparedKernel::Sample(double u0, const Vec2 &u, unsigned lobes) const {
    auto s = SampleLobes(u0, u);
    if (s && !(lobes & MaskOf(s->flags))) return std::nullopt;  // outside the mask: unbiased for the rest
    return s;
}

std::optional<ScatterSample> PreparedKernel::SampleLobes(double u0, const Vec2 &) const {
    return SampleListedLobe(lobes_, u0, q_.heroAfterDispersive);
}

std::optional<LobeResponse> PreparedKernel::EvalContinuousLobes(const Vec3 &wo) const {
    std::optional<LobeResponse> sum;
    for (int id : continuous_) {
        auto r = EvalLobe(id, wo);
        if (!r) continue;
        if (!sum) {
            sum = *r;
            continue;
        }
        sum->hasJones = false;
        for (int i = 0; i < q_.wl->Count(); ++i) sum->mueller[i] = sum->mueller[i] + r->mueller[i];
    }
    // Continuous lobes have no interference terms (LobeCoherence is for near-delta lobes).
    if (sum) sum->coherence = LobeCoherence{};
    return sum;
}

std::optional<ScatterSample> SampleListedLobe(std::span<const NearDeltaLobe> lobes, double u0, bool heroOnlyIfDispersive) {
    double c = 0;
    for (const NearDeltaLobe &l : lobes) {
        c += l.prob;
        if (u0 >= c && &l != &lobes.back()) continue;  // the last lobe takes rounding's remainder
        if (!(l.prob > 0)) return std::nullopt;
        ScatterSample s;
        s.wo = l.wo[0];
        if (heroOnlyIfDispersive && (l.flags & ScatterDispersive)) s.weight[0] = l.Weight(1u)[0] / l.prob;
        else s.weight = l.Weight() / l.prob;
        s.pdf = l.prob;
        s.lobe = l.id;
        s.flags = l.flags;
        s.eta = l.Eta(0);
        return s;
    }
    return std::nullopt;
}

std::optional<double> ReferenceAngleOf(const Material &m, const TextureEvalContext &tex) {
    const auto *r = dynamic_cast<const ReferenceDirection *>(&m);
    return r ? r->ReferenceAngle(tex) : std::nullopt;
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

namespace {
/// The tangential part of a near-delta lobe's direction: theory §4.2 (vector grating equation), the
/// tangential wave vector of the incident wave (travelling along −wi) plus the lobe's shift is the
/// outgoing one.
Vec2 NearDeltaTangential(const Vec3 &wi, double nIn, double nOut, const Vec2 &shift, double lambda) {
    const double s = lambda / (2 * Pi);
    return Vec2((-nIn * wi.x + shift.x * s) / nOut, (-nIn * wi.y + shift.y * s) / nOut);
}
}  // namespace

bool NearDeltaDirection(const Vec3 &wi, double nIn, double nOut, const Vec2 &shift, double lambda,
                        bool transmission, Vec3 *wo) {
    const Vec2 t = NearDeltaTangential(wi, nIn, nOut, shift, lambda);
    const double t2 = t.x * t.x + t.y * t.y;
    if (!(t2 < 1)) return false;  // evanescent
    const double z = std::sqrt(1 - t2);
    const double side = wi.z >= 0 ? 1.0 : -1.0;  // wi's side
    *wo = Vec3(t.x, t.y, transmission ? -side * z : side * z);
    return true;
}

bool NearDeltaPropagates(const Vec3 &wi, double nIn, double nOut, const Vec2 &shift, double lambda) {
    const Vec2 t = NearDeltaTangential(wi, nIn, nOut, shift, lambda);
    return t.x * t.x + t.y * t.y < 1;
}

OrderRange PropagatingOrders(const Vec3 &wi, double nIn, double nOut, const Vec2 &unit, double lambda, int maxOrder) {
    const auto propagates = [&](int j) { return NearDeltaPropagates(wi, nIn, nOut, unit * double(j), lambda); };
    // |a + j·b|² < nOut² with a = −nIn·wi.xy, b = unit·λ/2π: j within w of c = −a·b/|b|².
    const double s = lambda / (2 * Pi);
    const Vec2 a(-nIn * wi.x, -nIn * wi.y), b = unit * s;
    const double bb = b.x * b.x + b.y * b.y, ab = a.x * b.x + a.y * b.y, aa = a.x * a.x + a.y * a.y;
    OrderRange r;
    if (!(bb > 0)) {  // no shift: every order is the zeroth
        if (propagates(0)) r = {-maxOrder, maxOrder};
        return r;
    }
    const double c = -ab / bb, disc = ab * ab - bb * (aa - nOut * nOut);
    const double w = disc > 0 ? std::sqrt(disc) / bb : 0;
    const double lo = std::max(std::ceil(c - w), double(-maxOrder)), hi = std::min(std::floor(c + w), double(maxOrder));
    if (lo > hi) {
        // No integer inside the roots (or none in range): the nearest order in range, if rounding
        // lets it propagate, is the whole range.
        const int j = int(std::clamp(std::round(c), double(-maxOrder), double(maxOrder)));
        if (propagates(j)) r = {j, j};
        return r;
    }
    r = {int(lo), int(hi)};
    // The ends as the predicate has them (rounding at a root moves an end by at most one order).
    while (r.lo > -maxOrder && propagates(r.lo - 1)) --r.lo;
    while (r.lo <= r.hi && !propagates(r.lo)) ++r.lo;
    while (r.hi < maxOrder && propagates(r.hi + 1)) ++r.hi;
    while (r.hi >= r.lo && !propagates(r.hi)) --r.hi;
    return r;
}

}  // namespace phasor
