// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: diffraction kernels written in Python (phasor.Material subclasses,
// phasor.register_material; docs/python.md "Kernels in Python").
//
// A registered class becomes a plug-in of the `material` family like a C++ kernel: its schema is
// validated by BuildContext, scenes name it, every integrator that accepts its capabilities calls
// it, and the contract suite runs on it. PythonKernel adapts the Python methods to the Material
// interface of core/render/material.h; it is the one place that knows that interface.
//
// The Python kernel keeps a per-query view (python/phasor/_kernels.py documents it for users):
//   sample(wi, wl, u0, u) -> None | ScatterSample(wo, weight, pdf, lobe, near_delta, transmission, eta)
//   eval(wi, wo, wl) -> f [1/sr] (float, or one per carried wavelength), continuous lobes only
//   pdf(wi, wo, wl) -> solid-angle density of sample's continuous directions
//   list_lobes(wi, wl) -> [Lobe(id, wo, weight, prob, transmission, n_in, n_out, shift)]
// with directions as (x, y, z) tuples in the local shading frame (z = the normal, both pointing
// away from the surface) and wl the carried vacuum wavelengths [m], wl[0] the hero. Responses for
// polarisation (EvalLobe): a continuous lobe depolarises, a near-delta lobe does not polarise
// (Jones √a_j·I), since a Python kernel states scalar values only.
//
// The C++ side asks a kernel prepared per hit (Material::Prepare, docs/kernels.md): PythonKernel's
// Prepare places a PythonKernel::Prepared in the scratch buffer, which calls list_lobes once (the
// near-delta lobes are kept there as NearDeltaLobes) and passes Sample, Eval, Pdf on to sample,
// eval and pdf with that query's wi and wl.
//
// Threads: the render loop calls kernels from many threads; each call takes the GIL (so Python
// kernels run one at a time) and a Python exception propagates as py::error_already_set through
// the render loop (TBB rethrows it in the rendering thread), which stops the render; the module
// raises it again in Python.
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <deque>
#include <sstream>

#include "core/render/material.h"
#include "core/render/registry.h"
#include "python/common.h"

namespace phasor::python {

namespace {

/// The continuous lobe's id (Python kernels have one continuous lobe, the sum of their continuous
/// terms), apart from the ids a kernel gives its near-delta lobes.
constexpr int ContinuousLobeId = 1 << 20;

/// What a registered Python class is: its scene name, schema, class object and capabilities.
struct PythonKernelClass {
    std::string name;
    Schema schema;
    py::object cls;  // (never released: registrations live as long as the process)
    bool continuous = false, nearDelta = false, reciprocal = true;
    std::vector<ParamDict> presets;
};

/// Takes the GIL for one kernel call; keeps the calling thread's Python thread state from then on
/// (a render's threads call kernels millions of times; creating a thread state per call would cost
/// more than the call).
struct KernelGil {
    py::gil_scoped_acquire acquire;
    KernelGil() {
        thread_local bool kept = false;
        if (!kept) {
            acquire.inc_ref();
            kept = true;
        }
    }
};

py::tuple Dir(const Vec3 &w) { return py::make_tuple(w.x, w.y, w.z); }

py::tuple Wavelengths(const ScatterQuery &q) {
    py::tuple t(q.wl->Count());
    for (int i = 0; i < q.wl->Count(); ++i) t[i] = py::float_(q.wl->lambda[i]);
    return t;
}

Vec3 ToDir(const py::handle &h, const char *what) {
    const auto v = h.cast<std::array<double, 3>>();
    (void)what;
    return Vec3(v[0], v[1], v[2]);
}

/// A float or a sequence of one value per carried wavelength.
SampledSpectrum ToSpectrum(const py::handle &h, int count, const std::string &what) {
    SampledSpectrum s(0.0);
    if (py::isinstance<py::float_>(h) || py::isinstance<py::int_>(h)) return SampledSpectrum(h.cast<double>());
    const auto seq = py::reinterpret_borrow<py::sequence>(h);
    if (int(py::len(seq)) != count)
        throw py::value_error(what + ": a number, or one per carried wavelength (" + std::to_string(count) + "); got " +
                              std::to_string(py::len(seq)));
    for (int i = 0; i < count; ++i) s[i] = seq[i].cast<double>();
    return s;
}

class PythonKernel final : public Material {
  public:
    /// (copies what it needs of `k`: registering the name again must not change this kernel)
    PythonKernel(const PythonKernelClass &k, py::object instance)
        : k_{k.name, {}, {}, k.continuous, k.nearDelta, k.reciprocal, {}}, self_(std::move(instance)) {}
    ~PythonKernel() override {
        if (!Py_IsInitialized()) {
            self_.release();  // the interpreter is gone: nothing to release it to
            return;
        }
        py::gil_scoped_acquire gil;
        self_ = py::object();
    }

