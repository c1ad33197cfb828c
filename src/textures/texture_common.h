// SPDX-License-Identifier: Apache-2.0
// phasor — helpers shared by the scalar texture plug-ins: the dimension a texture's values share.
//
// A scalar texture takes its dimension from its values (`offset = 300 nm` makes a length
// texture): the values given must agree, and a value left at its default (0, 1 …) is read in the
// texture's dimension.
#pragma once

#include <initializer_list>
#include <optional>
#include <string>

#include "core/diagnostics.h"
#include "core/params/dict.h"
#include "core/units.h"

namespace phasor::texture_common {

/// One value of a scalar texture: its parameter name and the dimension it was given with
/// (nullopt: not given).
struct ValueDim {
    const char *name;
    std::optional<Dim> dim;
};

/// The dimension of the number parameter `name` as written, or nullopt if it is absent.
inline std::optional<Dim> GivenDim(const ParamDict &dict, const char *name) {
    if (const Param *p = dict.Find(name)) return p->value.dim;
    return std::nullopt;
}

/// The one dimension of the given values, or `fallback` if none was given. Throws phasor::Error
/// at the first value whose dimension differs from the first given one's, naming both.
inline Dim CommonDim(const ParamDict &dict, std::initializer_list<ValueDim> values, Dim fallback = Dim::None()) {
    const ValueDim *first = nullptr;
    for (const ValueDim &v : values) {
        if (!v.dim) continue;
        if (!first) {
            first = &v;
        } else if (*v.dim != *first->dim) {
            throw Error(dict.Loc(v.name), "'" + std::string(v.name) + "' is " + v.dim->Describe() + ", but '" +
                                              first->name + "' is " + first->dim->Describe() +
                                              ": the values of a texture share one dimension");
        }
    }
    return first ? *first->dim : fallback;
}

}  // namespace phasor::texture_common
