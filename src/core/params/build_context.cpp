// SPDX-License-Identifier: Apache-2.0
#include "core/params/build_context.h"

#include <algorithm>
#include <cstdio>

#include "core/render/registry.h"
#include "core/spectrum/complex_spectrum.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

BuildContext::BuildContext(const SceneDesc &desc, Diagnostics &diag) : desc_(desc), diag_(diag) {
    state_.assign(desc.entities.size(), 0);
    byIndex_.resize(desc.entities.size());
    for (std::size_t i = 0; i < desc.entities.size(); ++i) {
        const SceneEntity &e = desc.entities[i];
        if (e.name.empty()) continue;
        auto [it, inserted] = byName_.emplace(e.name, i);
        if (!inserted) {
            const SceneEntity &first = desc.entities[it->second];
            diag_.Error(e.nameLoc.Known() ? e.nameLoc : e.loc, "'" + e.name + "' is already defined",
                        {Diagnostic{Severity::Note, first.nameLoc.Known() ? first.nameLoc : first.loc,
                                    "previous definition is here", {}}});
        }
    }
}

BuildContext::~BuildContext() = default;

std::filesystem::path BuildContext::ResolveFile(const ParamDict &dict, const std::string &name) const {
    const Value &v = dict.GetValue(name);
    std::filesystem::path p(v.text);
    FileLoc loc = dict.Loc(name);
    if (p.is_relative()) {
        std::string base = loc.file.empty() ? desc_.sourceFile : loc.file;
        if (!base.empty()) p = std::filesystem::path(base).parent_path() / p;
    }
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec))
        throw Error(loc, "cannot open '" + p.string() + "': " +
                             (std::filesystem::exists(p, ec) ? "not a regular file" : "no such file"));
    return p;
}

std::shared_ptr<const Spectrum> BuildContext::GetSpectrum(const ParamDict &dict, const std::string &name) {
    return SpectrumFromValue(dict.GetValue(name));
}

std::shared_ptr<const Spectrum> BuildContext::SpectrumFromValue(const Value &v) {
    switch (v.kind) {
        case Value::Kind::Number:
            if (!v.dim.IsNone())
                throw Error(v.loc, "a spectrum given as a number must be a plain number; got " + v.DescribeKind());
            // Every spectrum is an emission, a reflectance or an optical constant: never negative
            // (a negative emitter would only be discarded sample by sample at render time).
            if (!(v.number >= 0))
                throw Error(v.loc, "a spectrum cannot be negative; got " + v.ToString() + " (give a value >= 0)");
            return std::make_shared<ConstantSpectrum>(v.number);
        case Value::Kind::Ref: return std::static_pointer_cast<const Spectrum>(Resolve(v, "spectrum"));
        case Value::Kind::Call: return std::static_pointer_cast<const Spectrum>(CreateFromCall(v, "spectrum"));
        default: throw Error(v.loc, "expected a spectrum; got " + v.DescribeKind());
    }
}

namespace {

Vec3 VectorArg(const Value &v, Dim dim, const std::string &what) {
    if (v.kind != Value::Kind::List || v.items.size() != 3)
        throw Error(v.loc, what + " expects a list of 3 numbers; got " + v.DescribeKind());
    Vec3 r;
    for (int i = 0; i < 3; ++i) {
        const Value &it = v.items[i];
        if (it.kind != Value::Kind::Number || it.dim != dim)
            throw Error(it.loc.Known() ? it.loc : v.loc,
                        what + " expects " + dim.Describe() + " components; got " + it.DescribeKind());
        r[i] = it.number;
    }
    return r;
}

// Binds a call's arguments to named slots: positional arguments fill `order` in turn.
std::vector<const Value *> BindArgs(const Value &call, const std::vector<std::string> &order) {
    std::vector<const Value *> slots(order.size(), nullptr);
    std::size_t next = 0;
    for (std::size_t i = 0; i < call.items.size(); ++i) {
        const std::string &an = call.argNames[i];
        std::size_t slot;
        if (an.empty()) {
            slot = next++;
            if (slot >= order.size())
                throw Error(call.items[i].loc.Known() ? call.items[i].loc : call.loc,
                            "too many arguments to '" + call.text + "'");
        } else {
            slot = order.size();
            for (std::size_t j = 0; j < order.size(); ++j)
                if (order[j] == an) slot = j;
            if (slot == order.size()) {
                std::string s = Suggest(an, order);
                throw Error(call.items[i].loc.Known() ? call.items[i].loc : call.loc,
                            "'" + call.text + "' has no argument '" + an + "'" +
                                (s.empty() ? "" : "; did you mean '" + s + "'?"));
            }
        }
        if (slots[slot])
            throw Error(call.items[i].loc.Known() ? call.items[i].loc : call.loc,
                        "argument '" + order[slot] + "' of '" + call.text + "' given twice");
        slots[slot] = &call.items[i];
    }
    return slots;
}

const Value &Need(const std::vector<const Value *> &slots, std::size_t i, const Value &call,
                  const std::vector<std::string> &order) {
    if (!slots[i]) throw Error(call.loc, "'" + call.text + "' needs argument '" + order[i] + "'");
    return *slots[i];
}

}  // namespace

