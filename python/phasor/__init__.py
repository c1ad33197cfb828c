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

# The program's image writers draw one-row images through the plot module; this package ships its
# own copy (the program looks for it beside its executable, which here is the Python interpreter).
_os.environ.setdefault("PHASOR_PLOT_MODULE", _os.path.join(_os.path.dirname(__file__), "phasor_plot.py"))

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
