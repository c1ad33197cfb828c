// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: phasor.testing.check_kernel's C++ half — the generic kernel contract suite
// (tests/materials/kernel_contract_test.cpp, run through contract_harness.h) on one kernel.
#include <pybind11/stl.h>

#include "core/render/material.h"
#include "core/render/registry.h"
#include "python/common.h"
#include "python/contract_harness.h"

namespace phasor::python {

void BindTesting(py::module_ &m) {
    m.def(
        "_contract_domain",
        [] {
            const contract::Domain d = test::KernelContractDomain();
            return py::make_tuple(d.lambdas, d.incidents);
        },
        "The kernel contract suite's wavelengths [m] and incident directions (cos theta, phi).");

    m.def(
        "_check_kernel",
        [](const std::string &name, const std::vector<int> &lambdas, const std::vector<int> &incidents,
           double sampleScale) {
            const PluginEntry<Material> *entry = Registry<Material>::Find(name);
            if (!entry) {
                const std::string sug = Suggest(name, Registry<Material>::Names());
                throw py::value_error("no kernel named '" + name + "'" +
                                      (sug.empty() ? "" : "; did you mean '" + sug + "'?"));
            }
            if (entry->presets().empty())
                throw py::value_error("kernel '" + name + "' has no presets to check (give presets=[{...}, ...])");
            contract::Options o;
            o.kernel = name;
            o.lambdas = lambdas;
            o.incidents = incidents;
            o.sampleScale = sampleScale;
            o.fatal = [](const std::exception &e) {  // Ctrl-C ends the run; a kernel's other errors fail a check
                const auto *p = dynamic_cast<const py::error_already_set *>(&e);
                return p && p->matches(PyExc_KeyboardInterrupt);
            };
            const contract::Report r = test::RunKernelContract(o);
            py::list outcomes;
            for (const contract::Outcome &x : r.outcomes) {
                py::dict d;
                d["check"] = x.check;
                d["case"] = x.caseName;
                d["status"] = x.failed ? "failed" : x.skipped ? "skipped" : "passed";
                d["failures"] = x.failures;
                d["messages"] = x.messages;
                py::dict props;
                for (const auto &[k, v] : x.properties) props[py::str(k)] = v;
                d["properties"] = props;
                outcomes.append(d);
            }
            return py::make_tuple(r.cases, outcomes, r.alpha);
        },
        py::arg("name"), py::arg("lambdas"), py::arg("incidents"), py::arg("sample_scale"));
}

}  // namespace phasor::python