Transform BuildContext::TransformFromValue(const Value &v) {
    if (v.kind == Value::Kind::List) {
        // Written order = application order: [a, b] means b(a(p)).
        Transform t;
        for (const Value &it : v.items) t = TransformFromValue(it) * t;
        return t;
    }
    if (v.kind != Value::Kind::Call) throw Error(v.loc, "expected a transform; got " + v.DescribeKind());
    const std::string &f = v.text;
    try {
        if (f == "translate") {
            static const std::vector<std::string> order = {"offset"};
            auto s = BindArgs(v, order);
            return Transform::Translate(VectorArg(Need(s, 0, v, order), Dim::Length(), "translate"));
        }
        if (f == "scale") {
            static const std::vector<std::string> order = {"factor"};
            auto s = BindArgs(v, order);
            const Value &a = Need(s, 0, v, order);
            if (a.kind == Value::Kind::Number && a.dim.IsNone())
                return Transform::Scale(Vec3(a.number, a.number, a.number));
            return Transform::Scale(VectorArg(a, Dim::None(), "scale"));
        }
        if (f == "rotate") {
            static const std::vector<std::string> order = {"angle", "axis"};
            auto s = BindArgs(v, order);
            const Value &a = Need(s, 0, v, order);
            if (a.kind != Value::Kind::Number || a.dim != Dim::Angle())
                throw Error(a.loc.Known() ? a.loc : v.loc, "rotate expects an angle (e.g. 30 deg); got " +
                                                               a.DescribeKind());
            return Transform::Rotate(a.number, VectorArg(Need(s, 1, v, order), Dim::None(), "rotate axis"));
        }
        if (f == "lookat") {
            static const std::vector<std::string> order = {"eye", "target", "up"};
            auto s = BindArgs(v, order);
            Vec3 up = s[2] ? VectorArg(*s[2], Dim::None(), "lookat up") : Vec3(0, 1, 0);
            return Transform::LookAt(VectorArg(Need(s, 0, v, order), Dim::Length(), "lookat eye"),
                                     VectorArg(Need(s, 1, v, order), Dim::Length(), "lookat target"), up);
        }
        if (f == "matrix") {
            static const std::vector<std::string> order = {"values"};
            auto s = BindArgs(v, order);
            const Value &a = Need(s, 0, v, order);
            if (a.kind != Value::Kind::List || (a.items.size() != 16 && a.items.size() != 12))
                throw Error(a.loc.Known() ? a.loc : v.loc, "matrix expects 12 or 16 numbers (row-major)");
            Transform::Mat m{};
            m[3][3] = 1;
            for (std::size_t i = 0; i < a.items.size(); ++i) {
                if (a.items[i].kind != Value::Kind::Number)
                    throw Error(a.items[i].loc, "matrix entries must be numbers");
                m[i / 4][i % 4] = a.items[i].number;  // translation column in metres (plain numbers)
            }
            if (m[3][0] != 0 || m[3][1] != 0 || m[3][2] != 0 || m[3][3] != 1)
                throw Error(a.loc, "matrix must be affine (last row 0 0 0 1)");
            return Transform(m);
        }
    } catch (const std::invalid_argument &e) {
        throw Error(v.loc, std::string(e.what()));
    }
    std::string s = Suggest(f, {"translate", "scale", "rotate", "lookat", "matrix"});
    throw Error(v.loc, "unknown transform '" + f + "'" + (s.empty() ? "" : "; did you mean '" + s + "'?"));
}

