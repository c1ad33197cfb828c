// SPDX-License-Identifier: Apache-2.0
// phasor — `aperture`: an opaque, infinitely thin planar plate with openings (theory §9, D11).
//
// The footprint-aware diffraction kernel. A generalized ray (GR) that meets the plate is not
// scattered into a fixed lobe: its own wave function on the plate (GenRay::OnPlane, the oblique
// cut of theory §6.3; the physical field is its time reverse, D3) is cut by the openings, and the
// amplitude it exchanges with an incident wave U_inc travelling along s is
//     A(s) = ∫_window OnPlane(x')·t(x')·U_inc(x') d²x'          (theory §9 items 1–2),
// evaluated in closed form along one plate axis (Faddeeva function) and by Gauss–Legendre
// quadrature along the other (materials/aperture_integral.h). Values per carried wavelength, each
// with its own k, β², ρ (radiance units, D4):
//   * next-event estimation towards a source of irradiance E along −wo gives L = E·|A|²·|cosθ_i|/λ²,
//     cosθ_i = d·n of the incident GR (so that an open plate passes radiance unchanged and a
//     `virtual_plane` reports E·cosθ for a tilted plane wave, D4). As a per-steradian density,
//     Eval = |A(s = −wo, plane wave)|²·|cosθ_i|/(λ²·|cosθ_o|) and EvalFrom uses the spherical
//     wave of a source at distance `dist`, so the generic NEE f·|cosθ_o|·E gives that line. A
//     Gaussian beam (IncidentWave::beam) enters with its own field across the footprint, per unit
//     on-axis irradiance.
//   * Sample draws from a proxy whose Pdf is exact: an anisotropic Gaussian in plate-transverse
//     wavevector about the straight-through direction (the GR's own angular spread, widened), a
//     wider Gaussian for the openings' diffraction (std 2π/ℓ, ℓ = the smallest opening seen in the
//     window), and a cosine lobe that covers every far-side direction.
//   * The GR leaving the plate is spread-free (ScatterSpreadFree, theory §9 item 5): its angular
//     spread is already inside |A|².
//   * Ray-optics limit (q.rayOptics or no GR): straight transmission with weight t at the hit.
// Two-sided: light may arrive from either side; only transmission is modelled (the plate absorbs
// what it does not transmit; Kirchhoff boundary values, valid for openings ≫ λ and a thin plate).
// Not reciprocal: the value belongs to the incident GR's footprint on the plate, which is not
// the footprint a GR arriving along wo would have (f(wi→wo) ≠ f(wo→wi)).
//
// Parameters (plate coordinates = the shape's local x, y in metres): rectangles, discs, one
// polygon and a bitmap mask; `window` is the locality radius in units of β (D13).
#include <memory>
#include <sstream>

#include "core/render/aperture.h"
#include "core/diagnostics.h"
#include "core/render/genray.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/render/sampling.h"
#include "core/geometry/shape.h"
#include "materials/aperture_integral.h"

