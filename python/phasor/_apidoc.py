# SPDX-License-Identifier: Apache-2.0
"""The API reference of docs/python.md, generated from the package's docstrings:

    PYTHONPATH=build/python python3 -m phasor._apidoc > reference.md

docs/python.md holds the output between its `<!-- api: begin -->` and `<!-- api: end -->` lines,
and tests/python/test_docs.py fails when the two differ, so the reference cannot go stale
(`make docs` rewrites it)."""

import inspect
import re
import sys

import phasor

BEGIN, END = "<!-- api: begin -->", "<!-- api: end -->"


def _clean(text):
    text = re.sub(r"phasor\._phasor\.|phasor\._errors\.|phasor\._kernels\.", "phasor.", text)
    return re.sub(r"\(self(: [\w.]+)?(, )?", "(", text)  # methods are shown without self


def _signature_and_doc(name, obj):
    """(signature, doc) of a function, method or class: pybind11 puts the signature on the
    docstring's first line; Python objects have inspect.signature."""
    doc = inspect.getdoc(obj) or ""
    if not inspect.isclass(obj) and not isinstance(obj, property) and doc.startswith(name + "("):
        first, _, rest = doc.partition("\n")
        return _clean(first), rest.strip()
    try:
        sig = str(inspect.signature(obj))
    except (TypeError, ValueError):
        sig = ""
    return _clean(name + sig), doc.strip()


def _members(cls):
    """A class's public members in definition order: (name, object)."""
    out = []
    seen = set()
    for klass in cls.__mro__:
        if klass is object or klass.__module__ == "builtins" or klass.__name__ in ("pybind11_object",):
            continue
        for name, obj in vars(klass).items():
            if name in seen or (name.startswith("_") and name not in ("__getitem__", "__array__", "_repr_png_")):
                continue
            if klass is not cls and klass.__module__.startswith("typing"):
                continue
            seen.add(name)
            if type(obj).__name__ in ("member_descriptor", "getset_descriptor"):
                continue  # plain attributes (__slots__), documented by the class
            out.append((name, obj))
    return out


def _entry(qualname, obj, level):
    name = qualname.rsplit(".", 1)[-1]
    if isinstance(obj, property) or type(obj).__name__ == "property":
        doc = inspect.getdoc(obj) or ""
        return [f"{'#' * level} `{qualname}` (property)", "", doc.strip(), ""]
    sig, doc = _signature_and_doc(name, obj)
    lines = [f"{'#' * level} `{qualname.rsplit('.', 1)[0] + '.' if '.' in qualname else ''}{sig}`", ""]
    if doc:
        lines += [doc, ""]
    return lines


def reference():
    """The API reference as Markdown."""
    lines = []
    for name in phasor.__all__:
        obj = getattr(phasor, name)
        if inspect.isclass(obj):
            doc = (inspect.getdoc(obj) or "").strip()
            base = [b.__name__ for b in obj.__bases__ if b.__name__ not in ("object", "pybind11_object", "tuple")]
            lines += [f"### class `phasor.{name}`" + (f" ({', '.join(base)})" if base else ""), "", doc, ""]
            if issubclass(obj, BaseException):
                continue
            fields = getattr(obj, "_fields", None)
            for mname, member in _members(obj):
                if fields and mname in fields:
                    continue
                if mname in ("parameters", "presets", "reciprocal", "count", "index"):
                    continue
                lines += _entry(f"phasor.{name}.{mname}", member, 4)
        else:
            lines += _entry(f"phasor.{name}", obj, 3)
    lines += ["### module `phasor.testing`", "", (inspect.getdoc(phasor.testing) or "").strip(), ""]
    for name in ("check_kernel", "KernelReport", "WAVELENGTHS", "INCIDENTS"):
        obj = getattr(phasor.testing, name)
        if name.isupper():
            lines += [f"#### `phasor.testing.{name}`", "", f"`{obj!r}`", ""]
        elif inspect.isclass(obj):
            lines += [f"#### class `phasor.testing.{name}`", "", (inspect.getdoc(obj) or "").strip(), ""]
        else:
            lines += _entry(f"phasor.testing.{name}", obj, 4)
    text = "\n".join(lines)
    return re.sub(r"\n{3,}", "\n\n", text).strip() + "\n"


def replace_in(path):
    """Rewrites the reference between the markers of the Markdown file `path`."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    head, _, rest = text.partition(BEGIN + "\n")
    _, _, tail = rest.partition(END)
    with open(path, "w", encoding="utf-8") as f:
        f.write(head + BEGIN + "\n" + reference() + END + tail)


if __name__ == "__main__":
    if len(sys.argv) > 1:
        replace_in(sys.argv[1])
    else:
        sys.stdout.write(reference())