std::shared_ptr<const ComplexSpectrum> BuildContext::ComplexSpectrumFromValue(const Value &v) {
    switch (v.kind) {
        case Value::Kind::Complex: return std::make_shared<ConstantComplexSpectrum>(v.complex);
        case Value::Kind::Number:
            if (!v.dim.IsNone())
                throw Error(v.loc, "a complex index given as a number must be a plain number; got " + v.DescribeKind());
            return std::make_shared<ConstantComplexSpectrum>(Complex(v.number, 0));
        case Value::Kind::String: {
            if (const NamedIndex *m = FindNamedIndex(v.text)) return std::make_shared<NamedComplexSpectrum>(*m);
            const std::string s = Suggest(v.text, NamedIndexNames());
            throw Error(v.loc, "unknown material \"" + v.text + "\"" + (s.empty() ? "" : "; did you mean \"" + s + "\"?"));
        }
        case Value::Kind::Call:
            if (v.text == "nk") {
                static const std::vector<std::string> order = {"n", "k"};
                auto slots = BindArgs(v, order);
                auto k = slots[1] ? SpectrumFromValue(*slots[1]) : nullptr;
                return std::make_shared<NkSpectrum>(SpectrumFromValue(Need(slots, 0, v, order)), std::move(k));
            }
            if (!Registry<Spectrum>::Find(v.text)) {
                std::vector<std::string> names = Registry<Spectrum>::Names();
                names.push_back("nk");
                const std::string s = Suggest(v.text, names);
                throw Error(v.loc, "unknown complex spectrum '" + v.text + "' (nk(n = …, k = …) or a spectrum)" +
                                       (s.empty() ? "" : "; did you mean '" + s + "'?"));
            }
            return std::make_shared<NkSpectrum>(SpectrumFromValue(v), nullptr);
        case Value::Kind::Ref: return std::make_shared<NkSpectrum>(SpectrumFromValue(v), nullptr);
        default: throw Error(v.loc, "expected a complex index; got " + v.DescribeKind());
    }
}

std::shared_ptr<const ComplexSpectrum> BuildContext::GetComplexSpectrum(const ParamDict &dict, const std::string &name) {
    auto s = ComplexSpectrumFromValue(dict.GetValue(name));
    // A passive medium over the visible and near infrared (the range every kernel checked before).
    for (double l = 360e-9; l <= 1000e-9; l += 5e-9) {
        const Complex n = s->Eval(l);
        if (!(n.real() > 0) || !(n.imag() >= 0)) {
            char at[96];
            std::snprintf(at, sizeof at, "%.6g%+.6gi at %.0f nm", n.real(), n.imag(), l * 1e9);
            throw Error(dict.Loc(name), "'" + name + "' must be n + iκ with n > 0 and κ ≥ 0; it is " + at);
        }
    }
    return s;
}

Transform BuildContext::GetTransform(const ParamDict &dict, const std::string &name) {
    if (!dict.Has(name)) {
        const Schema *s = dict.GetSchema();
        const ParamSpec *p = s ? s->Find(name) : nullptr;
        if (!p || !p->defaultValue) return Transform();
    }
    return TransformFromValue(dict.GetValue(name));
}

std::string BuildContext::FamilyOf(const Value &ref) const {
    auto it = byName_.find(ref.text);
    if (ref.kind != Value::Kind::Ref || it == byName_.end()) return "";
    const FamilyOps *ops = FindFamilyOps(desc_.entities[it->second].keyword);
    return ops ? ops->family : "";
}

std::shared_ptr<const Texture> BuildContext::ResolveTexture(const ParamDict &dict, const std::string &name) {
    return std::static_pointer_cast<const Texture>(Resolve(dict.GetValue(name), "texture"));
}

void BuildContext::CheckTextureRange(const ParamDict &dict, const std::string &name, const Texture &tex) const {
    const Value &v = dict.GetValue(name);
    const ParamSpec *spec = dict.GetSchema() ? dict.GetSchema()->Find(name) : nullptr;
    if (!spec) return;
    const double lo = tex.MinValue(), hi = tex.MaxValue();
    const bool tooLow = spec->minValue && (spec->minExclusive ? !(lo > *spec->minValue) : !(lo >= *spec->minValue));
    const bool tooHigh = spec->maxValue && !(hi <= *spec->maxValue);
    if (tooLow || tooHigh) {
        const Dim d = tex.ScalarDim().value_or(Dim::None());
        std::string range;
        if (spec->minValue)
            range += std::string(spec->minExclusive ? "> " : "≥ ") + Value::Number(*spec->minValue, d).ToString();
        if (spec->maxValue)
            range += (range.empty() ? "" : " and ") + std::string("≤ ") + Value::Number(*spec->maxValue, d).ToString();
        throw Error(v.loc, "'" + name + "' must be " + range + " everywhere, but texture '@" + v.text +
                               "' ranges over [" + Value::Number(lo, d).ToString() + ", " +
                               Value::Number(hi, d).ToString() + "]");
    }
}