namespace phasor {

namespace {

// Below this |cosθ_i| the plate is seen edge-on: its footprint spans > 10³ β and it is treated as
// opaque (the transmitted flux is ∝ cosθ_i anyway).
constexpr double MinCosIncidence = 1e-3;

// Proxy mixture: GR lobe, diffraction lobe, cosine lobe.
constexpr double ProbLobe = 0.5, ProbDiffraction = 0.35, ProbCosine = 0.15;
constexpr double LobeWidening = 1.5;  // the GR lobe's std in units of the GR's σ_k

// Density of the 2-D normal with stds (st, sp) along (t, p) at offset (a, b).
double Normal2Aniso(double a, double b, double st, double sp) {
    return std::exp(-0.5 * (a * a / (st * st) + b * b / (sp * sp))) / (2 * Pi * st * sp);
}

}  // namespace

class ApertureMaterial final : public Material, public PlateOpenings {
  public:
    ApertureMaterial(ApertureMask mask, double window) : mask_(std::move(mask)), window_(window) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "aperture",
            "opaque thin plate with openings: footprint-aware diffraction of generalized rays (theory §9)",
            {
                P::NumberList("rects",
                              "rectangular openings u0 v0 u1 v1 … in plate coordinates (the shape's "
                              "local x, y)",
                              Dim::Length()),
                P::NumberList("rect_transmission", "transmission t ∈ [0, 1] of each rectangle (default 1)")
                    .Min(0)
                    .Max(1),
                P::NumberList("discs", "circular openings cu cv r … in plate coordinates", Dim::Length()),
                P::NumberList("disc_transmission", "transmission t ∈ [0, 1] of each disc (default 1)")
                    .Min(0)
                    .Max(1),
                P::NumberList("polygon",
                              "one polygonal opening: x y pairs of ≥ 3 vertices (simple, either "
                              "orientation)",
                              Dim::Length()),
                P::Number("polygon_transmission", "transmission of the polygon")
                    .Default(Value::Number(1))
                    .Min(0)
                    .Max(1),
                P::File("mask",
                        "image whose first channel (or luminance) is the transmission over "
                        "'mask_extent' (row 0 at the top, v = v1)"),
                P::NumberList("mask_extent", "rectangle u0 v0 u1 v1 covered by 'mask'", Dim::Length())
                    .Size(4),
                P::Number("window", "locality radius of the footprint integral in units of the GR's β (D13)")
                    .Default(Value::Number(4))
                    .Min(1),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &ctx) {
        ApertureMask mask;
        auto count = [&](const char *name, std::size_t per, const char *what) {
            const std::vector<double> v = d.GetNumbers(name);
            if (v.size() % per != 0)
                throw Error(d.Loc(name), std::string("'") + name + "' needs " + std::to_string(per) +
                                             " numbers per " + what + "; got " + std::to_string(v.size()));
            return v;
        };
        auto transmissions = [&](const char *name, std::size_t n, const char *list) {
            std::vector<double> t(n, 1.0);
            if (!d.Has(name)) return t;
            t = d.GetNumbers(name);
            if (t.size() != n)
                throw Error(d.Loc(name), std::string("'") + name + "' needs one value per entry of '" + list +
                                             "' (" + std::to_string(n) + "); got " +
                                             std::to_string(t.size()));
            return t;
        };
        struct Box {
            Vec2 lo, hi;
        };
        struct Circle {
            Vec2 c;
            double r;
        };
        std::vector<Box> boxes;
        std::vector<Circle> circles;
        if (d.Has("rects")) {
            const std::vector<double> r = count("rects", 4, "rectangle (u0 v0 u1 v1)");
            const std::vector<double> t = transmissions("rect_transmission", r.size() / 4, "rects");
            for (std::size_t i = 0; i < r.size(); i += 4) {
                const Vec2 lo(r[i], r[i + 1]), hi(r[i + 2], r[i + 3]);
                if (!(hi.x > lo.x && hi.y > lo.y))
                    throw Error(d.Loc("rects"), "rectangle " + std::to_string(i / 4) +
                                                    " of 'rects' needs u0 < u1 and v0 < v1");
                if (t[i / 4] > 0) boxes.push_back({lo, hi});  // a closed opening may overlap others
                mask.AddRect(lo, hi, t[i / 4]);
            }
        } else if (d.Has("rect_transmission")) {
            throw Error(d.Loc("rect_transmission"), "'rect_transmission' needs 'rects'");
        }
        if (d.Has("discs")) {
            const std::vector<double> c = count("discs", 3, "disc (cu cv r)");
            const std::vector<double> t = transmissions("disc_transmission", c.size() / 3, "discs");
            for (std::size_t i = 0; i < c.size(); i += 3) {
                if (!(c[i + 2] > 0))
                    throw Error(d.Loc("discs"),
                                "disc " + std::to_string(i / 3) + " of 'discs' needs a positive radius");
                if (t[i / 3] > 0) circles.push_back({Vec2(c[i], c[i + 1]), c[i + 2]});
                mask.AddDisc(Vec2(c[i], c[i + 1]), c[i + 2], t[i / 3]);
            }
        } else if (d.Has("disc_transmission")) {
            throw Error(d.Loc("disc_transmission"), "'disc_transmission' needs 'discs'");
        }
        // Open openings may touch but not overlap (pieces would count the overlap twice); the
        // numbering below counts open rectangles / discs only.
        auto overlap = [&](const std::string &what) {
            throw Error(d.EntityLoc(), "aperture: " + what + " overlap; openings must not overlap");
        };
        for (std::size_t i = 0; i < boxes.size(); ++i)
            for (std::size_t j = i + 1; j < boxes.size(); ++j)
                if (std::min(boxes[i].hi.x, boxes[j].hi.x) > std::max(boxes[i].lo.x, boxes[j].lo.x) &&
                    std::min(boxes[i].hi.y, boxes[j].hi.y) > std::max(boxes[i].lo.y, boxes[j].lo.y))
                    overlap("rectangles " + std::to_string(i) + " and " + std::to_string(j));
        for (std::size_t i = 0; i < circles.size(); ++i) {
            for (std::size_t j = i + 1; j < circles.size(); ++j)
                if (Length(circles[i].c - circles[j].c) < circles[i].r + circles[j].r)
                    overlap("discs " + std::to_string(i) + " and " + std::to_string(j));
            for (std::size_t j = 0; j < boxes.size(); ++j) {
                const Vec2 q(std::clamp(circles[i].c.x, boxes[j].lo.x, boxes[j].hi.x),
                             std::clamp(circles[i].c.y, boxes[j].lo.y, boxes[j].hi.y));
                if (Length(q - circles[i].c) < circles[i].r)
                    overlap("disc " + std::to_string(i) + " and rectangle " + std::to_string(j));
            }
        }
        if (d.Has("polygon")) {
            const std::vector<double> p = count("polygon", 2, "vertex (x y)");
            if (p.size() < 6)
                throw Error(d.Loc("polygon"), "'polygon' needs at least 3 vertices (x y pairs)");
            std::vector<Vec2> v;
            for (std::size_t i = 0; i < p.size(); i += 2) v.emplace_back(p[i], p[i + 1]);
            const double tp = d.GetNumber("polygon_transmission");
            ApertureMask alone;  // the polygon by itself, to test it against the other openings
            try {
                mask.AddPolygon(v, tp);
                alone.AddPolygon(v, 1);
            } catch (const Error &e) {
                throw Error(d.Loc("polygon"), "'polygon': " + e.Message());
            }
            if (tp > 0) {
                for (std::size_t j = 0; j < boxes.size(); ++j) {
                    double area = 0;  // of polygon ∩ rectangle, from the polygon's slabs in the box
                    alone.ForEachPiece({boxes[j].lo, boxes[j].hi}, [&](const MaskPiece &pc) {
                        const double vm = 0.5 * (pc.v0 + pc.v1);
                        area += std::max(0.0, pc.UHi(vm) - pc.ULo(vm)) * (pc.v1 - pc.v0);
                    });
                    const Vec2 e = boxes[j].hi - boxes[j].lo;
                    if (area > 1e-9 * e.x * e.y) overlap("the polygon and rectangle " + std::to_string(j));
                }
                for (std::size_t j = 0; j < circles.size(); ++j) {
                    // They overlap iff the centre is inside the polygon or an edge passes closer than r.
                    bool meets = alone.Transmission(circles[j].c) > 0;
                    for (std::size_t i = 0; i < v.size() && !meets; ++i) {
                        const Vec2 a = v[i], b = v[(i + 1) % v.size()], ab = b - a;
                        const double t = std::clamp(Dot(circles[j].c - a, ab) / Dot(ab, ab), 0.0, 1.0);
                        meets = Length(a + ab * t - circles[j].c) < circles[j].r * (1 - 1e-12);
                    }
                    if (meets) overlap("the polygon and disc " + std::to_string(j));
                }
            }
        }
        if (d.Has("mask")) {
            if (!d.Has("mask_extent"))
                throw Error(d.Loc("mask"),
                            "'mask' needs 'mask_extent' = [u0 v0 u1 v1] (the plate area it covers)");
            const std::vector<double> e = d.GetNumbers("mask_extent");
            const std::string path = ctx.ResolveFile(d, "mask").string();
            if (!(e[2] > e[0] && e[3] > e[1]))
                throw Error(d.Loc("mask_extent"), "'mask_extent' needs u0 < u1 and v0 < v1");
            // The bitmap's extent must stay clear of the other openings (its texels would add).
            const Bounds2 extent{Vec2(e[0], e[1]), Vec2(e[2], e[3])};
            bool clear = true;
            mask.ForEachPiece(extent, [&](const MaskPiece &pc) {
                const double vm = 0.5 * (pc.v0 + pc.v1);
                if (pc.t > 0 && pc.v1 > pc.v0 && pc.UHi(vm) > pc.ULo(vm)) clear = false;
            });
            if (!clear)
                throw Error(d.Loc("mask_extent"),
                            "'mask_extent' overlaps another opening (rects, discs or polygon); openings must "
                            "not overlap");
            try {
                mask.AddBitmap(path, Vec2(e[0], e[1]), Vec2(e[2], e[3]));
            } catch (const Error &err) {
                throw Error(d.Loc("mask"), err.Message());
            }
        } else if (d.Has("mask_extent")) {
            throw Error(d.Loc("mask_extent"), "'mask_extent' needs 'mask'");
        }
        return std::make_unique<ApertureMaterial>(std::move(mask), d.GetNumber("window"));
    }

