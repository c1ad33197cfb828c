// SPDX-License-Identifier: Apache-2.0
// phasor — plug-in registry and scene building (docs/architecture.md, "Plug-ins").
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
#include "core/params.h"
#include "core/plugin_families.h"
#include "core/render/texture.h"

namespace phasor {

#define PHASOR_DECLARE_INTERFACE(Keyword, family, Interface, Example) class Interface;
PHASOR_PLUGIN_FAMILIES(PHASOR_DECLARE_INTERFACE)
#undef PHASOR_DECLARE_INTERFACE
class ComplexSpectrum;
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

/// One entity of a scene description (the IR the parser produces; C++ code may build it too).
struct SceneEntity {
    std::string keyword;  // "Shape", "Light", … or "Render"
    std::string type;     // plug-in name ("sphere"); empty for Render
    std::string name;     // optional user name (defines @name)
    ParamDict params;
    FileLoc loc;          // location of the keyword
    FileLoc nameLoc;      // location of the name (for redefinition errors)

    /// How messages name the entity: its name, or `type@file:line` (file without directories)
    /// if it has none.
    std::string DisplayName() const;
};

/// A whole scene description, in source order.
struct SceneDesc {
    std::vector<SceneEntity> entities;
    std::string sourceFile;  // the top-level file ("" for C++-built scenes)

    /// Errors were reported while reading: `entities` holds only what was read cleanly, so that
    /// building it can report the remaining errors of the scene in the same run.
    bool incomplete = false;
    /// Names already reported (a block that failed to read, an undefined or disabled reference):
    /// a reference to one fails without a further error. With `namesLost` (text was skipped after a
    /// lexical error, or an Include after a limit), so does a reference to any unknown name.
    std::unordered_set<std::string> unavailable;
    bool namesLost = false;
};

/// Resolves references while plug-ins are created; owns every created object until the Scene
/// takes them. Referenced objects are built on demand, so references may point forward.
class BuildContext {
  public:
    BuildContext(const SceneDesc &desc, Diagnostics &diag);
    ~BuildContext();

    Diagnostics &Diag() { return diag_; }

    /// Resolves a `File` parameter relative to the directory of the file that wrote it.
    /// Throws phasor::Error if the file does not exist.
    std::filesystem::path ResolveFile(const ParamDict &dict, const std::string &name) const;
    /// A spectrum parameter: number → constant, call → a spectrum plug-in built from the call's
    /// arguments (positional arguments bind to the schema's parameters in order), @ref → named.
    std::shared_ptr<const Spectrum> GetSpectrum(const ParamDict &dict, const std::string &name);
    /// A spectrum from a Value (used by plug-ins whose parameters hold nested spectra).
    std::shared_ptr<const Spectrum> SpectrumFromValue(const Value &v);
    /// A ComplexSpectrum parameter (core/spectrum/complex_spectrum.h): n + iκ(λ) from a plain number or
    /// n+ik (constant), a named material ("Au"), a spectrum call or @ref (κ = 0), or
    /// nk(n = spectrum, k = spectrum) (k defaults to 0). Every kernel with an index reads it
    /// through this. Throws phasor::Error at the parameter if n ≤ 0 or κ < 0 anywhere in
    /// 360–1000 nm (a passive medium).
    std::shared_ptr<const ComplexSpectrum> GetComplexSpectrum(const ParamDict &dict, const std::string &name);
    std::shared_ptr<const ComplexSpectrum> ComplexSpectrumFromValue(const Value &v);
    /// A transform parameter: translate(v), rotate(angle, axis = v), scale(s | v),
    /// lookat(eye, target, up), matrix([16 numbers, row-major]), or a list applied in order
    /// (the first listed is applied first).
    Transform GetTransform(const ParamDict &dict, const std::string &name);
    /// A constant-or-texture scalar parameter (ParamKind::FloatTexture): a number → a constant;
    /// @ref → a scalar texture, whose dimension must be the spec's (unless the spec is AnyDim:
    /// then the value brings its own, FloatTexture::GetDim) and whose [MinValue, MaxValue] must
    /// lie in the spec's range. Throws phasor::Error naming both dimensions on a mismatch.
    FloatTexture GetFloatTexture(const ParamDict &dict, const std::string &name);
    /// A constant-or-texture spectral parameter (ParamKind::SpectrumTexture, also Spectrum and
    /// Ref-to-texture parameters): what GetSpectrum accepts, or @ref to a spectral or a
    /// dimensionless scalar texture (whose range must lie in the spec's). Throws phasor::Error.
    SpectrumTexture GetSpectrumTexture(const ParamDict &dict, const std::string &name);
    Transform TransformFromValue(const Value &v);

