// SPDX-License-Identifier: Apache-2.0
// phasor — `grating`: a sinusoidal surface-relief diffraction grating on a smooth substrate
// (theory §0 D6, §4.2, §4.6; the CD, the rainbow boa's scales).
//
// Model. The surface is z(x_g) = (h/2)·sin(2π·x_g/Λ) along the grating vector ĝ (h peak-to-peak,
// grooves along TangentAtAngle(angle)). In the thin-phase (Raman–Nath) approximation the relief is
// a phase screen on the smooth substrate: the reflected field is the substrate's, times
// exp(i·a·sin(2π x_g/Λ)) = Σ_j J_j(a)·exp(i·j·2π x_g/Λ), so order j is a plane wave whose
// tangential wave vector is the specular one plus j·2π/Λ·ĝ (the vector grating equation,
// NearDeltaDirection; conical incidence included) with power efficiency
//     a_j = J_j(m)²·F,   m = |a| = k·h·cosθ_i,   k = 2π·n_in/λ                    (D6)
// where F is the substrate's unpolarised Fresnel reflectance at θ_i (SmoothSurface, its coating
// included). Σ_j J_j(m)² = 1 over all j ∈ ℤ. Orders with no propagating direction (evanescent)
// and orders beyond `max_order` are dropped; with `renormalize` (default) their share is given to
// the propagating orders in proportion, a_j = J_j²·F/Σ_prop J², so the grating reflects exactly F
// (a lossless substrate conserves energy, as a rigorous solution does); `renormalize = false` keeps
// the plain thin-phase values and loses the dropped share. Either way the dropped share is
// reported per side (GratingMaterial::Orders, grating.h).
// Transmission (`transmission = true`, a transparent substrate): the same screen in transmission
// has the phase amplitude a = k₀·(h/2)·(n_t·cosθ_t − n_i·cosθ_i) (the optical path through a
// bump of height z is n_t z cosθ_t instead of n_i z cosθ_i), and order j of the transmitted side
// carries J_j(a)²·T (T the substrate's transmittance at θ_i, renormalised over the propagating
// transmitted orders) with the (η_i/η_t)² radiance factor of dielectric.cpp. Light arriving from
// inside the substrate (wi.z < 0) is handled symmetrically (n_i = the substrate's index). Without
// `transmission` the grating is an opaque two-sided reflector, like `conductor`: wi.z < 0 is
// reflected on that side, and a dielectric substrate's transmitted share is absorbed.
//
// Whose incidence. The efficiencies belong to the light's incident direction: a lobe of a query
// at wi, pointing at wo (where the light comes from in a backward tracer), carries the efficiency
// of the order that takes light arriving from wo into wi — m, F and the renormalisation at wo's
// angle, not wi's (the order index is the same both ways: the tangential wave vector out is the one
// in plus j·2π/Λ·ĝ). So a pixel, camera or sensor, that sees a laser or the sun through order j
// receives exactly J_j(k·h·cosθ_source)²·F/Σ. The model is not reciprocal (m depends on the
// incidence only), so the lobes of one query need not sum to at most 1 (the light they gather comes
// from different directions); energy is conserved per incident direction: the orders of the light
// from one direction carry F (+ T) — ConservesEnergyPerIncidentDirection(), which the contract suite
// checks (harvey_shack normalises its halo the same way; docs/kernels.md).
//
// Validity. Thin-phase theory needs a shallow profile (h ≪ Λ, slopes πh/Λ ≪ 1) and is scalar.
// Against a rigorous FDTD reference of a sinusoidal metal grating, J_j(k·h·cosθ_i)² is within
// ≈ 2e-3 of the unpolarised efficiencies up to h/λ ≈ 0.18 at normal incidence and within
// ≈ 2.5e-2 up to h/λ ≈ 0.27 at 20° incidence; there the unrenormalised thin-phase sum over the
// propagating orders is 0.994 whereas the rigorous one is 1 (hence `renormalize`). Beyond
// h/λ ≈ 0.3, or for Λ ≲ λ (one or two propagating orders, resonances, Wood anomalies) and for
// polarisation-resolved work, use a rigorous method (RCWA, FDTD). Not reciprocal (m depends on θ_i
// only; the exact thin-phase argument is ½kh(cosθ_i + cosθ_o), which D6 trades for Σ_j J_j² = 1).
//
// Polarisation (EvalLobe): order j's Jones matrix is J_j(a)·√scale times the substrate's
// diag(r_s, r_p) at the source's θ (diag(t_s, t_p)·√(power factor)·(n_exit/n_source) when
// transmitted), so M00 = a_j.
// The rotation between the incident and the diffracted planes of incidence of conical orders is
// not modelled (the thin-phase screen is scalar). The relief has no coherence terms of its own: a
// partially coherent field is an incoherent mixture of plane waves, each diffracted with
// the same efficiencies, so only each order's angular spread depends on the coherence, and that is
// the generalized ray's own spread; an order needs mutually coherent periods by definition (if they
// were not, there would be no order at all, only a single period's diffraction, a continuous lobe).
// A reflected order over a coated substrate carries the coating's coherence terms (its incoherent
// response times the order's share, and its shear), which sample_solve weights by μ.
//
// Ray-optics limit (ScatterQuery::rayOptics: the `ray` integrator, GRs after an aperture): the
// grooves are not resolved and the kernel is its smooth substrate — the zeroth orders only, with
// J_0 = 1 (the h → 0 limit): reflection F, transmission T (of a coated substrate, the incoherent
// sum of its layers, as the smooth kernels). Chosen over J_0(m)²·F so that a `ray`
// render of a grating on a lossless substrate keeps the energy the wave-optical kernel
// (renormalised) reflects and `phasor compare` shows only what diffraction redistributes.
//
// Lobes (all listed near-delta lobes, listed once when the kernel is prepared for a query — a
// listing evaluates the orders of every lobe's source direction (which of them propagate follows
// from the query's own reflected orders, BackOrders: one rounding for all lobes, so the listing,
// LobeWeightAt and EvalLobe agree even at a Rayleigh anomaly); Sample picks one ∝ its radiance
// weight at the hero wavelength, SampleListedLobe): reflected order j has id j, transmitted order j id 1000 + j
// (GratingMaterial::TransmittedId). Orders j ≠ 0 are ScatterDispersive (their direction depends
// on λ); the zeroth reflected order is not, the zeroth transmitted order is when the substrate
// disperses. An order is listed if it propagates with non-zero weight at some carried wavelength;
// at a wavelength where it is evanescent its weight is 0 (and its direction that of the first
// wavelength where it carries light; if that is not the hero, its probability is 0).
//
// Parameters: `period` Λ and `angle` (the groove direction, radians from the first shading
// tangent dp/du, counter-clockwise about the normal) are constants or scalar textures (texture-
// driven pitch and orientation over a body, as on the boa's scales), `angle_texture` names an angle
// texture instead of `angle`; `height` h; `substrate` a conductor or dielectric (ReadSubstrate);
// `max_order`, `transmission`, `renormalize` as above.
//
// References: J. W. Goodman, Introduction to Fourier Optics, 3rd ed. (2005), §4.4.4 (thin
// sinusoidal phase grating, Jacobi–Anger expansion); E. G. Loewen & E. Popov, Diffraction
// Gratings and Applications (1997), ch. 2 (vector grating equation, conical diffraction);
// DLMF §10.12 (Σ J_n² = 1).
#include "materials/grating.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/diagnostics.h"
#include "core/numerics/bessel.h"
#include "core/render/lobe_average.h"
#include "core/render/registry.h"
#include "materials/smooth_surface.h"
#include "materials/validity.h"
#include "materials/smooth_kernel.h"