    static std::vector<ParamDict> TestPresets() {
        auto lengths = [](std::initializer_list<double> v) {
            std::vector<Value> items;
            for (double x : v) items.push_back(Value::Number(x, Dim::Length()));
            return Value::List(std::move(items));
        };
        std::vector<ParamDict> p(2);
        // A 2 µm slit, longer than the contract suite's GR footprint (β = 0.5 µm).
        p[0].Set("rects", lengths({-1e-6, -50e-6, 1e-6, 50e-6}));
        // A disc of radius 1.5 µm, off the hit point.
        p[1].Set("discs", lengths({0.5e-6, 0.2e-6, 1.5e-6}));
        return p;
    }

    /// Ray-optics limit (or no GR): one near-delta lobe (id 1), straight transmission with the
    /// transmission t at the hit. A generalized ray: one footprint-aware continuous lobe (id 0, the
    /// diffraction pattern |A|²). EvalLobe: scalar diffraction (Kirchhoff) keeps the polarisation:
    /// M = value·I, Jones = √value·I (the phase of a single lobe does not enter its Mueller matrix);
    /// lobe 0's value is Eval·|cosθo|, lobe 1's is t.
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(*this, q);
    }
    bool IsFootprintAware() const override { return true; }

    // See the file comment: the value depends on the incident GR's footprint.
    bool IsReciprocal() const override { return false; }
    const ApertureMask &Openings() const override { return mask_; }

