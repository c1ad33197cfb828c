// SPDX-License-Identifier: Apache-2.0
// phasor — the plug-in registry: every family's table of plug-ins, looked up by name
// (docs/architecture.md, "Plug-ins"). Building a scene from them is BuildContext's
// (core/params/build_context.h, included here: a plug-in's Create takes one).
//
// A plug-in is one .cpp file holding a class with
//     static const Schema &GetSchema();
//     static std::unique_ptr<Interface> Create(const ParamDict &, BuildContext &);
// ending in PHASOR_EXPORT_PLUGIN(Interface, Class), plus one line in its directory's
// CMakeLists.txt:  phasor_add_plugin(<family> <scene name> <Class> <file.cpp>)
// which adds the file to the build and the class to a generated table that the registry reads.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/params/build_context.h"
#include "core/params/dict.h"
#include "core/params/schema.h"
#include "core/plugin_families.h"

namespace phasor {

#define PHASOR_DECLARE_INTERFACE(Keyword, family, Interface, Example) class Interface;
PHASOR_PLUGIN_FAMILIES(PHASOR_DECLARE_INTERFACE)
#undef PHASOR_DECLARE_INTERFACE
class BuildContext;

template <typename T>
struct PluginEntry {
    const char *name;  // scene name, e.g. "sphere"
    const Schema &(*schema)();
    std::unique_ptr<T> (*create)(const ParamDict &, BuildContext &);
    /// 2–5 parameter sets for the generic contract tests (empty if the class defines no
    /// `static std::vector<ParamDict> TestPresets()`).
    std::vector<ParamDict> (*presets)();
    /// The cases of the integrator contract suite (tests/integrators/integrator_contract_test.cpp)
    /// the class supports, from its `static std::vector<std::string> ContractCases()`; nullopt if
    /// it declares none (an integrator without it fails that suite; other families have none).
    std::optional<std::vector<std::string>> (*contractCases)();
    /// True for the family's default plug-in, the one used when a scene names none (the `ray`
    /// integrator, the `sobol` sampler): the class's `static constexpr bool IsDefault = true`.
    bool (*isDefault)();
};

/// The class's TestPresets() if it has one.
template <typename C>
std::vector<ParamDict> PresetsOf() {
    if constexpr (requires { C::TestPresets(); }) return C::TestPresets();
    else return {};
}

/// The class's ContractCases() if it has one.
template <typename C>
std::optional<std::vector<std::string>> ContractCasesOf() {
    if constexpr (requires { C::ContractCases(); }) return C::ContractCases();
    else return std::nullopt;
}

/// The class's IsDefault if it has one.
template <typename C>
bool IsDefaultOf() {
    if constexpr (requires { C::IsDefault; }) return C::IsDefault;
    else return false;
}

/// Registry of one plug-in family. The entries come from the generated plug-in tables.
template <typename T>
struct Registry {
    static const char *Family();
    static const std::vector<PluginEntry<T>> &Entries();
    static const PluginEntry<T> *Find(const std::string &name) {
        for (const auto &e : Entries())
            if (name == e.name) return &e;
        return nullptr;
    }
    /// The family's default plug-in (PluginEntry::isDefault), nullptr if it has none.
    static const PluginEntry<T> *Default() {
        for (const auto &e : Entries())
            if (e.isDefault()) return &e;
        return nullptr;
    }
    static std::vector<std::string> Names() {
        std::vector<std::string> v;
        for (const auto &e : Entries()) v.push_back(e.name);
        return v;
    }
    /// Adds a plug-in compiled outside the tree's tables (a test kernel, an application embedding
    /// phasor), normally through PHASOR_REGISTER_PLUGIN at static-initialisation time. Throws
    /// phasor::Error if the family already has a plug-in of that name.
    static void Register(const PluginEntry<T> &e) {
        if (Find(e.name)) throw Error(std::string("duplicate ") + Family() + " plug-in '" + e.name + "'");
        // Entries() is a function-local static that is not const (render/registry.cpp).
        const_cast<std::vector<PluginEntry<T>> &>(Entries()).push_back(e);
    }
};

/// Every family of core/plugin_families.h, in its order: names and the schemas of its plug-ins.
struct FamilyInfo {
    std::string keyword;  // as written in scene files: "Material"
    std::string family;   // "material"
    std::vector<const Schema *> schemas;
};
std::vector<FamilyInfo> AllFamilies();
/// The schema of a plug-in by family ("material" or "Material") and name, or nullptr.
const Schema *FindSchema(const std::string &family, const std::string &name);

/// Type-erased access to one family's registry (what BuildContext needs to build an entity or a
/// call of any family).
struct FamilyOps {
    const char *keyword;  // "Material"
    const char *family;   // "material"
    /// The schema of plug-in `type`, or nullptr if the family has none of that name.
    const Schema *(*schema)(const std::string &type);
    /// Creates plug-in `type` and gives the object (if its interface has a `name`) `displayName`.
    std::shared_ptr<void> (*create)(const std::string &type, const ParamDict &, BuildContext &,
                                    const std::string &displayName);
    std::vector<std::string> (*names)();
};
/// A family by name ("material"), scene keyword ("Material") or "kernel"; nullptr if none.
const FamilyOps *FindFamilyOps(const std::string &familyOrKeyword);

}  // namespace phasor

/// Registers a plug-in class at static-initialisation time under scene name `name` (inside
/// namespace phasor), for plug-ins that are not in the generated tables (e.g. test kernels in
/// tests/): one line at the end of the file instead of PHASOR_EXPORT_PLUGIN + the CMake line.
#define PHASOR_REGISTER_PLUGIN(Interface, Class, name)                                           \
    [[maybe_unused]] static const bool PhasorRegistered_##Class = [] {                           \
        Registry<Interface>::Register({name, &Class::GetSchema, &Class::Create, &PresetsOf<Class>, &ContractCasesOf<Class>, \
                                      &IsDefaultOf<Class>});                                     \
        return true;                                                                             \
    }()

/// Ends a plug-in file (inside namespace phasor): defines the functions the generated table
/// refers to.
#define PHASOR_EXPORT_PLUGIN(Interface, Class)                                                 \
    const Schema &PhasorSchema_##Class() { return Class::GetSchema(); }                        \
    std::unique_ptr<Interface> PhasorCreate_##Class(const ParamDict &d, BuildContext &c) {     \
        return Class::Create(d, c);                                                            \
    }                                                                                          \
    std::vector<ParamDict> PhasorPresets_##Class() { return PresetsOf<Class>(); }              \
    std::optional<std::vector<std::string>> PhasorContractCases_##Class() {                    \
        return ContractCasesOf<Class>();                                                       \
    }                                                                                          \
    bool PhasorIsDefault_##Class() { return IsDefaultOf<Class>(); }
