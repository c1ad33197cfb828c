// SPDX-License-Identifier: Apache-2.0
// Free-space diffraction tests: the occluders of the FSD presets as scene text (meshes only), a
// scene around them, and a generalized ray crossing them.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/math.h"
#include "core/render/genray.h"
#include "core/render/scene.h"
#include "parser/parser.h"
#include "support/genray_builder.h"

namespace phasor::test {

/// A trianglemesh in micrometres.
struct MeshText {
    std::vector<Vec3> p;
    std::vector<int> idx;
    void Tri(int a, int b, int c) { idx.insert(idx.end(), {a, b, c}); }
    int Add(const Vec3 &v) {
        p.push_back(v);
        return int(p.size()) - 1;
    }
    std::string Shape(const std::string &name, const std::string &extra = "") const {
        std::ostringstream os;
        os.precision(17);
        os << "Shape \"trianglemesh\" \"" << name << "\" {\n    positions = [";
        for (const Vec3 &v : p) os << v.x << ' ' << v.y << ' ' << v.z << "  ";
        os << "] um\n    indices = [";
        for (int i : idx) os << i << ' ';
        os << "]\n    " << extra << "\n}\n";
        return os.str();
    }
};

/// A closed box [lo, hi] (µm), outward counter-clockwise triangles sharing 8 vertices.
inline MeshText Box(const Vec3 &lo, const Vec3 &hi) {
    MeshText m;
    for (int i = 0; i < 8; ++i) m.Add(Vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z));
    // Faces as quads (a, b, c, d) counter-clockwise seen from outside.
    const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &f : q) {
        m.Tri(f[0], f[1], f[2]);
        m.Tri(f[0], f[2], f[3]);
    }
    return m;
}

/// A flat plate in the plane z = z0 (µm): the square [−half, half]² with a hole whose outline is
/// r(φ) about (cx, cy) (star-shaped about it), triangulated as a ring of n quads between the hole's
/// vertices and the square's points at the same angles (plus the square's corners). Single-sided,
/// zero thickness: an open mesh whose boundaries are the hole and the square.
template <typename R>
MeshText HolePlate(double half, double z0, int n, R r, double cx = 0, double cy = 0) {
    MeshText m;
    std::vector<int> inner, outer;
    for (int i = 0; i < n; ++i) {
        const double phi = 2 * Pi * i / n, c = std::cos(phi), s = std::sin(phi);
        inner.push_back(m.Add(Vec3(cx + r(phi) * c, cy + r(phi) * s, z0)));
        const double t = half / std::max(std::abs(c), std::abs(s));  // the square along the ray
        outer.push_back(m.Add(Vec3(t * c, t * s, z0)));
    }
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        m.Tri(inner[i], outer[i], outer[j]);
        m.Tri(inner[i], outer[j], inner[j]);
    }
    return m;
}

/// A star of `points` points with outer and inner radii (µm).
inline auto Star(double outer, double inner, int points) {
    return [=](double phi) {
        const double a = std::fmod(phi * points / (2 * Pi), 1.0);  // 0 at a tip, 0.5 at a notch
        const double t = 1 - 2 * std::abs(a - 0.5);                 // 1 at a tip, 0 at a notch
        return inner + (outer - inner) * t;
    };
}

/// A scene around the given shapes: a unit plane wave travelling towards +z (the GRs of the tests
/// are traced towards −z… or +z; only the geometry matters for the FSD unit tests) and a small
/// sensor far behind.
inline std::string FsdScene(const std::string &shapes, double lambdaNm = 500) {
    std::ostringstream os;
    os << "wscene 1\n"
       << "Light \"plane_wave\" \"w\" { direction = [0 0 1]  irradiance = 1 W/m^2  spectrum = line(" << lambdaNm
       << " nm) }\n"
       << shapes
       << "Detector \"virtual_plane\" \"s\" { to_world = translate([0 0 -1] m)  extent = [10 um 10 um]  pitch = 10 um "
          " auto_aim = false }\n"
       << "Integrator \"grt\" \"grt\" {}\n"
       << "Render { detector = @s  integrator = @grt  spp = 1 }\n";
    return os.str();
}

/// FsdScene(shapes, λ) built; a failed build is a test failure (with the diagnostics) and null.
inline std::unique_ptr<Scene> BuildFsdScene(const std::string &shapes, double lambdaNm = 500) {
    Diagnostics diag;
    auto desc = ParseSceneString(FsdScene(shapes, lambdaNm), "fsd.wscene", DefineList{}, diag);
    std::unique_ptr<Scene> scene;
    if (desc) scene = Scene::Build(*desc, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(scene) << os.str();
    return scene;
}

/// One carried wavelength λ [m] (a line spectrum).
inline SampledWavelengths OneWavelength(double lambda) {
    SampledWavelengths wl;
    wl.lambda.fill(lambda);
    wl.pdf.fill(1);
    wl.delta = true;
    return wl;
}

}  // namespace phasor::test