    void CheckShape(const Shape &shape) const override {
        const std::string desc = shape.ToString();
        const std::string type = desc.substr(0, desc.find(' '));
        const std::string who = "material 'aperture' on shape " +
                                (shape.name.empty() ? "" : "'" + shape.name + "' ") + "(" + type + ")";
        if (!shape.IsPlanar())
            throw Error(who + ": the plate must be a planar shape (rectangle or disk), not a " + type);
        try {
            (void)PlateFrame::FromTransform(shape.objectToWorld);
        } catch (const Error &e) {
            throw Error(who + ": " + e.Message());
        }
    }

    std::string ToString() const override {
        std::ostringstream os;
        os << "ApertureMaterial[ " << mask_.ToString() << ", window = " << window_ << " β ]";
        return os.str();
    }

  private:
    // The plate seen by one query.
    struct Geometry {
        PlateFrame f;
        Vec3 d;           // incident GR direction (world, into the plate)
        double dn = 0;    // d·n
        double side = 1;  // sign(d·n): the far side, where transmitted directions point
        Vec2 hit;         // hit point in plate coordinates
    };

    // The proxy distribution of Sample (hero wavelength), in plate-transverse wavevector κ.
    struct Proxy {
        bool valid = false;  // the window sees an opening
        double k = 0;
        Vec2 kappa0, t{1, 0}, p{0, 1};
        double sigmaT = 0, sigmaP = 0, sigmaD = 0;
    };

    bool MakeGeometry(const ScatterQuery &q, Geometry *g) const {
        if (!q.si || !q.si->shape || !q.gr) return false;
        // CheckShape verified that to_world is a rigid motion, so its columns are the plate axes.
        const Transform &t = q.si->shape->objectToWorld;
        g->f.origin = t.Point(Vec3(0, 0, 0));
        g->f.e1 = t.Vector(Vec3(1, 0, 0));
        g->f.e2 = t.Vector(Vec3(0, 1, 0));
        g->f.n = t.Vector(Vec3(0, 0, 1));
        g->d = q.gr->d;
        g->dn = Dot(g->d, g->f.n);
        if (!(std::abs(g->dn) >= MinCosIncidence)) return false;
        g->side = g->dn > 0 ? 1 : -1;
        g->hit = g->f.ToPlate(q.si->p);
        return true;
    }

    // The window box (plate coordinates) that ForEachPiece is asked for: `far` times the D13 box.
    static Bounds2 PieceBox(const PlateGaussian &g, const Vec2 &hit) {
        const Vec2 h(g.far * g.hx, g.far * g.hy);
        return Bounds2{hit - h, hit + h};
    }