    /// The kernel at one hit: the Python near-delta lobes listed once (list_lobes, with the GIL),
    /// the other questions passed on to the Python methods as they are asked.
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        Prepared *p = scratch.New<Prepared>(q, *this);
        if (k_.nearDelta) p->List(scratch);
        return *p;
    }

    bool IsReciprocal() const override { return k_.reciprocal; }

    std::string ToString() const override {
        KernelGil gil;
        return "PythonKernel[ " + k_.name + ": " + py::repr(self_).cast<std::string>() + " ]";
    }

  private:
    /// The Python kernel prepared for one query. It lives in a ScratchBuffer, which runs no
    /// destructors, so it holds no Python object: the directions and wavelengths are made into
    /// tuples at each call, and the lobes are converted to NearDeltaLobes in the buffer.
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const ScatterQuery &q, const PythonKernel &k) : PreparedKernel(q), k_(k) {
            caps_ = (k.k_.continuous ? CapContinuous : 0u) | (k.k_.nearDelta ? CapNearDelta : 0u);
            if (k.k_.continuous) continuous_.Add(ContinuousLobeId);
        }

        /// Asks list_lobes once for this query; its lobes go into `scratch`.
        void List(ScratchBuffer &scratch) {
            KernelGil gil;
            const py::list lobes(k_.self_.attr("list_lobes")(Dir(q_.wi), Wavelengths(q_)));
            LobeList out(scratch, int(py::len(lobes)));
            for (py::handle h : lobes) {
                NearDeltaLobe &l = out.Add();
                const py::tuple t = py::reinterpret_borrow<py::tuple>(h);  // phasor.Lobe (a named tuple)
                l.id = t[0].cast<int>();
                const Vec3 wo = ToDir(t[1], "wo");
                l.SetWeight(ToSpectrum(t[2], q_.wl->Count(), "Lobe.weight"));
                l.prob = t[3].cast<double>();
                const bool transmission = t[4].cast<bool>();
                l.flags = ScatterNearDelta | (transmission ? ScatterTransmission : ScatterReflection);
                const double nIn = t[5].cast<double>(), nOut = t[6].cast<double>();
                const auto shift = t[7].cast<std::array<double, 2>>();
                l.shift = Vec2(shift[0], shift[1]);
                for (int i = 0; i < NumWavelengths; ++i) {
                    l.wo[i] = wo;
                    l.nIn[i] = nIn;
                    l.nOut[i] = nOut;
                }
            }
            lobes_ = out.Lobes();
        }

        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            LobeResponse r;
            if (lobe == ContinuousLobeId) {
                if (!(caps_ & CapContinuous)) return std::nullopt;
                const SampledSpectrum f = EvalContinuous(wo) * std::abs(wo.z);
                if (f.IsZero()) return std::nullopt;
                for (int i = 0; i < q_.wl->Count(); ++i) r.mueller[i] = Mueller::Depolarizer(f[i]);
                return r;
            }
            const NearDeltaLobe *l = FindLobe(lobe);
            if (!l || !SameDirection(l->wo[0], wo)) return std::nullopt;
            for (int i = 0; i < q_.wl->Count(); ++i) {
                r.jones[i] = Jones::Identity() * Complex(std::sqrt(l->Weight()[i]), 0);
                r.mueller[i] = Mueller::FromJones(r.jones[i]);
            }
            r.hasJones = true;
            return r;
        }

      private:
        std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const override {
            KernelGil gil;
            const py::object r = k_.self_.attr("sample")(Dir(q_.wi), Wavelengths(q_), u0, py::make_tuple(u.x, u.y));
            if (r.is_none()) return std::nullopt;
            // phasor.ScatterSample (a named tuple), or a plain (wo, weight, pdf) of a continuous lobe.
            const py::tuple t = py::reinterpret_borrow<py::tuple>(r);
            const std::size_t n = py::len(t);
            if (n != 3 && n != 7)
                throw py::value_error(k_.k_.name +
                                      ".sample() must return None, a phasor.ScatterSample or (wo, weight, pdf)");
            ScatterSample s;
            s.wo = ToDir(t[0], "wo");
            s.weight = ToSpectrum(t[1], q_.wl->Count(), "ScatterSample.weight");
            s.pdf = t[2].cast<double>();
            const bool nearDelta = n == 7 && t[4].cast<bool>();
            const bool transmission = n == 7 ? t[5].cast<bool>() : s.wo.z * q_.wi.z < 0;
            s.lobe = nearDelta ? t[3].cast<int>() : ContinuousLobeId;
            s.flags = (nearDelta ? ScatterNearDelta : ScatterDiffuse) |
                      (transmission ? ScatterTransmission : ScatterReflection);
            s.eta = n == 7 ? t[6].cast<double>() : 1.0;
            return s;
        }

        SampledSpectrum EvalContinuous(const Vec3 &wo) const override {
            if (!(caps_ & CapContinuous)) return SampledSpectrum(0.0);
            KernelGil gil;
            return ToSpectrum(k_.self_.attr("eval")(Dir(q_.wi), Dir(wo), Wavelengths(q_)), q_.wl->Count(), "eval()");
        }

        double PdfContinuous(const Vec3 &wo) const override {
            if (!(caps_ & CapContinuous)) return 0;
            KernelGil gil;
            return k_.self_.attr("pdf")(Dir(q_.wi), Dir(wo), Wavelengths(q_)).cast<double>();
        }

        const PythonKernel &k_;  // (outlives the buffer's kernels: the scene holds it)
    };

    PythonKernelClass k_;  // name and capabilities (no schema, class or presets)
    py::object self_;
};

