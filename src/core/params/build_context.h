// SPDX-License-Identifier: Apache-2.0
// phasor — BuildContext: turns a scene description into plug-in objects, and resolves the values a
// plug-in reads beyond plain numbers (docs/architecture.md, "From a scene value to a plug-in").
//
// For each entity: look the type up in the registry (core/render/registry.h), validate its
// ParamDict against the schema, call the plug-in's Create, report parameters given but never read.
// Create reads numbers from the dictionary and everything else here: files, spectra, complex
// indices, transforms, constant-or-texture values, references (@name, built on demand, so they
// may point forward) and calls (blackbody(5800 K): a plug-in built from the call's arguments).
//
// Part of the `phasor` library, not of the base: resolving a reference or a call creates a
// plug-in through the registry's tables, and textures are render-layer interfaces.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/diagnostics.h"
#include "core/params/dict.h"
#include "core/params/scene_desc.h"
#include "core/render/texture.h"

namespace phasor {

template <typename T>
struct Registry;  // core/render/registry.h: GetRef<T> names T's family through it
class ComplexSpectrum;

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
    /// The texture a constant-or-texture parameter names.
    std::shared_ptr<const Texture> ResolveTexture(const ParamDict &dict, const std::string &name);
    /// Throws (at the parameter) when the texture's range leaves the spec's; called after the
    /// kind and dimension checks, so that a texture of the wrong kind is reported as such.
    void CheckTextureRange(const ParamDict &dict, const std::string &name, const Texture &tex) const;
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
