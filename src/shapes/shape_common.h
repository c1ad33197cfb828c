// SPDX-License-Identifier: Apache-2.0
// phasor — helpers shared by the shape plug-ins: the parameters every shape takes (material,
// to_world), error relocation for loaders and meshes from the geometry cache.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "core/diagnostics.h"
#include "core/geometry/geometry_cache.h"
#include "core/render/material.h"
#include "core/params/dict.h"
#include "core/render/registry.h"
#include "core/geometry/shape.h"

namespace phasor::shape_common {

inline ParamSpec MaterialParam() {
    return P::Ref("material", "material",
                  "surface material (none: the shape only bounds a light or is black)");
}
inline ParamSpec ToWorldParam() {
    return P::Transform("to_world", "object-to-world transform (default: identity)");
}

/// Assigns the `material` reference (the BuildContext owns referenced objects for the scene's
/// lifetime, so the raw pointer stays valid).
template <typename S>
std::unique_ptr<Shape> Finish(std::unique_ptr<S> shape, const ParamDict &d, BuildContext &ctx) {
    if (d.Has("material")) shape->material = ctx.GetRef<Material>(d, "material").get();
    if (d.Has("to_world")) shape->objectToWorld = ctx.GetTransform(d, "to_world");
    return shape;
}

/// Runs `f`; a phasor::Error without a location (from a loader or a geometry constructor) is
/// re-thrown at the location of parameter `param`, keeping its message (which names the file).
template <typename F>
auto AtParam(const ParamDict &d, const std::string &param, F &&f) -> decltype(f()) {
    try {
        return f();
    } catch (const Error &e) {
        if (e.Loc().Known()) throw;
        Error relocated(d.Loc(param), e.Message());
        relocated.notes = e.notes;
        throw relocated;
    }
}

/// A mesh shape S over the process-wide cached mesh of the key `makeKey()` returns, built by
/// `build()` (a TriangleMesh in world space) if no scene or recent use holds it; an error without
/// a location (a file that cannot be read, a loader's) is reported at parameter `param`.
template <typename S, typename MakeKey, typename Build>
std::unique_ptr<S> CachedMeshShape(const ParamDict &d, const std::string &param, MakeKey &&makeKey, Build &&build) {
    return AtParam(d, param, [&] { return std::make_unique<S>(CachedMesh(makeKey(), build)); });
}

}  // namespace phasor::shape_common