FloatTexture BuildContext::GetFloatTexture(const ParamDict &dict, const std::string &name) {
    const Value &v = dict.GetValue(name);
    const ParamSpec *spec = dict.GetSchema() ? dict.GetSchema()->Find(name) : nullptr;
    const bool anyDim = spec && spec->anyDim;
    const Dim want = spec ? spec->dim : Dim::None();
    const std::string expected = anyDim ? "a number" : want.Describe();
    if (v.kind == Value::Kind::Number) {
        if (!anyDim && v.dim != want)
            throw Error(v.loc, "'" + name + "' expects " + expected + "; got " + v.DescribeKind());
        return FloatTexture(v.number, v.dim);
    }
    if (v.kind != Value::Kind::Ref)
        throw Error(v.loc, "'" + name + "' expects " + expected + " or @texture; got " + v.DescribeKind());
    std::shared_ptr<const Texture> tex = ResolveTexture(dict, name);
    const std::optional<Dim> d = tex->ScalarDim();
    if (!d || (!anyDim && *d != want))
        throw Error(v.loc, "'" + name + "' expects " + expected + " (or a texture of " + expected + "); texture '@" +
                               v.text + "' yields " + tex->DescribeYield());
    CheckTextureRange(dict, name, *tex);
    return FloatTexture(std::static_pointer_cast<const ScalarTexture>(tex));
}

SpectrumTexture BuildContext::GetSpectrumTexture(const ParamDict &dict, const std::string &name) {
    const Value &v = dict.GetValue(name);
    if (v.kind != Value::Kind::Ref) return SpectrumTexture(SpectrumFromValue(v));
    // A Ref parameter (e.g. diffuse's `texture`) names only its own family.
    const ParamSpec *spec = dict.GetSchema() ? dict.GetSchema()->Find(name) : nullptr;
    const std::string allowed = spec && spec->kind == ParamKind::Ref ? spec->refFamily : "spectrum or texture";
    const std::string family = FamilyOf(v);
    if (family == "spectrum" && allowed != "texture") return SpectrumTexture(SpectrumFromValue(v));
    if (family != "texture") Resolve(v, allowed);  // throws: undefined, or of another family
    std::shared_ptr<const Texture> tex = ResolveTexture(dict, name);
    if (std::shared_ptr<const Texture> colour = tex->AsColour()) tex = std::move(colour);  // read as a colour
    if (const std::optional<Dim> d = tex->ScalarDim(); d && !d->IsNone())
        throw Error(v.loc, "'" + name + "' expects a spectrum or a dimensionless texture; texture '@" + v.text +
                               "' yields " + tex->DescribeYield());
    CheckTextureRange(dict, name, *tex);
    return SpectrumTexture(std::move(tex));
}

std::shared_ptr<void> BuildContext::CreateFromCall(const Value &call, const std::string &family) {
    const FamilyOps *ops = FindFamilyOps(family);
    const Schema *schema = ops ? ops->schema(call.text) : nullptr;
    if (!schema) {
        std::string s = ops ? Suggest(call.text, ops->names()) : "";
        throw Error(call.loc, "unknown " + family + " '" + call.text + "'" +
                                  (s.empty() ? "" : "; did you mean '" + s + "'?"));
    }
    // Bind positional arguments to the schema's parameters in order.
    auto dict = std::make_unique<ParamDict>(call.loc);
    std::vector<std::string> order = schema->Names();
    std::size_t next = 0;
    for (std::size_t i = 0; i < call.items.size(); ++i) {
        std::string an = call.argNames[i];
        if (an.empty()) {
            if (next >= order.size())
                throw Error(call.items[i].loc.Known() ? call.items[i].loc : call.loc,
                            "too many arguments to '" + call.text + "'");
            an = order[next++];
        }
        if (!dict->Add(an, call.items[i], call.items[i].loc))
            throw Error(call.items[i].loc.Known() ? call.items[i].loc : call.loc,
                        "argument '" + an + "' of '" + call.text + "' given twice");
    }
    std::size_t errors = diag_.ErrorCount();
    if (!dict->Validate(*schema, diag_) || diag_.ErrorCount() > errors)
        throw Error::Consequence(call.loc);  // the arguments' errors were reported
    std::shared_ptr<void> obj = ops->create(call.text, *dict, *this, AnonymousName(call.text, call.loc));
    dict->ReportUnused(diag_, family + " '" + call.text + "'");
    callDicts_.push_back(std::move(dict));
    return obj;
}

