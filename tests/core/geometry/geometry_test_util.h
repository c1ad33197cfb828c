// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the geometry tests: temporary files, asset paths and long-double reference
// intersections (independent of the code under test).
#pragma once

#include "core/math.h"
#include "core/geometry/shape.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

namespace phasor::test {

inline std::string AssetPath(const std::string &name) {
    return std::string(PHASOR_SOURCE_DIR) + "/scenes/assets/" + name;
}

/// A per-process scratch directory for files the tests write; removed at exit.
inline std::filesystem::path ScratchDir() {
    struct Holder {
        std::filesystem::path dir;
        ~Holder() {
            std::error_code ec;
            std::filesystem::remove_all(dir, ec);
        }
    };
    static Holder holder{[] {
        auto d = std::filesystem::temp_directory_path() /
                 ("phasor_geometry_test_" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }()};
    return holder.dir;
}

inline std::string WriteScratch(const std::string &name, const std::string &content) {
    auto p = ScratchDir() / name;
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
}

inline std::string ReadFile(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

using LD = long double;
struct LVec {
    LD x, y, z;
};
inline LVec L(const Vec3 &v) { return {v.x, v.y, v.z}; }
inline LVec Sub(LVec a, LVec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline LD LDot(LVec a, LVec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline LVec LCross(LVec a, LVec b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Nearest ray–sphere root in (tMin, tMax), long double, textbook quadratic formula.
inline std::optional<LD> RefSphere(const Ray &r, const Vec3 &c, double radius, LD tMin, LD tMax) {
    LVec oc = Sub(L(r.o), L(c)), d = L(r.d);
    LD a = LDot(d, d), b = LDot(oc, d), cc = LDot(oc, oc) - LD(radius) * radius;
    LD disc = b * b - a * cc;
    if (disc < 0) return std::nullopt;
    LD s = sqrtl(disc);
    LD t0 = (-b - s) / a, t1 = (-b + s) / a;
    if (t0 > tMin && t0 < tMax) return t0;
    if (t1 > tMin && t1 < tMax) return t1;
    return std::nullopt;
}

struct RefTri {
    LD t, b1, b2;
};
/// Ray–triangle by Cramer's rule in long double (t, barycentrics of p1 and p2).
inline std::optional<RefTri> RefTriangle(const Ray &r, const Vec3 &p0, const Vec3 &p1, const Vec3 &p2) {
    LVec e1 = Sub(L(p1), L(p0)), e2 = Sub(L(p2), L(p0)), d = L(r.d), s = Sub(L(r.o), L(p0));
    // o + t d = p0 + b1 e1 + b2 e2  ⇔  [−d e1 e2]·(t, b1, b2) = s
    LVec md{-d.x, -d.y, -d.z};
    LD det = LDot(md, LCross(e1, e2));
    if (det == 0) return std::nullopt;
    LD t = LDot(s, LCross(e1, e2)) / det;
    LD b1 = LDot(md, LCross(s, e2)) / det;
    LD b2 = LDot(md, LCross(e1, s)) / det;
    if (b1 < 0 || b2 < 0 || b1 + b2 > 1) return std::nullopt;
    return RefTri{t, b1, b2};
}

}  // namespace phasor::test
