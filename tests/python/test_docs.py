# SPDX-License-Identifier: Apache-2.0
"""docs/python.md cannot go stale: its API reference is the package's docstrings, entry by entry,
and every name of the package has one; help(phasor) is useful."""
import inspect
import pydoc

import phasor
import phasor._apidoc as apidoc
from conftest import SOURCE

DOC = SOURCE / "docs" / "python.md"


def documented_section():
    text = DOC.read_text(encoding="utf-8")
    assert apidoc.BEGIN in text and apidoc.END in text
    return text.split(apidoc.BEGIN + "\n", 1)[1].split(apidoc.END, 1)[0]


def test_api_reference_equals_the_docstrings():
    expected, documented = apidoc.reference(), documented_section()
    if documented != expected:
        # The first entry that differs, for the message.
        a, b = documented.split("\n### "), expected.split("\n### ")
        first = next((f"{x[:200]!r}\n  vs the docstrings:\n{y[:200]!r}" for x, y in zip(a, b) if x != y),
                     "(entries added or removed)")
        raise AssertionError("docs/python.md's API reference differs from the docstrings; regenerate it with "
                             "`make docs`. First difference:\n" + first)


def test_every_public_name_has_a_documented_entry_with_a_docstring():
    section = documented_section()
    for name in phasor.__all__:
        obj = getattr(phasor, name)
        assert f"`phasor.{name}" in section, name
        assert inspect.getdoc(obj), f"phasor.{name} has no docstring"
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for member, value in vars(obj).items():
                if member.startswith("_") or type(value).__name__ in ("member_descriptor", "getset_descriptor"):
                    continue
                if member in ("parameters", "presets", "reciprocal"):
                    continue
                assert inspect.getdoc(value), f"phasor.{name}.{member} has no docstring"


def test_help_is_useful():
    text = pydoc.render_doc(phasor, renderer=pydoc.plaintext)
    for word in ("load", "render", "SceneError", "RenderCancelled", "register_material", "docs/python.md"):
        assert word in text