    // Eval/EvalFrom for a world direction wo (local z = woZ) and the incident wave w, for the GR gr
    // meeting the plate at p (world).
    SampledSpectrum EvalWorld(const SampledWavelengths &wl, const SpectralGenRay &gr, const Vec3 &p,
                              const Geometry &geo, const Vec3 &woWorld, double woZ, const IncidentWave &w) const {
        SampledSpectrum f(0.0);
        if (!(Dot(woWorld, geo.f.n) * geo.side > 0)) return f;  // transmission only
        const Vec3 s = -woWorld;                                // the incident wave's direction
        const int n = std::min(wl.Count(), gr.count);
        for (int i = 0; i < n; ++i) {
            if (!(gr.beta2[i] > 0 && gr.k[i] > 0)) continue;  // no footprint: nothing to diffract
            PlateGaussian g = MakePlateGaussian(geo.d, s, geo.f.e1, geo.f.e2, geo.f.n, gr.k[i], gr.beta2[i],
                                                gr.rho[i], w.beam ? Infinity : w.dist, window_);
            if (w.beam) AddIncidentBeam(&g, *w.beam, p, geo.f.e1, geo.f.e2);
            if (gr.pixel.valid) {
                // A narrow sensor pixel's own state, non-paraxially (PixelWavelet): |A|² per unit
                // label area is already the flux through the sensor, so no cosθ_i.
                const PixelWavelet pw = PixelWavelet::Make(gr.pixel, p, geo.f.e1, geo.f.e2, geo.f.n, gr.k[i]);
                if (pw.Preferred()) {
                    const Complex a = IntegrateWavelet(g, pw, mask_, geo.hit, window_);
                    const double lambda = 2 * Pi / gr.k[i];
                    f[i] = std::norm(a) / (lambda * lambda * std::abs(woZ));
                    continue;
                }
            }
            Complex a = 0;
            mask_.ForEachPiece(PieceBox(g, geo.hit), [&](const MaskPiece &piece) {
                a += piece.t * IntegratePiece(g, piece, geo.hit);
            });
            // A = C·∫…, C² = |d·n|/(πβ²) (unit-norm OnPlane); value |A|²·|cosθ_i|/(λ²|cosθ_o|).
            const double lambda = 2 * Pi / gr.k[i];
            const double c2 = std::abs(geo.dn) / (Pi * gr.beta2[i]);
            f[i] = c2 * std::norm(a) * std::abs(geo.dn) / (lambda * lambda * std::abs(woZ));
        }
        return f;
    }

    Proxy MakeProxy(const ScatterQuery &q, const Geometry &geo) const {
        Proxy px;
        const SpectralGenRay &gr = *q.gr;
        const double k = gr.k[0], beta2 = gr.beta2[0], rho = gr.rho[0];
        if (!(beta2 > 0 && k > 0)) return px;
        // The hero's window: does it see an opening, and how small is the smallest one?
        const PlateGaussian g =
            MakePlateGaussian(geo.d, -geo.d, geo.f.e1, geo.f.e2, geo.f.n, k, beta2, rho, Infinity, window_);
        const Bounds2 window{geo.hit - Vec2(g.hx, g.hy), geo.hit + Vec2(g.hx, g.hy)};
        const Bounds2 box = PieceBox(g, geo.hit);
        double ell = Infinity;
        auto inner = [&](double a, double lo, double hi) {  // an edge that is not the box's
            return std::abs(a - lo) > 1e-9 * (hi - lo) && std::abs(a - hi) > 1e-9 * (hi - lo);
        };
        mask_.ForEachPiece(box, [&](const MaskPiece &m) {
            const double vm = 0.5 * (m.v0 + m.v1);
            const double uLo = m.ULo(vm), uHi = m.UHi(vm);
            if (!(std::min(uHi, window.hi.x) > std::max(uLo, window.lo.x) &&
                  std::min(m.v1, window.hi.y) > std::max(m.v0, window.lo.y)))
                return;
            px.valid = true;
            if (m.circle) {
                ell = std::min(ell, 2 * m.r);
                return;
            }
            if (inner(uLo, box.lo.x, box.hi.x) && inner(uHi, box.lo.x, box.hi.x))
                ell = std::min(ell, uHi - uLo);
            if (m.loB == 0 && m.hiB == 0 && inner(m.v0, box.lo.y, box.hi.y) &&
                inner(m.v1, box.lo.y, box.hi.y))
                ell = std::min(ell, m.v1 - m.v0);
        });
        if (!px.valid) return px;
        px.k = k;
        const double d1 = Dot(geo.d, geo.f.e1), d2 = Dot(geo.d, geo.f.e2);
        px.kappa0 = Vec2(d1, d2) * k;  // straight through: wo = d
        const double tl = std::hypot(d1, d2);
        if (tl > 1e-12) {
            px.t = Vec2(d1, d2) / tl;
            px.p = Vec2(-px.t.y, px.t.x);
        }
        // The GR's angular spread σ_k per axis (theory §1.2) seen in plate κ: compressed by
        // |cosθ_i| along the plane of incidence.
        const double sigmaK = std::sqrt(0.5 * (1 + rho * rho) / beta2) * LobeWidening;
        px.sigmaP = sigmaK;
        px.sigmaT = sigmaK * std::max(std::abs(geo.dn), 0.1);
        px.sigmaD = std::min(std::max(2 * Pi / ell, 3 * sigmaK), k);
        return px;
    }