namespace phasor {

namespace {

/// J_j(a) for integer j and real a from J_|j|(|a|): J_{−n}(x) = (−1)ⁿJ_n(x) = J_n(−x) (DLMF 10.4.1).
double SignedBessel(const double *jAbs, int j, double a) {
    const int n = std::abs(j);
    const bool flip = (n & 1) && ((j < 0) != (a < 0));
    return flip ? -jAbs[n] : jAbs[n];
}

/// The orders worth considering at |a|/2 = half: up to the first n ≥ half with halfⁿ/n! < 1e-10
/// (past it |J_n(a)| ≤ halfⁿ/n!, DLMF 10.14.4, falls faster still), at most maxOrder. halfⁿ/n! <
/// 1e-10 ⟺ half < (1e-10·n!)^{1/n}, tabulated: compares, where a running product needs a division
/// per order.
int ConsideredOrders(double half, int maxOrder) {
    static const std::array<double, GratingSide::MaxOrder + 1> below = [] {
        std::array<double, GratingSide::MaxOrder + 1> b{};
        for (int n = 1; n <= GratingSide::MaxOrder; ++n) b[std::size_t(n)] = std::exp((std::log(1e-10) + std::lgamma(n + 1.0)) / n);
        return b;
    }();
    int n = 1;
    while (n < maxOrder && (n < half || !(half < below[std::size_t(n)]))) ++n;
    return std::min(n, maxOrder);
}

}  // namespace

GratingMaterial::GratingMaterial(FloatTexture period, double height, FloatTexture angle,
                                 std::shared_ptr<const SmoothKernel> substrate, int maxOrder, bool transmission,
                                 bool renormalize)
    : period_(std::move(period)),
      height_(height),
      angle_(std::move(angle)),
      substrate_(std::move(substrate)),
      surface_(&substrate_->Surface()),
      maxOrder_(maxOrder),
      transmission_(transmission),
      renormalize_(renormalize) {
    // Dispersive if the substrate's index varies over the band a path may carry (as dielectric.cpp).
    const double n0 = surface_->SubstrateIndex(550e-9).real();
    for (double l = 200e-9; l <= 3000e-9; l *= 1.005)
        if (std::abs(surface_->SubstrateIndex(l).real() - n0) > 1e-12 * n0) dispersive_ = true;
}

const Schema &GratingMaterial::GetSchema() {
    static const Schema s{
        "material",
        "grating",
        "sinusoidal surface-relief grating on a conductor or dielectric: thin-phase orders J_j(k·h·cosθ_i)²·F "
        "along the vector grating equation",
        {
            P::FloatTexture("period", "grating period Λ (a length, or a texture of a length for a varying pitch)",
                            Dim::Length())
                .Required()
                .Min(0, true),
            P::Length("height", "peak-to-peak height h of the sinusoidal profile (≤ period; thin-phase theory "
                                "holds for h/λ ≲ 0.2)")
                .Required()
                .Min(0),
            P::FloatTexture("angle",
                            "groove direction in the tangent plane, from the first shading tangent (dp/du) "
                            "counter-clockwise about the normal; the grating vector is perpendicular to it "
                            "(an angle or a texture of an angle)",
                            Dim::Angle())
                .Default(Value::Number(0, Dim::Angle())),
            P::FloatTexture("angle_texture", "@texture of an angle: the groove direction, instead of 'angle'",
                            Dim::Angle()),
            P::Ref("substrate", "material",
                   "the smooth surface under the relief: @conductor or @dielectric (its coating included); its "
                   "Fresnel reflectance F (transmittance T) multiplies the orders")
                .Required(),
            P::Integer("max_order", "highest order |j| listed (orders beyond it are dropped like evanescent ones)")
                .Default(Value::Integer(10))
                .Min(0)
                .Max(GratingSide::MaxOrder),
            P::Bool("transmission", "also list transmitted orders (a transparent substrate only); otherwise the "
                                    "grating is an opaque two-sided reflector")
                .Default(Value::Bool(false)),
            P::Bool("renormalize", "give the share of the evanescent (and beyond max_order) orders to the "
                                   "propagating ones in proportion, so the grating reflects exactly F; false: "
                                   "plain thin-phase efficiencies J_j²·F")
                .Default(Value::Bool(true)),
        }};
    return s;
}

std::unique_ptr<Material> GratingMaterial::Create(const ParamDict &d, BuildContext &ctx) {
    FloatTexture period = ctx.GetFloatTexture(d, "period");
    const double height = d.GetNumber("height");
    if (height > period.MinValue()) {
        const std::string what = period.IsConstant()
                                     ? "the period (" + period.ToString() + ")"
                                     : "the smallest period of texture " + d.GetValue("period").ToString() + " (" +
                                           Value::Number(period.MinValue(), Dim::Length()).ToString() + ")";
        throw Error(d.Loc("height"), "'height' (" + Value::Number(height, Dim::Length()).ToString() + ") exceeds " +
                                         what + ": a sinusoidal relief deeper than its period is far outside "
                                                "the thin-phase model (use height ≲ 0.2·λ)");
    }
    WarnIfBeyondVisible(d, ctx, "height", height, "the thin-phase model holds for h/λ ≲ 0.2 (docs/kernels.md, grating)",
                        5, "a deep grating needs a rigorous method (RCWA, FDTD)");
    if (d.Has("angle") && d.Has("angle_texture"))
        throw Error(d.Loc("angle_texture"), "give either 'angle' or 'angle_texture', not both");
    FloatTexture angle;
    if (d.Has("angle_texture")) {
        const Value &v = d.GetValue("angle_texture");
        if (v.kind != Value::Kind::Ref)
            throw Error(v.loc, "'angle_texture' expects @texture (a texture of an angle); got " + v.DescribeKind() +
                                   " (for a constant groove direction write 'angle = …')");
        angle = ctx.GetFloatTexture(d, "angle_texture");
    } else {
        angle = ctx.GetFloatTexture(d, "angle");
    }
    std::shared_ptr<const SmoothKernel> substrate = ReadSubstrate(d, ctx);
    const std::string name = "'" + d.GetValue("substrate").ToString() + "'";
    const bool transmission = d.GetBool("transmission");
    if (transmission) {
        for (double l = 360e-9; l <= 1000e-9; l += 5e-9) {
            if (!substrate->Surface().Absorbing(l)) continue;
            const Complex n = substrate->Surface().SubstrateIndex(l);
            std::ostringstream os;
            os << "'transmission = true' needs a transparent substrate (a dielectric), but " << name << " absorbs: n + iκ = "
               << n.real() << (n.imag() < 0 ? "" : "+") << n.imag() << "i at " << std::lround(l * 1e9) << " nm";
            throw Error(d.Loc("transmission"), os.str());
        }
    }
    return std::make_unique<GratingMaterial>(std::move(period), height, std::move(angle), std::move(substrate),
                                             d.GetInt("max_order"), transmission, d.GetBool("renormalize"));
}

std::vector<ParamDict> GratingMaterial::TestPresets() {
    const auto um = [](double v) { return Value::Number(v * 1e-6, Dim::Length()); };
    std::vector<ParamDict> p(4);
    // p[0]: a CD-like reflection grating on gold.
    p[0].Set("substrate", Value::Ref("contract_gold"))
        .Set("period", um(1.6))
        .Set("height", um(0.1))
        .Set("max_order", Value::Integer(5));
    // p[1]: texture-driven pitch (1.2–2.4 µm along u) and groove direction (0–120° along v).
    p[1].Set("substrate", Value::Ref("contract_gold"))
        .Set("period", Value::Ref("contract_pitch"))
        .Set("angle", Value::Ref("contract_groove_angle"))
        .Set("height", um(0.15))
        .Set("max_order", Value::Integer(8));
    // p[2]: transmission into a dispersive glass (BK7), grooves at 30°.
    p[2].Set("substrate", Value::Ref("contract_bk7"))
        .Set("transmission", Value::Bool(true))
        .Set("period", um(2))
        .Set("height", um(0.25))
        .Set("angle", Value::Number(30 * Pi / 180, Dim::Angle()));
    // p[3]: a long period with many propagating orders, plain (unrenormalised) efficiencies, the
    // groove direction from angle_texture.
    p[3].Set("substrate", Value::Ref("contract_glass"))
        .Set("period", um(20))
        .Set("height", um(0.4))
        .Set("max_order", Value::Integer(15))
        .Set("renormalize", Value::Bool(false))
        .Set("angle_texture", Value::Ref("contract_groove_angle"));
    return p;
}

Vec3 GratingMaterial::GratingVector(const ScatterQuery &q) const {
    const Vec3 t = TangentAtAngle(angle_.Eval(q.tex));
    return {-t.y, t.x, 0};  // the groove direction rotated by +90° about the normal
}

GratingMaterial::Site GratingMaterial::SiteOf(const ScatterQuery &q, double *thickness) const {
    Site site;
    site.period = period_.Eval(q.tex);
    site.g = GratingVector(q);
    surface_->Thicknesses(q.tex, thickness);
    site.thickness = thickness;
    for (int i = 0; i < q.wl->Count(); ++i) site.substrate[std::size_t(i)] = surface_->SubstrateIndex(q.wl->lambda[i]);
    return site;
}

GratingOrders GratingMaterial::Orders(const ScatterQuery &q, int i) const {
    std::vector<double> thickness(std::size_t(surface_->LayerCount()));
    GratingOrders o;
    FillOrders(q, i, SiteOf(q, thickness.data()), SideReflected | SideTransmitted, true, &o);
    return o;
}

void GratingMaterial::FillOrders(const ScatterQuery &q, int i, const Site &site, unsigned sides, bool directions,
                                 GratingOrders *out, int only, bool energyOnly, const OrderRange *back) const {
    // *out may hold an earlier call's orders: every field read below is set (without directions,
    // the other orders' amplitude[] and propagating[] keep their earlier values: see grating.h).
    GratingOrders &o = *out;
    o.reflected.present = o.transmitted.present = false;
    o.reflected.maxOrder = o.transmitted.maxOrder = 0;
    const double lambda = q.wl->lambda[i];
    o.period = site.period;
    o.vector = Vec2(site.g.x, site.g.y);
    o.groove = Vec2(site.g.y, -site.g.x);
    o.fromInside = transmission_ && q.wi.z < 0;
    const Complex substrate = site.substrate[std::size_t(i)];
    const double nSub = substrate.real();
    const double nI = o.fromInside ? nSub : q.etaOutside, nT = o.fromInside ? q.etaOutside : nSub;
    o.reflected.nIn = o.reflected.nOut = o.transmitted.nIn = nI;
    o.transmitted.nOut = nT;
    if (q.wi.z == 0 || !(o.period > 0)) return;
    const double cosI = std::abs(q.wi.z);
    // The ray-optics limit of a coated substrate is the incoherent sum of its layers (as the smooth
    // kernels: SmoothKernel::Evaluate).
    o.incoherent = q.rayOptics && surface_->LayerCount() > 0;
    if (!energyOnly) o.surface = surface_->Response(lambda, q.etaOutside, cosI, o.fromInside, site.thickness, substrate);
    double fR = 0, fT = 0;  // F of the reflected and the transmitted side: the substrate's R and T at θ_i
    if (o.incoherent) {
        o.layers = surface_->IncoherentResponse(lambda, q.etaOutside, cosI, o.fromInside, site.thickness, substrate);
        fR = o.layers.R();
        fT = o.layers.T();
    } else if (energyOnly) {  // the sides asked for, their power alone
        if (sides & SideReflected)
            fR = surface_->Power(lambda, q.etaOutside, cosI, o.fromInside, site.thickness, substrate, false);
        if (transmission_ && (sides & SideTransmitted))
            fT = surface_->Power(lambda, q.etaOutside, cosI, o.fromInside, site.thickness, substrate, true);
    } else {
        fR = o.surface.R();
        fT = o.surface.T();
    }
    // Ray-optics limit: the smooth substrate (zeroth orders, J_0(0) = 1).
    const int maxOrder = q.rayOptics ? 0 : maxOrder_;
    const double h = q.rayOptics ? 0 : height_, k0 = 2 * Pi / lambda;
    const Vec2 unitShift = site.UnitShift();
    auto fill = [&](GratingSide &s, bool transmitted, double a, double f) {
        s.present = true;
        s.propagatingSum = s.evanescent = 0;
        s.modulation = a;
        s.substrate = f;
        // Orders whose efficiency is below 1e-20 are not considered (they count as truncated,
        // ConsideredOrders): at m ≈ 1 this lists ~10 orders instead of 2·max_order + 1.
        const int used = ConsideredOrders(std::abs(a) / 2, maxOrder);
        s.maxOrder = used;
        double jAbs[GratingSide::MaxOrder + 1];
        if (!directions) {
            // Which orders propagate is an interval found at once; the sum over it, and order `only`
            // (J_n up to the largest |n| of these, not to `used`).
            if (!back) throw Error("GratingMaterial::FillOrders without directions needs `back` (a kernel bug)");
            const OrderRange range{std::max(only - back->hi, -used), std::min(only - back->lo, used)};
            const bool onlyUsed = std::abs(only) <= used;
            int top = onlyUsed ? std::abs(only) : -1;  // -1: no J_n needed
            if (range.lo <= range.hi) top = std::max({top, std::abs(range.lo), std::abs(range.hi)});
            BesselJSequence(std::abs(a), top, jAbs);
            for (int j = range.lo; j <= range.hi; ++j) s.propagatingSum += Sqr(SignedBessel(jAbs, j, a));
            if (onlyUsed) {
                const std::size_t k = std::size_t(only + GratingSide::MaxOrder);
                s.amplitude[k] = SignedBessel(jAbs, only, a);
                s.propagating[k] = range.Contains(only);
            }
        } else {
            BesselJSequence(std::abs(a), used, jAbs);
            double total = 0;
            for (int j = -used; j <= used; ++j) {
                const std::size_t k = std::size_t(j + GratingSide::MaxOrder);
                s.amplitude[k] = SignedBessel(jAbs, j, a);
                const double e = s.amplitude[k] * s.amplitude[k];
                total += e;
                s.propagating[k] =
                    NearDeltaDirection(q.wi, s.nIn, s.nOut, unitShift * double(j), lambda, transmitted, &s.wo[k]);
                (s.propagating[k] ? s.propagatingSum : s.evanescent) += e;
            }
            s.truncated = std::max(0.0, 1 - total);
        }
        s.scale = !renormalize_ ? 1.0 : (s.propagatingSum > 0 ? 1 / s.propagatingSum : 0.0);
    };
    // Reflection: the phase 2·k·z·cosθ_i of the double pass, a = −k₀·n_i·h·cosθ_i (D6).
    if (sides & SideReflected) fill(o.reflected, false, -k0 * nI * h * cosI, fR);
    if (transmission_ && (sides & SideTransmitted)) {
        // Transmission: a = k₀·(h/2)·(n_t cosθ_t − n_i cosθ_i) with the zeroth order's θ_t.
        const double sin2T = (nI / nT) * (nI / nT) * (1 - cosI * cosI);
        if (sin2T < 1 && fT > 0) fill(o.transmitted, true, k0 * h / 2 * (nT * std::sqrt(1 - sin2T) - nI * cosI), fT);
    }
}

double GratingMaterial::SourceEfficiency(const ScatterQuery &q, int i, const Site &site, const Vec3 &source,
                                         bool transmitted, int j, const OrderRange &back, GratingOrders *orders,
                                         bool energyOnly) const {
    ScatterQuery from = q;
    from.wi = source;  // the light arrives from `source`: its order j is the lobe's weight towards q.wi
    FillOrders(from, i, site, transmitted ? SideTransmitted : SideReflected, false, orders, j, energyOnly, &back);
    return (transmitted ? orders->transmitted : orders->reflected).Energy(j);
}

/// The kernel at one hit: its site (Λ, ĝ, the substrate's layers and index) and the listed orders.
class GratingMaterial::Prepared final : public PreparedKernel {
  public:
    Prepared(const GratingMaterial &m, const ScatterQuery &q, ScratchBuffer &scratch)
        : PreparedKernel(q), m_(&m), site_(m.SiteOf(q, scratch.Room<double>(std::size_t(m.surface_->LayerCount())))) {
        caps_ = CapNearDelta;
        if (q.wi.z == 0) return;
        const int maxOrder = q.rayOptics ? 0 : m.maxOrder_;
        const Vec2 unitShift = site_.UnitShift();
        for (int i = 0; i < q.wl->Count(); ++i)
            back_[std::size_t(i)] = BackOrders(q.wi, Indices(q.wi, i).first, unitShift, q.wl->lambda[i]);
        LobeList lobes(scratch, (m.transmission_ ? 2 : 1) * (2 * maxOrder + 1));
        List(q, maxOrder, lobes);
        lobes_ = lobes.Lobes();
    }

