#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Checks that src/ keeps the layering of docs/architecture.md ("Libraries and where they live").

    check_layering.py ROOT          check the tree at ROOT (exit 1 on any violation)
    check_layering.py --self-test   check the checker on small trees (exit 1 on failure)

Every source file under src/ belongs to one module (by its folder, MODULES below); a quoted
`#include "a/b.h"` of a file under src/ may only name a module that the including module is
allowed to use (ALLOWED). No arrow runs back up: the geometry library includes nothing of
core/render, the base (maths, units, diagnostics, values, schemas, ParamDict) nothing above it,
the parser only the base. A file in a folder the table does not know is an error too, so that a
new module has to be placed in the layering before it can be built on.

Includes in angle brackets (the standard library, third-party libraries) and quoted includes of
files that are not under src/ (the generated plug-in tables, tests' support headers) are not
modules' arrows and are not checked.
"""
import os
import re
import shutil
import sys
import tempfile

# Folder (relative to src/, most specific first) → module. A prefix ending in "/" is a folder
# (with its sub-folders); one without names the files of that stem (a .h and its .cpp).
MODULES = [
    ("core/spectrum/", "spectrum"),
    ("core/numerics/", "numerics"),
    ("core/geometry/", "geometry"),
    ("core/image/", "image"),
    ("core/render/", "render"),
    # BuildContext sits beside ParamDict but builds plug-ins through the registry (library phasor).
    ("core/params/build_context", "render"),
    ("core/params/", "base"),  # values, schemas, ParamDict, scene descriptions
    ("core/", "base"),  # the files directly in src/core: maths, units, diagnostics
    ("parser/", "parser"),
    ("spectra/", "plugins"),
    ("textures/", "plugins"),
    ("shapes/", "plugins"),
    ("lights/", "plugins"),
    ("detectors/", "plugins"),
    ("materials/", "plugins"),
    ("integrators/", "plugins"),
    ("samplers/", "plugins"),
    ("app/", "app"),
    ("python/", "python"),
]

# Module → the modules its files may include (itself included). The libraries of
# src/CMakeLists.txt and src/core/CMakeLists.txt: phasor_base, phasor_spectrum, phasor_numerics,
# phasor_geometry, phasor_image, phasor (render + plug-ins), phasor_parser, the program, Python.
_CORE = {"base", "spectrum", "numerics", "geometry", "image", "render"}
ALLOWED = {
    "base": {"base"},
    "spectrum": {"base", "spectrum"},
    "numerics": {"base", "numerics"},
    "geometry": {"base", "geometry"},
    "image": {"base", "spectrum", "image"},
    "render": _CORE,
    "plugins": _CORE | {"plugins"},
    "parser": {"base", "parser"},
    "app": _CORE | {"plugins", "parser", "app"},
    "python": _CORE | {"plugins", "parser", "app", "python"},
}

# Single arrows that are allowed although their modules' rule forbids them, each with its reason.
EXCEPTIONS = {
    # The base's schema lists the named materials as a complex index's choices; named_ior.h is a
    # header-only table (no link dependency on phasor_spectrum).
    ("core/params/schema.cpp", "core/spectrum/named_ior.h"),
}

SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".inc")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def module_of(path):
    """The module of a path relative to src/, or None."""
    for prefix, module in MODULES:
        if prefix.endswith("/"):
            if path.startswith(prefix) and (prefix != "core/" or "/" not in path[len(prefix):]):
                return module
        elif os.path.splitext(path)[0] == prefix:
            return module
    return None


def check(src):
    """Violations in the tree under `src` (the src/ folder), as 'file:line: message' strings."""
    errors = []
    for dirpath, _, files in os.walk(src):
        for name in sorted(files):
            if not name.endswith(SOURCE_SUFFIXES):
                continue
            full = os.path.join(dirpath, name)
            rel = os.path.relpath(full, src).replace(os.sep, "/")
            if os.path.dirname(rel) == "":
                continue  # src/ itself holds only CMake files
            mod = module_of(rel)
            if mod is None:
                errors.append("src/%s: the folder '%s' is not a module of the layering (add it to MODULES "
                              "in tests/architecture/check_layering.py and to docs/architecture.md)"
                              % (rel, os.path.dirname(rel)))
                continue
            with open(full, encoding="utf-8", errors="replace") as f:
                text = f.read()
            for m in INCLUDE.finditer(text):
                inc = m.group(1)
                if "/" not in inc or not os.path.isfile(os.path.join(src, inc)):
                    continue  # generated, or not under src/
                target = module_of(inc)
                if target is None or target in ALLOWED[mod] or (rel, inc) in EXCEPTIONS:
                    continue
                line = text.count("\n", 0, m.start()) + 1
                errors.append('src/%s:%d: the %s module includes "%s" (%s); %s may include only %s'
                              % (rel, line, mod, inc, target, mod, ", ".join(sorted(ALLOWED[mod]))))
    return errors


def self_test():
    """The checker finds each kind of violation and accepts a clean tree."""
    def tree(files):
        root = tempfile.mkdtemp(prefix="layering_")
        for path, text in files.items():
            full = os.path.join(root, path)
            os.makedirs(os.path.dirname(full), exist_ok=True)
            with open(full, "w") as f:
                f.write(text)
        return root

    clean = {
        "core/math.h": "#pragma once\n",
        "core/render/shape_user.h": '#include "core/geometry/shape.h"\n#include "core/math.h"\n',
        "core/geometry/shape.h": '#include "core/math.h"\n#include <vector>\n',
        "core/render/registry.cpp": '#include "plugin_tables.inc"\n',
        "materials/foo.cpp": '#include "core/render/shape_user.h"\n',
    }
    cases = [
        ("clean tree", {}, 0),
        ("geometry includes render", {"core/geometry/mesh.cpp": '#include "core/render/shape_user.h"\n'}, 1),
        ("base includes geometry", {"core/params.cpp": '#include "core/geometry/shape.h"\n'}, 1),
        ("render includes a plug-in", {"core/render/scene.cpp": '#include "materials/foo.cpp"\n'}, 1),
        ("unknown folder", {"newthing/x.cpp": "\n"}, 1),
        ("params' dict includes render", {"core/params/dict.cpp": '#include "core/render/shape_user.h"\n'}, 1),
        ("build context includes render", {"core/params/build_context.cpp": '#include "core/render/shape_user.h"\n'}, 0),
        ("parser includes render", {"parser/parser.h": '#include "core/render/shape_user.h"\n'}, 1),
        ("spaces in the directive", {"core/geometry/a.h": '  #  include "core/render/shape_user.h"\n'}, 1),
    ]
    failures = 0
    for what, extra, expected in cases:
        root = tree({**clean, **extra})
        try:
            found = check(root)
        finally:
            shutil.rmtree(root)
        if len(found) != expected:
            print("self-test FAILED (%s): expected %d violation(s), found %d: %s" % (what, expected, len(found), found))
            failures += 1
    print("check_layering self-test: %d of %d cases pass" % (len(cases) - failures, len(cases)))
    return 1 if failures else 0


def main(argv):
    if len(argv) == 2 and argv[1] == "--self-test":
        return self_test()
    if len(argv) != 2:
        print(__doc__)
        return 2
    errors = check(os.path.join(argv[1], "src"))
    for e in errors:
        print(e)
    print("check_layering: %d violation(s)" % len(errors))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