    // Solid-angle density of the proxy at a world direction (d²κ = k²|cosθ_o| dω).
    static double ProxyPdf(const Proxy &px, const Geometry &geo, const Vec3 &woWorld) {
        const double cosO = Dot(woWorld, geo.f.n) * geo.side;
        if (!(cosO > 0)) return 0;
        const Vec2 dk = Vec2(Dot(woWorld, geo.f.e1), Dot(woWorld, geo.f.e2)) * px.k - px.kappa0;
        const double lobe = Normal2Aniso(Dot(dk, px.t), Dot(dk, px.p), px.sigmaT, px.sigmaP);
        const double diff = Normal2Aniso(dk.x, dk.y, px.sigmaD, px.sigmaD);
        return px.k * px.k * cosO * (ProbLobe * lobe + ProbDiffraction * diff) + ProbCosine * cosO * InvPi;
    }

    static constexpr int StraightLobe = 1;  // the ray-optics limit's lobe id
    static bool RayLimit(const ScatterQuery &q) { return q.rayOptics || !q.gr; }
    /// The mask's transmission at the hit point (0 without a hit).
    double TransmissionAtHit(const ScatterQuery &q) const {
        if (!q.si || !q.si->shape) return 0;
        const Transform &tw = q.si->shape->objectToWorld;
        const Vec3 rel = q.si->p - tw.Point(Vec3(0, 0, 0));
        return mask_.Transmission(Vec2(Dot(rel, tw.Vector(Vec3(1, 0, 0))), Dot(rel, tw.Vector(Vec3(0, 1, 0)))));
    }

