# SPDX-License-Identifier: Apache-2.0
"""phasor — wave-optical rendering with generalized rays, from Python.

A thin layer over the library the ``phasor`` program runs (the same scene loading and checks,
render loop, film and image writers): what the command line does, with numpy arrays in and out.

    import phasor
    scene = phasor.load("scenes/validation/double_slit.wscene", defines={"d": "150um"})
    image = scene.render(spp=64, seed=0)          # an Image; image["intensity"] is a numpy view
    image.write("out/ds.exr")                     # as `phasor render` writes it
    images = phasor.sweep("scenes/validation/double_slit.wscene", "d", ["100um", "200um"])

Loading: load, load_string -> Scene; SceneError, SceneWarning.
Rendering: Scene.render, Scene.render_many, sweep -> Image; RenderCancelled (Ctrl-C), RenderError.
Images: Image (channels as numpy views, metadata, write, to_srgb, Jupyter display), read_image.
Plug-ins: plugins, describe, families. Quantities: quantity("550nm") -> 5.5e-07.
Kernels: probe; Material, register_material (kernels written in Python); phasor.testing.
Comparisons: compare -> Comparison. Reference: docs/python.md.
"""

import os as _os

# The program's writers run its Python modules (plots: phasor_plot.py; compare's page:
# phasor_report.py and templates/); this package ships its own copies (the program looks for them
# beside its executable, which here is the Python interpreter).
_os.environ.setdefault("PHASOR_MODULE_DIR", _os.path.dirname(_os.path.abspath(__file__)))

from ._errors import (  # noqa: E402
    Diagnostic,
    KernelContractError,
    PhasorError,
    RenderCancelled,
    RenderError,
    RenderWarning,
    SceneError,
    SceneWarning,
)
from ._kernels import Lobe, Material, ScatterSample, param, register_material  # noqa: E402
from ._phasor import (  # noqa: E402
    Comparison,
    Image,
    ProbeResult,
    Scene,
    compare,
    describe,
    families,
    geometry_cache,
    load,
    load_string,
    plugins,
    probe,
    quantity,
    read_image,
    sweep,
)

__all__ = [
    "Comparison",
    "Diagnostic",
    "Image",
    "KernelContractError",
    "Lobe",
    "Material",
    "PhasorError",
    "ProbeResult",
    "RenderCancelled",
    "RenderError",
    "RenderWarning",
    "Scene",
    "ScatterSample",
    "SceneError",
    "SceneWarning",
    "compare",
    "describe",
    "families",
    "geometry_cache",
    "load",
    "load_string",
    "param",
    "plugins",
    "probe",
    "quantity",
    "read_image",
    "register_material",
    "sweep",
]


# The error table's columns that hold numbers or a boolean (results.csv; the others are text).
_INT_COLUMNS = {"spp", "dof"}
_FLOAT_COLUMNS = {"seconds", "samples_per_second", "rmse", "rel_mse", "max_error", "rgb_rmse", "noise_floor",
                  "chi2", "z"}


def _table_cell(column, text):
    if column in _INT_COLUMNS:
        return int(text) if text else None
    if column in _FLOAT_COLUMNS:
        return float(text) if text else None
    if column == "comparable":
        return {"true": True, "false": False}.get(text)
    return text


def _comparison_table(self):
    """The error table as a list of dicts, one per run, read from the very results.csv the report
    writes: integrator (the reference run's as "NAME (reference)"), role ("reference" |
    "compared"), status ("ok", "interrupted", "failed", "not_run"), spp, seconds,
    samples_per_second, rmse, rel_mse, max_error, rgb_rmse (errors of `intensity` against the
    reference: docs/compare.md), noise_floor (the reference's), comparable (same physics as the
    reference), chi2, dof, z and verdict (the test of the run against the reference's noise),
    error (a failed integrator's message); None where a run has no value."""
    import csv
    import io

    return [{k: _table_cell(k, v) for k, v in row.items()} for row in csv.DictReader(io.StringIO(self._csv))]


def _comparison_images(self):
    """{integrator: Image} for every run that produced an image, keyed as the table's rows (the
    reference run's as "NAME (reference)")."""
    return {row["integrator"]: image for row, image in zip(self.table, self._images) if image is not None}


Comparison.table = property(_comparison_table)
Comparison.images = property(_comparison_images)


def _comparison_dataframe(self):
    """The error table (Comparison.table) as a pandas DataFrame; ImportError when pandas is not
    installed (Debian: python3-pandas)."""
    try:
        import pandas
    except ImportError as e:
        raise ImportError("Comparison.dataframe() needs pandas (apt-get install python3-pandas); "
                          "Comparison.table has the same rows as a list of dicts") from e
    return pandas.DataFrame(self.table)


Comparison.dataframe = _comparison_dataframe

from . import testing  # noqa: E402  (phasor.testing.check_kernel)