// ---- registration --------------------------------------------------------------------------------
// The registry holds plain function pointers (core/render/registry.h PluginEntry), so each
// registered class gets one of a fixed number of slots, each slot its own functions.

constexpr int MaxPythonKernels = 64;
// Never destroyed (they hold Python objects, which cannot be released after the interpreter has
// ended); a deque, so that references to its elements stay valid.
std::deque<PythonKernelClass> &gClasses = *new std::deque<PythonKernelClass>;
std::array<PythonKernelClass *, MaxPythonKernels> gSlots{};

py::object ParamValue(const ParamSpec &spec, const ParamDict &d) {
    if (!d.Has(spec.name) && !spec.defaultValue) return py::none();
    switch (spec.kind) {
        case ParamKind::Integer: return py::int_(d.GetInt(spec.name));
        case ParamKind::Bool: return py::bool_(d.GetBool(spec.name));
        case ParamKind::String: return py::str(d.GetString(spec.name));
        default: return py::float_(d.GetNumber(spec.name));
    }
}

std::unique_ptr<Material> Create(const PythonKernelClass &k, const ParamDict &d, BuildContext &) {
    KernelGil gil;
    py::dict params;
    for (const ParamSpec &spec : k.schema.params) params[py::str(spec.name)] = ParamValue(spec, d);
    try {
        return std::make_unique<PythonKernel>(k, k.cls(params));
    } catch (py::error_already_set &e) {  // a refusal in __init__: an error at the scene entity
        throw Error(d.EntityLoc(), "material '" + k.name + "': " + std::string(py::str(e.value())));
    }
}

template <int I>
struct Slot {
    static const Schema &GetSchema() { return gSlots[I]->schema; }
    static std::unique_ptr<Material> Make(const ParamDict &d, BuildContext &c) { return Create(*gSlots[I], d, c); }
    static std::vector<ParamDict> Presets() { return gSlots[I]->presets; }
    static std::optional<std::vector<std::string>> Cases() { return std::nullopt; }
    static bool IsDefault() { return false; }  // (a scene always names its material)
};

template <int... I>
PluginEntry<Material> EntryOf(int slot, const char *name, std::integer_sequence<int, I...>) {
    PluginEntry<Material> e{name, nullptr, nullptr, nullptr, nullptr, nullptr};
    ((slot == I ? (e = {name, &Slot<I>::GetSchema, &Slot<I>::Make, &Slot<I>::Presets, &Slot<I>::Cases,
                        &Slot<I>::IsDefault},
                   0)
                : 0),
     ...);
    return e;
}

