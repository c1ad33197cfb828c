// SPDX-License-Identifier: Apache-2.0
// phasor — `grating`: a sinusoidal surface-relief diffraction grating (theory §0 D6, §4.2, §4.6).
// The kernel and its physics are described in grating.cpp; this header declares what its tests
// (and tools such as `phasor probe`) read beyond the Material interface: the per-order
// efficiencies before and after renormalisation and the share of the energy that the listed
// orders do not carry (GratingMaterial::Orders).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/params/dict.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/render/texture.h"
#include "materials/layer_stack.h"

namespace phasor {

class SmoothKernel;
class SmoothSurface;

/// The orders of one side of the grating (reflected or transmitted) at one wavelength, for one
/// incident direction. Indices of the arrays are j + MaxOrder for order j ∈ [−maxOrder, maxOrder].
struct GratingSide {
    static constexpr int MaxOrder = 15;  // the schema's bound on `max_order`
    static constexpr int Slots = 2 * MaxOrder + 1;

    bool present = false;  // false: this side has no lobes (reflected: grazing wi; transmitted:
                           // `transmission` off, or no transmitted power, e.g. total internal reflection)
    /// Orders −maxOrder…maxOrder were considered: `max_order`, or fewer where the rest have
    /// J_j(a)² < 1e-20 (0 in the ray-optics limit). The others count as `truncated`.
    int maxOrder = 0;
    double nIn = 1, nOut = 1;  // absolute real indices of wi's and wo's media
    /// Signed phase amplitude a [rad] of the thin-phase screen: the field of order j is J_j(a)
    /// times the substrate's. Reflection: a = −k₀·n_in·h·cosθ_i (|a| = m of D6); transmission:
    /// a = k₀·(h/2)·(n_out·cosθ_t − n_in·cosθ_i).
    double modulation = 0;
    /// F: the smooth substrate's unpolarised reflectance R (reflected side) or transmittance T
    /// (transmitted side, a power ratio, no radiance factor) at θ_i, coating included.
    double substrate = 0;
    std::array<double, Slots> amplitude{};  // J_j(a)
    std::array<bool, Slots> propagating{};  // the order has a propagating direction
    std::array<Vec3, Slots> wo{};            // its direction (local frame), where propagating
    double propagatingSum = 0;  // Σ J_j² over the propagating orders |j| ≤ maxOrder
    double evanescent = 0;      // Σ J_j² over the evanescent orders |j| ≤ maxOrder
    double truncated = 0;       // 1 − Σ_{|j| ≤ maxOrder} J_j²: the orders beyond `max_order` (or negligible)
    /// The factor on every efficiency: 1/propagatingSum with `renormalize` (the dropped share is
    /// redistributed over the propagating orders in proportion), 1 without.
    double scale = 1;

    /// The share of the incident energy (relative to F) the listed orders do not carry before
    /// renormalisation: evanescent + truncated = 1 − propagatingSum.
    double Dropped() const { return 1 - propagatingSum; }
    /// J_j(a)²: order j's plain thin-phase efficiency (before F and renormalisation), propagating
    /// or not; 0 for |j| > maxOrder.
    double Efficiency(int j) const {
        if (!present || j < -maxOrder || j > maxOrder) return 0;
        const double a = amplitude[std::size_t(j + MaxOrder)];
        return a * a;
    }
    /// Order j's energy efficiency a_j = J_j²·scale·F (0 if evanescent or |j| > maxOrder). The
    /// listed lobe weight is this on the reflected side and this·(n_in/n_out)² (radiance) on the
    /// transmitted side.
    double Energy(int j) const {
        if (!present || j < -maxOrder || j > maxOrder || !propagating[std::size_t(j + MaxOrder)]) return 0;
        return Efficiency(j) * scale * substrate;
    }
};

/// Both sides at one wavelength (GratingMaterial::Orders).
struct GratingOrders {
    GratingSide reflected, transmitted;
    double period = 0;  // Λ at the hit [m]
    Vec2 groove;        // unit groove direction, local x, y: TangentAtAngle(angle)
    Vec2 vector;        // unit grating vector ĝ ⟂ grooves, local x, y (groove rotated by +90°)
    bool fromInside = false;  // wi lies in the substrate (transmission gratings with wi.z < 0)
    StackResponse surface;    // the substrate's plane-wave response at θ_i (r, t, R, T per polarisation)
    /// The coated substrate's incoherent response at θ_i (its layers' interference averaged out),
    /// set in the ray-optics limit of a coated substrate (`incoherent`), where it replaces `surface`.
    bool incoherent = false;
    IncoherentStackResponse layers;
};

/// The `grating` kernel (see grating.cpp for the physics and the parameters).
class GratingMaterial final : public Material, public ReferenceDirection {
  public:
    /// Lobe ids: reflected order j has id j; transmitted order j has id TransmittedId + j.
    static constexpr int TransmittedId = 1000;

    GratingMaterial(FloatTexture period, double height, FloatTexture angle,
                    std::shared_ptr<const SmoothKernel> substrate, int maxOrder, bool transmission, bool renormalize);

    static const Schema &GetSchema();
    static std::unique_ptr<Material> Create(const ParamDict &dict, BuildContext &ctx);
    static std::vector<ParamDict> TestPresets();

