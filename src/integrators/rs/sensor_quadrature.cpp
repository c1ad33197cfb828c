// SPDX-License-Identifier: Apache-2.0
// `rs`'s sensor quadrature (rs/sensor_quadrature.h; docs/rs.md §3): the field on a uniform grid
// over all pixel centres ± 6σ (± pitch/2 + 6σ for box pixels), spacing h ≤ 2π/(k·Δ + c/σ) per
// axis, Δ = an interval bound, tile by tile over the window, of the spread of the direction
// components along that axis from the openings' box to any one point (the band limit of the
// intensity); nodes no pixel window reaches are skipped (a one-row sensor evaluates only its
// row's nodes). Each pixel is Σ w(node)·F(node)·h_x·h_y: the trapezoid rule on a band-limited
// integrand times a Gaussian, aliasing ≈ e^{−c²/2} of the local intensity (e^{−c²/2} =
// accuracy/10). In the 2-D mode the field is constant along the slits, so the pixel sensitivity
// along them integrates to 1 and that grid axis collapses to one node.
// Parallel over grid nodes with TBB; every node and every pixel sum is computed in a fixed
// order, so the result does not depend on the thread count.
#include "integrators/rs/sensor_quadrature.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/diagnostics.h"

namespace phasor {
namespace rs {

double PixelWeight(double d, double sigma, double pitch, bool gaussian) {
    if (gaussian) return std::exp(-0.5 * d * d / (sigma * sigma)) / (std::sqrt(2 * Pi) * sigma);
    const double s = 1 / (std::sqrt(2.0) * sigma);
    return 0.5 * (std::erf((d + 0.5 * pitch) * s) - std::erf((d - 0.5 * pitch) * s)) / pitch;
}

double WindowHalfWidth(const SensorPlaneGeometry &g, double pitch) {
    return 6 * g.sigma + (g.gaussianPixel ? 0.0 : 0.5 * pitch);
}

namespace {

/// Uniform nodes over [lo, hi] with spacing ≤ hMax, keeping those within `ext` of a pixel centre
/// c0 + i·pitch (i < n).
std::vector<double> AxisNodes(double lo, double hi, double hMax, double c0, double pitch, int n, double ext,
                              double *h) {
    const long long intervals = std::max(1LL, (long long)std::ceil((hi - lo) / hMax));
    if (intervals > 50000000) throw Error("rs: the sensor grid would need more than 5e7 nodes along an axis");
    *h = (hi - lo) / intervals;
    std::vector<double> out;
    for (long long a = 0; a <= intervals; ++a) {
        const double x = lo + a * *h;
        const double i = std::clamp(std::round((x - c0) / pitch), 0.0, double(n - 1));
        if (std::abs(x - (c0 + i * pitch)) <= ext) out.push_back(x);
    }
    return out;
}

}  // namespace

SensorGrid MakeGrid(const SensorPlaneGeometry &g, const Propagator &prop) {
    SensorGrid grid;
    if (!(g.sigma > 0) || g.nx < 1 || g.ny < 1) throw Error("rs: the sensor plane has no valid pixels");
    const double extX = WindowHalfWidth(g, g.pitchX), extY = WindowHalfWidth(g, g.pitchY);
    const Vec2 c00 = g.PixelCenter(0, 0), c11 = g.PixelCenter(g.nx - 1, g.ny - 1);
    const double xLo = c00.x - extX, xHi = c11.x + extX;  // x grows with i, y falls with j
    const double yLo = c11.y - extY, yHi = c00.y + extY;
    if (prop.TwoD()) {
        const Vec3 e2 = prop.Plate().e2;
        if (std::abs(Dot(g.frame.t, e2)) >= 1 - 1e-9)
            grid.collapseY = true;
        else if (std::abs(Dot(g.frame.s, e2)) >= 1 - 1e-9)
            grid.collapseX = true;
        else
            throw Error("the 2-D mode needs a sensor axis parallel to the slits (the plate's y axis)");
    }
    // Band limit of the intensity along each axis (this file's header): the largest direction spread
    // seen from any point of the window, bounded tile by tile. A tile of size T overestimates the
    // spread by at most ~T/distance, so tiles a quarter of the openings' extent (at most 256 per
    // axis) keep the grid within ~25 % of the spacing the exact maximum would allow.
    const Bounds2 ob = prop.OpeningBounds();
    const double tileMin = ob.Empty() ? Infinity : 0.25 * std::max(ob.hi.x - ob.lo.x, ob.hi.y - ob.lo.y);
    auto tiles = [&](double lo, double hi, bool collapsed) {
        if (collapsed) return 1;
        const double n = std::ceil((hi - lo) / std::max(tileMin, (hi - lo) / 256));
        return std::clamp(int(n), 1, 256);
    };
    const int ns = tiles(xLo, xHi, grid.collapseX), nt = tiles(yLo, yHi, grid.collapseY);
    const double tx = grid.collapseX ? 0 : (xHi - xLo) / ns, ty = grid.collapseY ? 0 : (yHi - yLo) / nt;
    const double x0 = grid.collapseX ? 0.5 * (xLo + xHi) : xLo, y0 = grid.collapseY ? 0.5 * (yLo + yHi) : yLo;
    double spreadS = 0, spreadT = 0;
    for (int a = 0; a < ns; ++a)
        for (int b = 0; b < nt; ++b) {
            const Vec3 corner = g.origin + g.frame.s * (x0 + a * tx) + g.frame.t * (y0 + b * ty);
            const Vec3 es = g.frame.s * tx, et = g.frame.t * ty;
            if (!grid.collapseX) spreadS = std::max(spreadS, prop.DirectionSpread(corner, es, et, g.frame.s));
            if (!grid.collapseY) spreadT = std::max(spreadT, prop.DirectionSpread(corner, es, et, g.frame.t));
        }
    // One axis: a single node of weight 1 if collapsed, else spacing h ≤ 2π/(kΔ + c/σ) from the
    // first pixel centre c0 along it.
    const double k = prop.K();
    auto axis = [&](bool collapsed, double lo, double hi, double spread, double c0, double pitch, int n,
                    double ext, std::vector<double> *nodes, double *h) {
        if (collapsed) {
            *nodes = {0.5 * (lo + hi)};
            *h = 1;
            return;
        }
        const double hMax = 2 * Pi / (k * spread + prop.Rule().gridMargin / g.sigma);
        *nodes = AxisNodes(lo, hi, hMax, c0, pitch, n, ext, h);
    };
    axis(grid.collapseX, xLo, xHi, spreadS, c00.x, g.pitchX, g.nx, extX, &grid.xs, &grid.hx);
    // Pixel centres along y run downwards from c00.y; AxisNodes runs on the reversed axis from c11.y.
    axis(grid.collapseY, yLo, yHi, spreadT, c11.y, g.pitchY, g.ny, extY, &grid.ys, &grid.hy);
    return grid;
}

int ProgressUnits(const SensorGrid &grid) {
    return int(std::clamp<std::size_t>(grid.Nodes() / 64, 1, 1000));
}

std::vector<double> IntegrateSensor(const SensorPlaneGeometry &g, const Propagator &prop,
                                    const SensorGrid &grid, Quantity q,
                                    const std::function<bool(int)> &batchDone,
                                    const std::atomic<bool> *cancel, WorkShare *work) {
    const std::size_t nxg = grid.xs.size(), nyg = grid.ys.size(), total = nxg * nyg;
    std::vector<double> field(total, 0.0);
    auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
    auto batch = [&](std::size_t begin, std::size_t end) {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(begin, end, 1), [&](const tbb::blocked_range<std::size_t> &r) {
                for (std::size_t idx = r.begin(); idx < r.end(); ++idx) {
                    if (cancelled()) return;
                    const double x = grid.xs[idx % nxg], y = grid.ys[idx / nxg];
                    const Vec3 p = g.origin + g.frame.s * x + g.frame.t * y;
                    field[idx] = q == Quantity::Flux ? prop.Flux(p, g.frame.n) : prop.Intensity(p);
                }
            });
    };
    const bool complete = work ? work->Batches(field, ProgressUnits(grid), batch, batchDone, cancel)
                               : RunBatchesLocally(field, ProgressUnits(grid), batch, batchDone, cancel);
    if (!complete) return {};
    // Separable pixel sums: G(b, i) = Σ_a w_x(x_a − x_i)·F(a, b)·h_x, then Σ_b w_y·G·h_y, over the
    // nodes within each pixel's window (the node lists are sorted).
    struct Taps {
        std::size_t first = 0;
        std::vector<double> w;  // quadrature weights w(node − centre)·h of nodes first, first + 1, …
    };
    auto taps = [&](const std::vector<double> &nodes, double centre, double pitch, double h) {
        const double ext = WindowHalfWidth(g, pitch);
        Taps t;
        t.first = std::size_t(std::lower_bound(nodes.begin(), nodes.end(), centre - ext) - nodes.begin());
        for (std::size_t a = t.first; a < nodes.size() && nodes[a] <= centre + ext; ++a)
            t.w.push_back(PixelWeight(nodes[a] - centre, g.sigma, pitch, g.gaussianPixel) * h);
        return t;
    };
    std::vector<Taps> tapsX(g.nx), tapsY(g.ny);
    if (!grid.collapseX)
        for (int i = 0; i < g.nx; ++i) tapsX[i] = taps(grid.xs, g.PixelCenter(i, 0).x, g.pitchX, grid.hx);
    if (!grid.collapseY)
        for (int j = 0; j < g.ny; ++j) tapsY[j] = taps(grid.ys, g.PixelCenter(0, j).y, g.pitchY, grid.hy);
    std::vector<double> rowSums(nyg * std::size_t(g.nx), 0.0);
    tbb::parallel_for(std::size_t(0), nyg, [&](std::size_t b) {
        for (int i = 0; i < g.nx; ++i) {
            double s = 0;
            if (grid.collapseX) {
                s = field[b * nxg];
            } else {
                const Taps &t = tapsX[i];
                for (std::size_t a = 0; a < t.w.size(); ++a) s += t.w[a] * field[b * nxg + t.first + a];
            }
            rowSums[b * g.nx + i] = s;
        }
    });
    std::vector<double> pixels(std::size_t(g.nx) * g.ny, 0.0);
    tbb::parallel_for(0, g.ny, [&](int j) {
        for (int i = 0; i < g.nx; ++i) {
            double s = 0;
            if (grid.collapseY) {
                s = rowSums[i];
            } else {
                const Taps &t = tapsY[j];
                for (std::size_t b = 0; b < t.w.size(); ++b) s += t.w[b] * rowSums[(t.first + b) * g.nx + i];
            }
            pixels[std::size_t(j) * g.nx + i] = s;
        }
    });
    return pixels;
}

}  // namespace rs
}  // namespace phasor
