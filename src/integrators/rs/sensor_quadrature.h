// SPDX-License-Identifier: Apache-2.0
// The sensor quadrature of `rs` (rs/sensor_quadrature.cpp, docs/rs.md §3): the uniform grid on
// which the field is evaluated and the pixel integrals over it. Exposed for the integrator's tests.
#pragma once

#include <atomic>
#include <functional>
#include <vector>

#include "core/render/detector.h"
#include "core/render/work.h"
#include "integrators/rs/propagator.h"

namespace phasor::rs {

/// What IntegrateSensor integrates: Propagator::Flux through the sensor plane, or |U|²
/// (Propagator::Intensity).
enum class Quantity { Flux, Intensity };

/// The uniform grid on which the field is evaluated (rs/sensor_quadrature.cpp header): nodes
/// xs × ys in sensor-plane coordinates; a collapsed axis has one node of weight 1 (2-D mode,
/// the field is constant along it).
struct SensorGrid {
    std::vector<double> xs, ys;
    double hx = 0, hy = 0;
    bool collapseX = false, collapseY = false;
    std::size_t Nodes() const { return xs.size() * ys.size(); }
};

/// Chooses the grid for `sensor` and the field of `prop`. In 2-D mode the axis along the slits
/// is collapsed (it must be parallel to the plate's e2; checked by the caller).
SensorGrid MakeGrid(const SensorPlaneGeometry &sensor, const Propagator &prop);

/// Pixel values, row-major (j·nx + i), of the quantity integrated against each pixel's
/// sensitivity [W/m²] (not divided by the reference irradiance). The grid nodes are evaluated in
/// ProgressUnits(grid) equal batches; `batchDone(batches)` is called from the calling thread after
/// every batch with the number done so far; returning false cancels. `cancel`, when set, is also
/// checked before every node, so a stop request ends the current batch early. A cancelled call
/// returns an empty vector. Parallel over grid nodes (TBB), deterministic. With `work` the batches
/// are shared with other processes (WorkShare::Batches; every node's value is the same whoever
/// computes it): the pixels are returned on the coordinating process only, an empty vector elsewhere.
std::vector<double> IntegrateSensor(const SensorPlaneGeometry &sensor, const Propagator &prop,
                                    const SensorGrid &grid, Quantity q,
                                    const std::function<bool(int)> &batchDone = {},
                                    const std::atomic<bool> *cancel = nullptr, WorkShare *work = nullptr);
/// Number of progress units (batches of at least 64 grid nodes, at most 1000 batches) that
/// IntegrateSensor reports for `grid`.
int ProgressUnits(const SensorGrid &grid);

/// Pixel sensitivity along one axis at offset d [m] from the pixel centre (theory §0 D2), with
/// unit integral [1/m]: Gaussian N(0, σ²) or, for box pixels, box(pitch) ⊛ N(0, σ²).
double PixelWeight(double d, double sigma, double pitch, bool gaussian);
/// Half-width [m] of the window around a pixel centre outside which PixelWeight is neglected:
/// 6σ, plus pitch/2 for box pixels.
double WindowHalfWidth(const SensorPlaneGeometry &sensor, double pitch);

}  // namespace phasor::rs