    /// The orders of a plane wave arriving from q.wi (physical incidence) at carried wavelength
    /// slot i (q.wl->lambda[i]): their directions, plain thin-phase amplitudes, which propagate,
    /// the renormalisation and the dropped share per side. Order j's energy (GratingSide::Energy)
    /// is what lobe j of a query at that order's direction lists towards q.wi (at a Rayleigh
    /// anomaly, an order grazing, up to which side of the rounding each puts it: the listing
    /// decides from the query's direction, BackOrders, this from q.wi's). In the ray-optics
    /// limit (q.rayOptics) the zeroth orders only, with J_0 = 1.
    GratingOrders Orders(const ScatterQuery &q, int i) const;
    /// The unit grating vector ĝ at the query's hit (local frame, z = 0): the direction in which
    /// order +1 shifts the tangential wave vector, by 2π/Λ.
    Vec3 GratingVector(const ScatterQuery &q) const;

    /// Lists the orders (see grating.cpp, "Lobes"); EvalLobe gives an order's Jones matrix;
    /// AngularBandwidth: the rate of J_j(m(κ))² (twice that of m = k₀h·√(n² − κ²)) plus the
    /// substrate's (theory §0 D15). The renormalisation over the propagating orders jumps where an
    /// order appears; there the average converges only algebraically.
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override;
    /// Reflected orders carry a coated substrate's coherence terms.
    bool HasCoherenceTerms() const override;
    /// The grating vector ĝ: the groove direction (`angle`) + 90°.
    std::optional<double> ReferenceAngle(const TextureEvalContext &tex) const override;
    /// The diffraction order j of a reflected (id j) or transmitted (id TransmittedId + j) lobe.
    std::string LobeName(int id) const override;
    /// Not reciprocal: m = k·h·cosθ_i depends on the light's incident direction only (D6), and the
    /// renormalisation on that direction's set of propagating orders.
    bool IsReciprocal() const override { return false; }
    /// The orders of light arriving from one direction carry F (+ T): energy is conserved per
    /// incident direction, not per query (see grating.cpp).
    bool ConservesEnergyPerIncidentDirection() const override { return true; }
    std::string ToString() const override;

  private:
    class Prepared;
    static constexpr unsigned SideReflected = 1, SideTransmitted = 2;
    /// What the orders at one hit depend on besides the incident direction: the period Λ [m], the
    /// unit grating vector ĝ (local), the substrate coating's layer thicknesses (SmoothSurface::
    /// Thicknesses; none for a bare substrate) and the substrate's index per carried wavelength.
    struct Site {
        double period = 0;
        Vec3 g;
        const double *thickness = nullptr;
        std::array<Complex, NumWavelengths> substrate{};
        /// ĝ·2π/Λ [1/m] (local, in the tangent plane): the tangential wavevector shift of order 1.
        Vec2 UnitShift() const { return Vec2(g.x, g.y) * (2 * Pi / period); }
    };
    /// The site of the query's hit; `thickness` must hold LayerCount() values (filled here).
    Site SiteOf(const ScatterQuery &q, double *thickness) const;
    /// Orders() into *o for the sides asked for, at the site; with `directions`, every order's
    /// direction too (GratingSide::wo). Without, for one order `only` (an efficiency needs its
    /// amplitude and which orders propagate): amplitude[] and propagating[] hold order `only` alone,
    /// propagatingSum and scale are complete, evanescent is 0 and truncated is left as it was. With
    /// `energyOnly` (no directions) only what GratingSide::Energy reads: the substrate's R or T of
    /// the sides asked for (SmoothSurface::Power), `surface` is not set. Without directions (one
    /// side, from SourceEfficiency) `back` gives which orders propagate: see there.
    void FillOrders(const ScatterQuery &q, int i, const Site &site, unsigned sides, bool directions,
                    GratingOrders *o, int only = 0, bool energyOnly = false, const OrderRange *back = nullptr) const;
    /// The energy efficiency of order j (reflected or transmitted) at wavelength slot i for light
    /// arriving from `source` (a lobe's direction): what that lobe of the query at q.wi carries.
    /// `back` is BackOrders(q.wi, …) at slot i: the source's propagating orders are j minus those
    /// (its order m leaves along q.wi's tangential wavevector shifted by m − j) — one rounding for
    /// every lobe of the query, so the listing and EvalLobe agree even where an order grazes.
    /// The source's orders are left in *orders for order j (FillOrders without directions; with
    /// `energyOnly`, without the substrate's amplitudes: the efficiency alone).
    double SourceEfficiency(const ScatterQuery &q, int i, const Site &site, const Vec3 &source, bool transmitted,
                            int j, const OrderRange &back, GratingOrders *orders, bool energyOnly = false) const;
    /// The query's reflected orders p at wi that propagate (PropagatingOrders over ±2·MaxOrder,
    /// wi's medium on both sides). The light that leaves along wi through order j comes from a
    /// source whose own orders m propagate exactly where j − m is such a p: its order m leaves along
    /// wi's tangential wavevector shifted by (m − j)·2π/Λ·ĝ into wi's medium (where a reflected lobe's
    /// source lies, and where a transmitted lobe's source sends its transmitted orders).
    static OrderRange BackOrders(const Vec3 &wi, double nWi, const Vec2 &unitShift, double lambda) {
        return PropagatingOrders(wi, nWi, nWi, unitShift, lambda, 2 * GratingSide::MaxOrder);
    }

    FloatTexture period_;  // Λ [m], > 0
    double height_ = 0;    // h, peak-to-peak [m]
    FloatTexture angle_;   // groove direction [rad] from the first shading tangent
    std::shared_ptr<const SmoothKernel> substrate_;
    const SmoothSurface *surface_ = nullptr;  // &substrate_->Surface()
    int maxOrder_ = 0;
    bool transmission_ = false, renormalize_ = true;
    bool dispersive_ = false;  // the substrate's index varies with λ (the transmitted zeroth order disperses)
};

}  // namespace phasor