    std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override;
    double AngularBandwidth(double kappaMax) const override;
    /// One order's weight (Order) without listing the others: D15's nodes ask for one lobe.
    std::optional<SampledSpectrum> LobeWeightAt(int id, const Vec3 &wiPrime, unsigned slots) const override;

  private:
    void List(const ScatterQuery &q, int maxOrder, LobeList &out) const;
    /// Order j of one side for light leaving along wi (the query's, or a D15 node's wi′ at the same
    /// hit), per carried wavelength slot i with bit i set in `slots` (the others untouched): its direction (the vector grating equation from wi) in wo and
    /// its listed weight — the efficiency of order j for light arriving from that direction (see the
    /// file comment), times (η_i/η_t)² on transmission — in weight (0 where evanescent). Returns the
    /// first wavelength where it carries light, or −1. `scratch` holds the source's orders.
    int Order(const Vec3 &wi, bool transmitted, int j, unsigned slots, std::array<Vec3, NumWavelengths> &wo,
              SampledSpectrum &weight, GratingOrders &scratch) const;
    /// Wavelength slot i's BackOrders at wi (back_'s at the query's own wi).
    OrderRange BackAt(const Vec3 &wi, int i) const {
        if (wi == q_.wi) return back_[std::size_t(i)];
        return BackOrders(wi, Indices(wi, i).first, site_.UnitShift(), q_.wl->lambda[i]);
    }
    /// Order j's direction at carried wavelength slot i for light leaving along wi (the vector
    /// grating equation, shift j·2π/Λ·ĝ as List's l.shift); false where it is evanescent.
    bool OrderDirection(const Vec3 &wi, bool transmitted, int j, int i, Vec3 *wo) const {
        const auto [nWi, nFar] = Indices(wi, i);
        const Vec2 shift = site_.UnitShift() * double(j);
        return NearDeltaDirection(wi, nWi, transmitted ? nFar : nWi, shift, q_.wl->lambda[i], transmitted, wo);
    }
    /// The indices of wi's medium and of the far side (the substrate, or the outside when wi is
    /// inside) at carried wavelength slot i.
    std::pair<double, double> Indices(const Vec3 &wi, int i) const {
        const double nSub = site_.substrate[std::size_t(i)].real();
        const bool inside = m_->transmission_ && wi.z < 0;
        return {inside ? nSub : q_.etaOutside, inside ? q_.etaOutside : nSub};
    }