std::shared_ptr<void> BuildContext::Resolve(const Value &ref, const std::string &family) {
    if (ref.kind != Value::Kind::Ref) throw Error(ref.loc, "expected a reference (@name); got " + ref.DescribeKind());
    auto it = byName_.find(ref.text);
    if (it == byName_.end() && (desc_.namesLost || desc_.unavailable.count(ref.text)))
        throw Error::Consequence(ref.loc);
    if (it == byName_.end()) {
        std::vector<std::string> names;
        for (const auto &[n, i] : byName_) names.push_back(n);
        std::sort(names.begin(), names.end());  // deterministic suggestion on ties
        std::string s = Suggest(ref.text, names);
        throw Error(ref.loc, "'@" + ref.text + "' is not defined" + (s.empty() ? "" : "; did you mean '@" + s + "'?"));
    }
    const SceneEntity &e = desc_.entities[it->second];
    const FamilyOps *ops = FindFamilyOps(e.keyword);
    if (!ops || ops->family != family)
        throw Error(ref.loc, "'@" + ref.text + "' is " + (ops ? std::string("a ") + ops->family : e.keyword) +
                                 ", but a " + family + " is expected");
    std::shared_ptr<void> obj = BuildEntity(it->second);
    if (!obj) throw Error::Consequence(ref.loc);  // its error was reported
    return obj;
}

std::shared_ptr<void> BuildContext::BuildEntity(std::size_t index) {
    if (state_[index] == 2) return byIndex_[index];
    const SceneEntity &e = desc_.entities[index];
    if (state_[index] == 1) throw Error(e.loc, "'" + e.name + "' refers to itself (reference cycle)");
    state_[index] = 1;
    std::shared_ptr<void> obj;
    const FamilyOps *ops = FindFamilyOps(e.keyword);
    std::string what = std::string(ops ? ops->family : e.keyword) + " '" + e.DisplayName() + "'" +
                       (e.name.empty() ? "" : " (" + e.type + ")");
    try {
        if (!ops) throw Error(e.loc, "unknown statement '" + e.keyword + "'");
        const Schema *schema = ops->schema(e.type);
        if (!schema) {
            std::string s = Suggest(e.type, ops->names());
            FileLoc loc = e.loc;
            throw Error(loc, "unknown " + std::string(ops->family) + " type \"" + e.type + "\"" +
                                 (s.empty() ? "" : "; did you mean \"" + s + "\"?"));
        }
        if (e.params.Validate(*schema, diag_)) {
            obj = ops->create(e.type, e.params, *this, e.DisplayName());
            e.params.ReportUnused(diag_, what);
        }
    } catch (const Error &err) {
        diag_.Report(err);
    } catch (const std::bad_alloc &) {
        diag_.Error(e.loc, "out of memory while creating " + what);
    }
    state_[index] = 2;
    byIndex_[index] = obj;
    if (obj) built_.push_back(Built{ops->family, obj, &e});
    return obj;
}

void BuildContext::BuildAll() {
    for (std::size_t i = 0; i < desc_.entities.size(); ++i) {
        if (desc_.entities[i].keyword == "Render") continue;
        BuildEntity(i);  // (past the error limit too: the count of errors stays true)
    }
}

const SceneEntity *BuildContext::EntityOf(const void *object) const {
    for (const Built &b : built_)
        if (b.object.get() == object) return b.entity;
    return nullptr;
}

const SceneEntity *BuildContext::RenderEntity() const {
    for (const SceneEntity &e : desc_.entities)
        if (e.keyword == "Render") return &e;
    return nullptr;
}

}  // namespace phasor
