// SPDX-License-Identifier: Apache-2.0
// phasor — the plug-in families, listed once (docs/architecture.md "Plug-in families").
//
// PHASOR_PLUGIN_FAMILIES(FAMILY) calls FAMILY(Keyword, family, Interface, Example) once per family:
//   Keyword    the statement keyword of .wscene files (`Material "dielectric" { … }`);
//   family     the family's name: phasor_add_plugin's first argument, every Schema's `family`,
//              `phasor list`, Registry<Interface>::Family();
//   Interface  the C++ interface class its plug-ins implement (Registry<Interface>);
//   Example    a plug-in of the family, named in parser messages.
// The registry (core/render/registry.cpp), the parser's keywords (parser/lexer.cpp, syntax.cpp)
// and cmake/PhasorPlugins.cmake (which reads the FAMILY( lines of this file, so keep one entry a
// line) all take the list from here. Adding a family is one line here, its interface header in
// core/render/registry.cpp and a tests/ case; tests/core/render/registry_test.cpp checks that
// every table agrees.
#pragma once

// clang-format off
#define PHASOR_PLUGIN_FAMILIES(FAMILY)                   \
    FAMILY(Spectrum,   spectrum,   Spectrum,   blackbody)    \
    FAMILY(Texture,    texture,    Texture,    checkerboard) \
    FAMILY(Material,   material,   Material,   dielectric)   \
    FAMILY(Shape,      shape,      Shape,      sphere)       \
    FAMILY(Light,      light,      Light,      point)        \
    FAMILY(Detector,   detector,   Detector,   perspective)  \
    FAMILY(Integrator, integrator, Integrator, grt)          \
    FAMILY(Sampler,    sampler,    Sampler,    independent)
// clang-format on