    /// The plate at one hit: in the ray-optics limit the transmission there; for a generalized ray
    /// its footprint (a copy of the GR), the plate's geometry and the sampling proxy.
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const ApertureMaterial &m, const ScatterQuery &q) : PreparedKernel(q), m_(&m), rayLimit_(RayLimit(q)) {
            if (rayLimit_) {
                caps_ = CapNearDelta;
                t_ = m.TransmissionAtHit(q);
                if (!(t_ > 0) || q.wi.z == 0) return;
                lobe_.id = StraightLobe;
                lobe_.flags = ScatterTransmission | ScatterNearDelta;
                lobe_.wo.fill(-q.wi);
                lobe_.SetWeight(SampledSpectrum(t_));
                lobe_.nIn.fill(q.etaOutside);
                lobe_.nOut.fill(q.etaOutside);
                lobe_.prob = 1;
                lobes_ = std::span<const NearDeltaLobe>(&lobe_, 1);
                return;
            }
            caps_ = CapContinuous | CapFootprintAware;
            continuous_.Add(0);
            gr_ = *q.gr;
            if (q.si) {
                p_ = q.si->p;
                shading_ = q.si->shading;
            }
            geoOk_ = m.MakeGeometry(q, &geo_);  // false without a hit
            if (geoOk_) px_ = m.MakeProxy(q, geo_);
        }

        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            SampledSpectrum v(0.0);
            if (lobe == StraightLobe && rayLimit_ && SameDirection(wo, -q_.wi)) v = SampledSpectrum(t_);
            else if (lobe == 0 && !rayLimit_) v = EvalContinuous(wo) * std::abs(wo.z);
            else return std::nullopt;
            LobeResponse r;
            r.hasJones = true;
            for (int i = 0; i < q_.wl->Count(); ++i) {
                r.jones[i] = Jones::Identity() * Complex(std::sqrt(std::max(0.0, v[i])), 0);
                r.mueller[i] = Mueller::Identity() * std::max(0.0, v[i]);
            }
            return r;
        }

      private:
        std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const override {
            if (rayLimit_) return SampleRay();
            if (!geoOk_ || !px_.valid) return std::nullopt;
            const Geometry &geo = geo_;
            const Proxy &px = px_;
            // One direction from the proxy mixture, in plate coordinates.
            Vec3 woPlate;
            if (u0 < ProbLobe + ProbDiffraction) {
                // Box–Muller: two standard normals from u.
                const double r = std::sqrt(-2 * std::log(std::max(1 - u.x, 1e-300))), phi = 2 * Pi * u.y;
                const double n1 = r * std::cos(phi), n2 = r * std::sin(phi);
                Vec2 kappa;
                if (u0 < ProbLobe)
                    kappa = px.kappa0 + px.t * (n1 * px.sigmaT) + px.p * (n2 * px.sigmaP);
                else
                    kappa = px.kappa0 + Vec2(n1, n2) * px.sigmaD;
                const Vec2 s = kappa / px.k;
                const double s2 = LengthSquared(s);
                if (!(s2 < 1)) return std::nullopt;  // evanescent: no propagating direction
                woPlate = Vec3(s.x, s.y, geo.side * std::sqrt(1 - s2));
            } else {
                // Cosine lobe on the far side.
                const Vec2 c = ConcentricDisc(u);
                woPlate = Vec3(c.x, c.y, geo.side * SafeSqrt(1 - LengthSquared(c)));
                if (woPlate.z == 0) return std::nullopt;
            }
            const Vec3 woWorld = Normalize(geo.f.e1 * woPlate.x + geo.f.e2 * woPlate.y + geo.f.n * woPlate.z);
            ScatterSample s;
            s.wo = shading_.ToLocal(woWorld);
            s.pdf = ProxyPdf(px, geo, woWorld);
            if (!(s.pdf > 0) || s.wo.z == 0) return std::nullopt;
            s.weight = m_->EvalWorld(*q_.wl, gr_, p_, geo, woWorld, s.wo.z, IncidentWave{}) * (std::abs(s.wo.z) / s.pdf);
            s.lobe = 0;
            s.flags = ScatterTransmission | ScatterDiffuse | ScatterSpreadFree;
            s.eta = 1;
            return s;
        }
        SampledSpectrum EvalContinuous(const Vec3 &wo) const override { return EvalContinuousFrom(wo, IncidentWave{}); }
        SampledSpectrum EvalContinuousFrom(const Vec3 &wo, const IncidentWave &w) const override {
            if (rayLimit_ || wo.z == 0 || !geoOk_) return SampledSpectrum(0.0);
            return m_->EvalWorld(*q_.wl, gr_, p_, geo_, shading_.ToWorld(wo), wo.z, w);
        }
        double PdfContinuous(const Vec3 &wo) const override {
            if (rayLimit_ || !geoOk_ || !px_.valid) return 0;
            return ProxyPdf(px_, geo_, shading_.ToWorld(wo));
        }
        // Ray-optics limit: straight transmission with the transmission at the hit point.
        std::optional<ScatterSample> SampleRay() const {
            if (!(t_ > 0) || q_.wi.z == 0) return std::nullopt;
            ScatterSample s;
            s.wo = -q_.wi;
            s.weight = SampledSpectrum(t_);
            s.pdf = 1;
            s.lobe = StraightLobe;
            s.flags = ScatterTransmission | ScatterNearDelta;
            s.eta = 1;
            return s;
        }

        const ApertureMaterial *m_;
        bool rayLimit_;
        double t_ = 0;            // ray-optics limit: the transmission at the hit
        NearDeltaLobe lobe_;      // ray-optics limit: straight through, listed when t_ > 0
        SpectralGenRay gr_;       // the incident GR at the hit (generalized rays)
        Vec3 p_;                  // the hit (world)
        Frame shading_;           // the hit's shading frame
        bool geoOk_ = false;      // the plate is not seen edge-on (MakeGeometry)
        Geometry geo_;
        Proxy px_;                // Sample's proxy (hero wavelength)
    };

    ApertureMask mask_;
    double window_;
};

PHASOR_EXPORT_PLUGIN(Material, ApertureMaterial)

}  // namespace phasor
