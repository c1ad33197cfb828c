# SPDX-License-Identifier: Apache-2.0
"""Shared fixtures of the Python module's tests (run by ctest: tests/python/CMakeLists.txt sets
PYTHONPATH to the build tree's package, PHASOR_BIN to the program and PHASOR_SOURCE_DIR)."""
import os
import pathlib
import warnings

import pytest

SOURCE = pathlib.Path(os.environ.get("PHASOR_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SCENES = SOURCE / "tests" / "app" / "scenes"
VALIDATION = SOURCE / "scenes" / "validation"


@pytest.fixture
def phasor_bin():
    """The phasor program of the same build."""
    path = os.environ.get("PHASOR_BIN")
    if not path:
        pytest.fail("PHASOR_BIN is not set (run the tests through ctest)")
    return path


@pytest.fixture
def small_scene():
    return SCENES / "small.wscene"


@pytest.fixture(autouse=True)
def all_warnings():
    """Every warning is recorded (Python shows a warning only once per place by default)."""
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        yield
