// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: phasor.probe — `phasor probe` from Python, through the program's own
// measurement (app/probe.h: BuildProbedMaterial, ProbeKernel, ProbeCsv, StageProbeMap).
#include <pybind11/stl.h>

#include <cmath>

#include "app/probe.h"
#include "core/image/output_file.h"
#include "core/render/material.h"
#include "python/common.h"

namespace phasor::python {

namespace {

// A probe's result, with the scene it probed (kept alive) and what was asked.
struct PyProbe {
    std::shared_ptr<LoadedScene> scene;
    std::string material, type;
    ProbeRequest request;
    ProbeResult result;
};

}  // namespace

void BindProbe(py::module_ &m) {
    py::class_<PyProbe, std::shared_ptr<PyProbe>> cls(m, "ProbeResult", R"doc(
What phasor.probe measured (as `phasor probe` prints it): power fractions R and T with the
standard errors of their Monte-Carlo parts, and the near-delta lobes.)doc");
    cls.def_property_readonly("R", [](const PyProbe &p) { return p.result.R(); },
                              "Reflectance: every reflected lobe + the continuous reflection (power fraction).")
        .def_property_readonly("T", [](const PyProbe &p) { return p.result.T(); }, "Transmittance (power fraction).")
        .def_property_readonly("R_stderr", [](const PyProbe &p) { return p.result.seR; },
                               "Standard error of R (of its continuous, Monte-Carlo part).")
        .def_property_readonly("T_stderr", [](const PyProbe &p) { return p.result.seT; }, "Standard error of T.")
        .def_property_readonly(
            "parts",
            [](const PyProbe &p) {
                py::dict d;
                d["near_delta_R"] = p.result.discreteR;
                d["near_delta_T"] = p.result.discreteT;
                d["continuous_R"] = p.result.contR;
                d["continuous_T"] = p.result.contT;
                return d;
            },
            "R and T split into the near-delta lobes (exact) and the continuous ones (Monte Carlo).")
        .def_property_readonly("continuous", [](const PyProbe &p) { return p.result.continuous; },
                               "Whether the kernel has a continuous lobe for this light (the Monte Carlo ran).")
        .def_property_readonly("non_finite", [](const PyProbe &p) { return p.result.nonFinite; },
                               "Samples with a NaN or infinite weight (counted as 0): a kernel bug when > 0.")
        .def_property_readonly(
            "lobes",
            [](const PyProbe &p) {
                py::list out;
                for (const ProbeLobe &l : p.result.lobes) {
                    py::dict d;
                    d["kind"] = l.transmission ? "transmission" : "reflection";
                    d["order"] = l.id;
                    d["name"] = l.name;
                    d["theta_o"] = ProbeTheta(l.wo);
                    d["phi_o"] = ProbePhi(l.wo);
                    d["direction"] = py::make_tuple(l.wo.x, l.wo.y, l.wo.z);
                    d["efficiency"] = l.efficiency;
                    out.append(d);
                }
                return out;
            },
            R"doc(The near-delta lobes, one dict each: kind ("reflection" | "transmission"), order (the lobe's
id: a grating's order), name (the kernel's name of the lobe: the CSV's order column), theta_o and
phi_o [rad] (as the CSV), direction (x, y, z in the probe's frame: z = the normal, x = the
kernel's reference direction or dp/du) and efficiency (power).)doc")
        .def_property_readonly("csv", [](const PyProbe &p) { return ProbeCsv(p.result); },
                               "The CSV `phasor probe --csv` writes.")
        .def_property_readonly("material", [](const PyProbe &p) { return p.material; }, "The material's scene name.")
        .def_property_readonly("type", [](const PyProbe &p) { return p.type; }, "The material's plug-in.")
        .def_property_readonly("scene", [](const PyProbe &p) { return p.scene; }, "The Scene probed.")
        .def("__repr__", [](const PyProbe &p) {
            char buf[256];
            std::snprintf(buf, sizeof buf, "<phasor.ProbeResult %s (%s): R = %.6g +- %.2g, T = %.6g +- %.2g, %zu lobes>",
                          p.material.c_str(), p.type.c_str(), p.result.R(), p.result.seR, p.result.T(), p.result.seT,
                          p.result.lobes.size());
            return std::string(buf);
        });

    m.def(
        "probe",
        [](const py::object &sceneArg, const std::string &material, const py::object &theta, const py::object &lam,
           const py::object &phi, const py::object &uv, long long samples, long long seed, bool ray,
           const py::object &plot, const py::object &defines) {
            std::shared_ptr<LoadedScene> scene;
            ProbeRequest r;
            r.theta = Quantity(theta, Dim::Angle(), "theta", "30deg");
            r.phi = Quantity(phi, Dim::Angle(), "phi", "45deg");
            r.lambda = Quantity(lam, Dim::Length(), "lam", "550nm");
            if (r.theta < 0 || r.theta > Pi)
                throw py::value_error("'theta' must lie in [0deg, 180deg] (from the normal; above 90deg the light "
                                      "comes from below)");
            if (std::abs(std::cos(r.theta)) < 1e-6)
                throw py::value_error("'theta' is grazing (the light runs along the surface): no kernel scatters it; "
                                      "use an angle below or above 90deg");
            if (!(r.lambda > 0)) throw py::value_error("'lam' must be positive");
            if (!uv.is_none()) {
                const auto t = uv.cast<std::pair<double, double>>();
                r.uv = Vec2(t.first, t.second);
            }
            if (samples < 1) throw py::value_error("'samples' must be at least 1");
            if (seed < 0) throw py::value_error("'seed' must not be negative");
            r.samples = samples;
            r.seed = uint64_t(seed);
            r.rayOptics = ray;

            // A Scene, or a file of which only the material is built (a library without lights or
            // detector), as the program's probe builds it.
            Diagnostics diag;
            std::optional<SceneDesc> parsed;
            const SceneDesc *desc = nullptr;
            std::string path;
            if (py::isinstance<LoadedScene>(sceneArg)) {
                if (!defines.is_none()) throw py::value_error("'defines' applies to a scene file, not to a loaded Scene");
                scene = sceneArg.cast<std::shared_ptr<LoadedScene>>();
                desc = &scene->Desc();
                path = scene->Spec().path;
            } else {
                LoadSpec spec;
                spec.path = py::str(py::module_::import("os").attr("fspath")(sceneArg));
                AddDefines(spec, defines);
                path = spec.path;
                ParseOptions parse;
                parse.defines = spec.defines;
                parse.siDefines = spec.siDefines;
                {
                    py::gil_scoped_release release;
                    parsed = ParseSceneFile(spec.path, parse, diag);
                }
                if (!parsed || diag.HasErrors()) RaiseSceneError(diag, path);
                desc = &*parsed;
            }
            auto p = std::make_shared<PyProbe>();
            p->scene = scene;
            p->request = r;
            ProbedMaterial pm;
            try {
                {
                    py::gil_scoped_release release;
                    pm = BuildProbedMaterial(*desc, material, path, diag);
                }
                if (!pm.material) RaiseSceneError(diag, path);
                EmitWarnings(diag);
                p->material = pm.name;
                p->type = pm.type;
                {
                    py::gil_scoped_release release;
                    p->result = ProbeKernel(pm, r);
                }
                if (!plot.is_none()) {
                    const std::string out = py::str(py::module_::import("os").attr("fspath")(plot));
                    std::string staged;
                    {
                        py::gil_scoped_release release;
                        OutputFiles files;
                        staged = StageProbeMap(files, out, pm, r, p->result);
                        files.Commit();
                    }
                    if (staged != out)
                        EmitRenderWarning("'" + out + "' not drawn (matplotlib is missing); its data is in '" + staged + "'");
                }
            } catch (const Error &e) {
                RaisePhasorError(e);
            }
            if (p->result.nonFinite > 0)
                EmitRenderWarning(std::to_string(p->result.nonFinite) + " of " + std::to_string(samples) +
                                  " samples had a NaN or infinite weight (counted as 0): the kernel has a bug");
            return p;
        },
        py::arg("scene"), py::arg("material"), py::arg("theta"), py::arg("lam"), py::kw_only(), py::arg("phi") = 0.0,
        py::arg("uv") = py::none(), py::arg("samples") = 100000, py::arg("seed") = 0, py::arg("ray") = false,
        py::arg("plot") = py::none(), py::arg("defines") = py::none(), R"doc(
One kernel of a scene, as `phasor probe` measures it -> ProbeResult: light of vacuum wavelength
`lam` from (theta, phi) on the plane z = 0 (theta from the normal, above 90deg from below; phi from
the kernel's reference direction, e.g. a grating's grating vector, else dp/du), at texture
coordinates `uv` (default (0.5, 0.5)). R and T are power fractions: near-delta lobes exact,
continuous lobes by `samples` Monte-Carlo samples from `seed` with standard errors. ray=True asks for
the ray-optics limit. plot: a file for the angular map (matplotlib).

scene: a Scene, or a .wscene path of which only the material is built (a material library needs
no light or detector; `defines` as for load). Angles and lengths: "30deg", "550nm" or SI numbers.)doc");
}

}  // namespace phasor::python