// A parameter spec from what phasor.param() recorded: (name, kind, default, min, max,
// min_exclusive, choices, required, doc).
ParamSpec SpecOf(const py::handle &h) {
    const py::tuple t = py::reinterpret_borrow<py::tuple>(h);
    const std::string name = t[0].cast<std::string>(), kind = t[1].cast<std::string>(), doc = t[8].cast<std::string>();
    static const std::map<std::string, Dim> dims = {{"number", Dim::None()}, {"length", Dim::Length()},
                                                   {"angle", Dim::Angle()},  {"area", Dim::Area()},
                                                   {"power", Dim::Power()},  {"temperature", Dim::Temperature()}};
    ParamSpec s;
    if (auto it = dims.find(kind); it != dims.end()) {
        s = P::Number(name, doc, it->second);
        if (!t[2].is_none()) s.Default(Value::Number(Quantity(t[2], it->second, name, "1"), it->second));
    } else if (kind == "integer") {
        s = P::Integer(name, doc);
        if (!t[2].is_none()) s.Default(Value::Integer(t[2].cast<long long>()));
    } else if (kind == "bool") {
        s = P::Bool(name, doc);
        if (!t[2].is_none()) s.Default(Value::Bool(t[2].cast<bool>()));
    } else if (kind == "string") {
        s = P::String(name, doc);
        if (!t[2].is_none()) s.Default(Value::String(t[2].cast<std::string>()));
        if (!t[6].is_none()) s.Choices(t[6].cast<std::vector<std::string>>());
    } else {
        throw py::value_error("parameter '" + name + "': unknown kind '" + kind +
                              "' (number, length, angle, area, power, temperature, integer, bool, string)");
    }
    if (!t[3].is_none()) s.Min(t[3].cast<double>(), t[5].cast<bool>());
    if (!t[4].is_none()) s.Max(t[4].cast<double>());
    if (t[7].cast<bool>()) s.Required();
    return s;
}

// A preset (a dict of parameter values) as a ParamDict: numbers are SI, strings scene text.
ParamDict PresetOf(const Schema &schema, const py::handle &h) {
    ParamDict d;
    for (auto [k, v] : py::reinterpret_borrow<py::dict>(h)) {
        const std::string name = k.cast<std::string>();
        const ParamSpec *spec = schema.Find(name);
        if (!spec) throw py::value_error("preset parameter '" + name + "' is not in the schema");
        switch (spec->kind) {
            case ParamKind::Integer: d.Set(name, Value::Integer(v.cast<long long>())); break;
            case ParamKind::Bool: d.Set(name, Value::Bool(v.cast<bool>())); break;
            case ParamKind::String: d.Set(name, Value::String(v.cast<std::string>())); break;
            default: d.Set(name, Value::Number(Quantity(v, spec->dim, name, "1"), spec->dim));
        }
    }
    return d;
}

}  // namespace

void BindKernels(py::module_ &m) {
    m.def(
        "_register_material",
        [](const std::string &name, const py::object &cls, const std::string &doc, const py::list &params,
           const py::list &presets, bool continuous, bool nearDelta, bool reciprocal) {
            if (!continuous && !nearDelta)
                throw py::value_error("material '" + name + "' defines neither eval() (continuous lobes) nor "
                                      "list_lobes() (near-delta lobes)");
            Schema schema{"material", name, doc, {}};
            for (py::handle p : params) schema.params.push_back(SpecOf(p));
            std::vector<ParamDict> ps;
            for (py::handle p : presets) ps.push_back(PresetOf(schema, p));
            auto define = [&](PythonKernelClass &k) {
                k.schema = std::move(schema);
                k.cls = cls;
                k.continuous = continuous;
                k.nearDelta = nearDelta;
                k.reciprocal = reciprocal;
                k.presets = std::move(ps);
            };
            // Registered before (a notebook cell run again): the new class replaces the old one
            // for scenes built from now on.
            for (PythonKernelClass &k : gClasses)
                if (k.name == name) return define(k);
            if (Registry<Material>::Find(name))
                throw py::value_error("material '" + name + "' is a built-in kernel; choose another name");
            if (gClasses.size() >= std::size_t(MaxPythonKernels))
                throw py::value_error("at most " + std::to_string(MaxPythonKernels) + " kernels can be registered from Python");
            PythonKernelClass &k = gClasses.emplace_back();
            k.name = name;
            define(k);
            const int slot = int(gClasses.size()) - 1;
            gSlots[std::size_t(slot)] = &k;
            Registry<Material>::Register(
                EntryOf(slot, k.name.c_str(), std::make_integer_sequence<int, MaxPythonKernels>{}));
        },
        py::arg("name"), py::arg("cls"), py::arg("doc"), py::arg("params"), py::arg("presets"), py::arg("continuous"),
        py::arg("near_delta"), py::arg("reciprocal"));

    m.def(
        "_set_presets",
        [](const std::string &name, const py::list &presets) {
            for (PythonKernelClass &k : gClasses)
                if (k.name == name) {
                    std::vector<ParamDict> ps;
                    for (py::handle p : presets) ps.push_back(PresetOf(k.schema, p));
                    k.presets = std::move(ps);
                    return;
                }
            throw py::value_error(Registry<Material>::Find(name)
                                      ? "'" + name + "' is a C++ kernel: its presets are its TestPresets()"
                                      : "no kernel named '" + name + "' is registered");
        },
        py::arg("name"), py::arg("presets"));
}

}  // namespace phasor::python
