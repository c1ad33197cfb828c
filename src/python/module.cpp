// SPDX-License-Identifier: Apache-2.0
// phasor's Python module, phasor._phasor: the C++ half of the package `phasor` (python/phasor/),
// which re-exports it with the pure-Python parts (exceptions, phasor.testing). docs/python.md.
#include "python/common.h"

PYBIND11_MODULE(_phasor, m) {
    using namespace phasor::python;
    m.doc() = "phasor's C++ core (use the package `phasor`, which re-exports it).";
    BindScene(m);
    BindImage(m);
    BindRender(m);  // (adds Scene.render, Scene.render_many: after BindScene)
    BindPlugins(m);
    BindProbe(m);
    BindCompare(m);
    BindKernels(m);
    BindTesting(m);
}