    /// The object a Ref parameter names; it must be of family T. Throws phasor::Error.
    template <typename T>
    std::shared_ptr<T> GetRef(const ParamDict &dict, const std::string &name) {
        return std::static_pointer_cast<T>(Resolve(dict.GetValue(name), Registry<T>::Family()));
    }
    template <typename T>
    std::vector<std::shared_ptr<T>> GetRefs(const ParamDict &dict, const std::string &name) {
        std::vector<std::shared_ptr<T>> out;
        const Value &v = dict.GetValue(name);
        if (v.kind == Value::Kind::Ref) out.push_back(std::static_pointer_cast<T>(Resolve(v, Registry<T>::Family())));
        else
            for (const Value &it : v.items) out.push_back(std::static_pointer_cast<T>(Resolve(it, Registry<T>::Family())));
        return out;
    }

    /// Creates every entity. Errors are reported to Diag(); objects that failed are skipped.
    void BuildAll();

    /// Objects created so far, by family, in creation order.
    template <typename T>
    std::vector<std::shared_ptr<T>> All() const {
        std::vector<std::shared_ptr<T>> out;
        for (const auto &o : built_)
            if (o.family == Registry<T>::Family() && o.object) out.push_back(std::static_pointer_cast<T>(o.object));
        return out;
    }
    /// The entity an object was created from (for locations in later errors).
    const SceneEntity *EntityOf(const void *object) const;
    /// The `Render` entity, if any.
    const SceneEntity *RenderEntity() const;
    const SceneDesc &Desc() const { return desc_; }

  private:
    struct Built {
        std::string family;
        std::shared_ptr<void> object;
        const SceneEntity *entity;
    };
    std::shared_ptr<void> Resolve(const Value &ref, const std::string &family);
    /// The family ("texture") of the entity a reference names; "" if it names none.
    std::string FamilyOf(const Value &ref) const;
    /// The texture a constant-or-texture parameter names, with its range checked against the spec.
    std::shared_ptr<const Texture> ResolveTexture(const ParamDict &dict, const std::string &name);
    std::shared_ptr<void> BuildEntity(std::size_t index);
    std::shared_ptr<void> CreateFromCall(const Value &call, const std::string &family);

    const SceneDesc &desc_;
    Diagnostics &diag_;
    std::unordered_map<std::string, std::size_t> byName_;
    std::vector<int> state_;  // 0 = not built, 1 = building, 2 = done
    std::vector<Built> built_;
    std::vector<std::shared_ptr<void>> byIndex_;
    std::vector<std::unique_ptr<ParamDict>> callDicts_;
};

}  // namespace phasor

/// Registers a plug-in class at static-initialisation time under scene name `name` (inside
/// namespace phasor), for plug-ins that are not in the generated tables (e.g. test kernels in
/// tests/): one line at the end of the file instead of PHASOR_EXPORT_PLUGIN + the CMake line.
#define PHASOR_REGISTER_PLUGIN(Interface, Class, name)                                           \
    [[maybe_unused]] static const bool PhasorRegistered_##Class = [] {                           \
        Registry<Interface>::Register({name, &Class::GetSchema, &Class::Create, &PresetsOf<Class>, &ContractCasesOf<Class>}); \
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
    }