    const GratingMaterial *m_;
    Site site_;
    std::array<OrderRange, NumWavelengths> back_{};  // BackOrders at q.wi per carried wavelength slot
};

const PreparedKernel &GratingMaterial::Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const {
    return *scratch.New<Prepared>(*this, q, scratch);
}

double GratingMaterial::Prepared::AngularBandwidth(double kappaMax) const {
    // J_j(m)² oscillates twice per π of m, and m = k₀h·√(n² − κ²) (reflection; transmission: half of
    // the difference of two such roots) changes by k₀h·κ/√(n² − κ²) per unit κ; plus the substrate's.
    const GratingMaterial &m = *m_;
    const ScatterQuery &q = q_;
    const double lambda = q.wl->lambda[0], k0 = 2 * Pi / lambda;
    const bool inside = m.transmission_ && q.wi.z < 0;
    const double nSub = site_.substrate[0].real();
    const double nIn = inside ? nSub : q.etaOutside;
    const double root = std::sqrt(std::max(nIn * nIn - kappaMax * kappaMax, 1e-6));
    double relief = 2 * k0 * m.height_ * kappaMax / root;
    if (m.transmission_)
        relief += k0 * m.height_ * kappaMax / std::sqrt(std::max(nSub * nSub - kappaMax * kappaMax, 1e-6));
    return HeroToShortest(*q.wl) * (relief + m.surface_->Bandwidth(lambda, q.etaOutside, kappaMax, inside,
                                                                      site_.thickness, site_.substrate[0], LobeAverageTolerance));
}

void GratingMaterial::Prepared::List(const ScatterQuery &q, int maxOrder, LobeList &out) const {
    const GratingMaterial &m = *m_;
    const int count = q.wl->Count();
    const Vec2 unitShift = site_.UnitShift();
    GratingOrders scratch;
    for (const bool transmitted : {false, true}) {
        if (transmitted && !m.transmission_) break;
        // The orders that propagate at each wavelength (an interval, as NearDeltaDirection has them):
        // Order is asked only for those (most of the 2·max_order + 1 are evanescent at a CD's pitch).
        std::array<OrderRange, NumWavelengths> range{};
        int lo = maxOrder + 1, hi = -maxOrder - 1;
        for (int i = 0; i < count; ++i) {
            const auto [nWi, nFar] = Indices(q.wi, i);
            OrderRange &r = range[std::size_t(i)];
            if (!transmitted) {  // BackOrders' range within ±max_order
                const OrderRange &b = back_[std::size_t(i)];
                r = {std::max(b.lo, -maxOrder), std::min(b.hi, maxOrder)};
            } else {
                r = PropagatingOrders(q.wi, nWi, nFar, unitShift, q.wl->lambda[i], maxOrder);
            }
            if (r.lo <= r.hi) {
                lo = std::min(lo, r.lo);
                hi = std::max(hi, r.hi);
            }
        }
        for (int j = lo; j <= hi; ++j) {
            unsigned slots = 0;
            for (int i = 0; i < count; ++i) slots |= range[std::size_t(i)].Contains(j) ? 1u << i : 0u;
            std::array<Vec3, NumWavelengths> wo{};
            SampledSpectrum weight;
            // The hero's efficiency now (Sample picks a lobe by it); where the hero carries light,
            // the companions' only when a caller reads them (NearDeltaLobe::DeferWeights: most
            // lobes reach no light, and their companions' efficiencies would be computed for
            // nothing). Their directions are the grating equation's, as Order has them.
            unsigned deferred = 0;
            int lit = Order(q.wi, transmitted, j, slots & 1u, wo, weight, scratch);
            if (lit == 0) {
                for (int i = 1; i < count; ++i)
                    if (((slots >> i) & 1u) && OrderDirection(q.wi, transmitted, j, i, &wo[std::size_t(i)])) deferred |= 1u << i;
            } else {
                lit = Order(q.wi, transmitted, j, slots & ~1u, wo, weight, scratch);
            }
            if (lit < 0) continue;
            NearDeltaLobe &l = out.Add();
            l.id = (transmitted ? TransmittedId : 0) + j;
            l.flags = ScatterNearDelta | (transmitted ? ScatterTransmission : ScatterReflection) |
                      (j != 0 || (transmitted && m.dispersive_) ? ScatterDispersive : 0u);
            l.shift = unitShift * double(j);
            l.SetWeight(weight);
            l.DeferWeights(deferred, *this);
            for (int i = 0; i < count; ++i) {
                const std::size_t s = std::size_t(i);
                const auto [nWi, nFar] = Indices(q.wi, i);
                l.nIn[s] = nWi;
                l.nOut[s] = transmitted ? nFar : nWi;
                l.wo[s] = weight[i] > 0 || ((deferred >> i) & 1u) ? wo[s] : wo[std::size_t(lit)];
            }
        }
    }
    // Sample picks a lobe ∝ its weight at the hero (then a_j/p_j is the same for every lobe);
    // if the hero carries nothing, ∝ the weight summed over the carried wavelengths (then no
    // weight was deferred: only lobes whose hero carries light defer theirs).
    double hero = 0;
    for (int k = 0; k < out.Count(); ++k) hero += out[k].Weight(1u)[0];
    double all = 0;
    if (!(hero > 0))
        for (int k = 0; k < out.Count(); ++k)
            for (int i = 0; i < count; ++i) all += out[k].Weight()[i];
    for (int k = 0; k < out.Count(); ++k) {
        NearDeltaLobe &l = out[k];
        double w = 0;
        if (hero > 0) w = l.Weight(1u)[0];
        else
            for (int i = 0; i < count; ++i) w += l.Weight()[i];
        l.prob = hero > 0 ? w / hero : w / all;
    }
}

int GratingMaterial::Prepared::Order(const Vec3 &wi, bool transmitted, int j, unsigned slots,
                                     std::array<Vec3, NumWavelengths> &wo, SampledSpectrum &weight,
                                     GratingOrders &scratch) const {
    const ScatterQuery &q = q_;
    int lit = -1;
    for (int i = 0; i < q.wl->Count(); ++i) {
        if (!((slots >> i) & 1u)) continue;
        const std::size_t s = std::size_t(i);
        if (!OrderDirection(wi, transmitted, j, i, &wo[s])) continue;
        const auto [nWi, nFar] = Indices(wi, i);
        const double nOut = transmitted ? nFar : nWi;
        const OrderRange back = BackAt(wi, i);
        const double energy = m_->SourceEfficiency(q, i, site_, wo[s], transmitted, j, back, &scratch, true);
        const double ratio = nWi / nOut;
        weight[i] = transmitted ? energy * ratio * ratio : energy;  // (η_i/η_t)²: radiance
        if (energy > 0 && lit < 0) lit = i;
    }
    return lit;
}

std::optional<SampledSpectrum> GratingMaterial::Prepared::LobeWeightAt(int id, const Vec3 &wiPrime, unsigned slots) const {
    const bool transmitted = id >= TransmittedId / 2;
    const int j = transmitted ? id - TransmittedId : id;
    const int maxOrder = q_.rayOptics ? 0 : m_->maxOrder_;
    SampledSpectrum weight;
    if (wiPrime.z == 0 || std::abs(j) > maxOrder || (transmitted && !m_->transmission_)) return weight;
    std::array<Vec3, NumWavelengths> wo{};
    GratingOrders scratch;
    Order(wiPrime, transmitted, j, slots, wo, weight, scratch);
    return weight;
}

bool GratingMaterial::HasCoherenceTerms() const { return surface_->LayerCount() > 0; }

std::optional<double> GratingMaterial::ReferenceAngle(const TextureEvalContext &tex) const {
    return angle_.Eval(tex) + Pi / 2;  // as GratingVector
}

std::string GratingMaterial::LobeName(int id) const {
    // (reflected orders stay far below TransmittedId / 2 in magnitude: Capacity lobes in all)
    return std::to_string(id >= TransmittedId / 2 ? id - TransmittedId : id);
}

std::optional<LobeResponse> GratingMaterial::Prepared::EvalLobe(int lobe, const Vec3 &wo) const {
    const ScatterQuery &q = q_;
    const SmoothSurface &surface = *m_->surface_;
    const NearDeltaLobe *l = FindLobe(lobe);
    if (!l || !SameDirection(wo, l->wo[0])) return std::nullopt;
    const bool transmitted = (l->flags & ScatterTransmission) != 0;
    const int j = transmitted ? lobe - TransmittedId : lobe;
    LobeResponse r;
    // In the ray-optics limit a coated substrate answers with its incoherent Mueller matrix, no Jones.
    r.hasJones = !q.rayOptics || surface.LayerCount() == 0;
    // A reflected order over a coated substrate carries the coating's coherence terms (its incoherent
    // response at the source's angle times the order's share, and its shear): sample_solve weights
    // the coating's interference by the light's coherence. The relief itself has none (see above).
    r.coherence.any = !transmitted && surface.LayerCount() > 0;
    for (int i = 0; i < q.wl->Count(); ++i) {
        if (l->Weight(1u << i)[i] == 0) continue;  // evanescent at this wavelength: no response
        // The orders of the light arriving along the lobe (its source direction at this wavelength).
        GratingOrders o;
        m_->SourceEfficiency(q, i, site_, l->wo[std::size_t(i)], transmitted, j, back_[std::size_t(i)], &o);
        const GratingSide &s = transmitted ? o.transmitted : o.reflected;
        const std::size_t k = std::size_t(j + GratingSide::MaxOrder);
        // Order j's field relative to the substrate's: J_j(a)·√scale.
        const double amp = s.amplitude[k] * std::sqrt(s.scale);
        Jones base;
        if (!transmitted) {
            base = Jones::Diagonal(o.surface.rs, o.surface.rp);
        } else {
            // diag(t_s, t_p) with each component's power factor (|t'|² = T_s, T_p) and the
            // radiance factor n_exit/n_source (the light leaves into wi's medium), as dielectric.cpp.
            auto powered = [](Complex t, double power) {
                return std::abs(t) > 0 ? t * (std::sqrt(power) / std::abs(t)) : Complex(0, 0);
            };
            base = Jones::Diagonal(powered(o.surface.ts, o.surface.Ts), powered(o.surface.tp, o.surface.Tp)) *
                   Complex(s.nOut / s.nIn, 0);
        }
        if (o.incoherent) {
            const double radiance = transmitted ? (s.nOut / s.nIn) * (s.nOut / s.nIn) : 1.0;
            r.mueller[i] = (transmitted ? Mueller::FromDiagonalSums(o.layers.Ts, o.layers.Tp, o.layers.Tsp)
                                        : Mueller::FromDiagonalSums(o.layers.Rs, o.layers.Rp, o.layers.Rsp)) *
                           (amp * amp * radiance);
        } else {
            r.jones[i] = base * Complex(amp, 0);
            r.mueller[i] = Mueller::FromJones(r.jones[i]);
        }
        if (r.coherence.any) {
            const Vec3 &source = l->wo[std::size_t(i)];
            const IncoherentStackResponse n = surface.IncoherentResponse(
                q.wl->lambda[i], q.etaOutside, std::abs(source.z), o.fromInside, site_.thickness, site_.substrate[std::size_t(i)]);
            r.coherence.incoherent[i] = Mueller::FromDiagonalSums(n.Rs, n.Rp, n.Rsp) * (amp * amp);
            r.coherence.shear[i] =
                surface.ShearVector(q.wl->lambda[i], q.etaOutside, source, o.fromInside, site_.thickness);
        }
    }
    return r;
}

std::string GratingMaterial::ToString() const {
    std::ostringstream os;
    os << "GratingMaterial[ period = " << period_.ToString() << ", height = " << height_ << " m, angle = "
       << angle_.ToString() << ", max_order = " << maxOrder_ << ", transmission = " << (transmission_ ? "true" : "false")
       << ", renormalize = " << (renormalize_ ? "true" : "false") << ", substrate = { " << surface_->ToString()
       << " } ]";
    return os.str();
}

PHASOR_EXPORT_PLUGIN(Material, GratingMaterial)

}  // namespace phasor
