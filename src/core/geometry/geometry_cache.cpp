// SPDX-License-Identifier: Apache-2.0
#include "core/geometry/geometry_cache.h"

#include <cstdio>
#include <filesystem>
#include <vector>

#include "core/diagnostics.h"
#include "core/hash.h"
#include "core/geometry/accel.h"

namespace phasor {

namespace {

// What the strong references may hold [bytes]: a sweep over a scene of up to this much mesh keeps
// it between renders; beyond, the geometry is rebuilt per render as without the cache.
constexpr std::size_t MeshBudgetBytes = std::size_t(1) << 30;

SharedCache<MeshGeometry> &Meshes() {
    static SharedCache<MeshGeometry> cache(MeshBudgetBytes, [](const MeshGeometry &m) { return m.Bytes(); });
    return cache;
}

std::string Hex(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%a", v);
    return buf;
}

}  // namespace

GeometryKey &GeometryKey::Text(std::string_view name, std::string_view value) {
    // Lengths make the concatenation unambiguous whatever the text holds.
    key_ += "|" + std::string(name) + "=" + std::to_string(value.size()) + ":" + std::string(value);
    return *this;
}

GeometryKey &GeometryKey::Integer(std::string_view name, long long value) {
    return Text(name, std::to_string(value));
}

GeometryKey &GeometryKey::Number(std::string_view name, double value) { return Text(name, Hex(value)); }

GeometryKey &GeometryKey::Numbers(std::string_view name, const std::vector<double> &values) {
    std::string s;
    for (double v : values) s += Hex(v) + " ";
    return Text(name, s);
}

GeometryKey &GeometryKey::Matrix(std::string_view name, const Transform &t) {
    const Transform inverse = t.Inverse();
    std::string s;
    for (const Transform::Mat *m : {&t.Matrix(), &inverse.Matrix()})
        for (const auto &row : *m)
            for (double v : row) s += Hex(v) + " ";
    return Text(name, s);
}

GeometryKey &GeometryKey::File(std::string_view name, const std::string &path) {
    std::error_code ec;
    std::filesystem::path abs = std::filesystem::absolute(path, ec);
    std::size_t size = 0;
    ContentHasher hasher;
    if (!hasher.AddFile(path, &size)) throw Error("cannot read '" + path + "'");
    const uint64_t hash = hasher.Digest();
    char h[24];
    std::snprintf(h, sizeof h, "%016llx", static_cast<unsigned long long>(hash));
    return Text(name, (ec ? path : abs.lexically_normal().string()) + " " + std::to_string(size) + " bytes " + h);
}

std::shared_ptr<const MeshGeometry> CachedMesh(const GeometryKey &key, const std::function<TriangleMesh()> &build) {
    return Meshes().GetOrBuild(key.Str(),
                               [&] { return std::make_shared<const MeshGeometry>(build(), key.Str()); });
}

GeometryCacheStats GetGeometryCacheStats() {
    GeometryCacheStats s;
    s.meshBuilds = Meshes().Builds();
    s.meshReuses = Meshes().Reuses();
    const Accel::CacheCounts b = Accel::BvhCacheCounts();
    s.bvhBuilds = b.builds;
    s.bvhReuses = b.reuses;
    return s;
}

void ClearGeometryCache() {
    Meshes().Clear();
    Accel::ClearBvhCache();
}

}  // namespace phasor
