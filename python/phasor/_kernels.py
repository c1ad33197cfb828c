# SPDX-License-Identifier: Apache-2.0
"""Diffraction kernels written in Python: the base class, parameter declarations and
registration (src/python/kernel.cpp adapts them to the C++ kernel interface)."""

import inspect
from typing import NamedTuple, Sequence, Tuple, Union

from . import _phasor

Vector = Tuple[float, float, float]
Weight = Union[float, Sequence[float]]


class ScatterSample(NamedTuple):
    """What Material.sample returns (or None when the path is absorbed):

    wo: the sampled direction (x, y, z), unit, in the local frame, pointing away from the surface.
    weight: f(wi, wo)·|cos θo| / pdf for a continuous lobe, a_j / p_j for a near-delta lobe j
        (including the (η_i/η_t)² radiance factor on refraction); a float, or one per wavelength.
    pdf: the solid-angle density for a continuous lobe; the selection probability p_j of a
        near-delta lobe.
    lobe: a near-delta lobe's id (the one list_lobes gives it); ignored for continuous samples.
    near_delta: True for a near-delta lobe (one of list_lobes), False for a continuous one.
    transmission: True if wo is on the far side of the surface.
    eta: the relative index η_t/η_i crossed (1 for reflection).
    """

    wo: Vector
    weight: Weight
    pdf: float
    lobe: int = 0
    near_delta: bool = False
    transmission: bool = False
    eta: float = 1.0


class Lobe(NamedTuple):
    """A near-delta lobe (what list_lobes returns, one per lobe): a mirror reflection, a refraction,
    a grating order. Its direction obeys the vector grating equation
    n_out·wo.xy = −n_in·wi.xy + shift·λ/(2π) (shift [rad/m] = 0 for a mirror or Snell's law),
    the same at every carried wavelength (a dispersive lobe cannot be written in Python yet).

    id: stable per kernel; weight: a_j, the lobe's radiance throughput (float or per wavelength,
    Σ a_j ≤ 1 in energy); prob: the probability with which sample picks it; n_in, n_out: the real
    indices of wi's and wo's media."""

    id: int
    wo: Vector
    weight: Weight
    prob: float
    transmission: bool = False
    n_in: float = 1.0
    n_out: float = 1.0
    shift: Tuple[float, float] = (0.0, 0.0)


_KINDS = ("number", "length", "angle", "area", "power", "temperature", "integer", "bool", "string")


def param(kind="number", default=None, *, doc="", min=None, max=None, min_exclusive=False, choices=None,
          required=False):
    """Declares one parameter of a Python kernel (the class attribute ``parameters`` maps names to
    these). kind: one of number (dimensionless), length, angle, area, power, temperature, integer,
    bool, string. default: a number in SI units or a string with a unit ("550nm"); min, max: SI
    bounds (inclusive; min_exclusive makes min exclusive); choices: a string's allowed values.
    Scenes give the values with units as for any plug-in; the kernel receives them in SI."""
    if kind not in _KINDS:
        raise ValueError(f"unknown parameter kind {kind!r} (one of {', '.join(_KINDS)})")
    return {"kind": kind, "default": default, "doc": doc, "min": min, "max": max,
            "min_exclusive": min_exclusive, "choices": choices, "required": required}


class Material:
    """Base class of diffraction kernels written in Python.

    A subclass implements, in the local shading frame (z = the shading normal; wi and wo both point
    away from the surface; wi is where the tracer came from) with wl the tuple of carried vacuum
    wavelengths [m] (wl[0] the hero):

      sample(wi, wl, u0, u) -> ScatterSample | None   pick a lobe with u0, a direction with u (2 floats)
      eval(wi, wo, wl) -> f [1/sr]    the continuous lobes' value (no cosine), a float or one per wavelength
      pdf(wi, wo, wl) -> density      of sample's continuous directions [1/sr] (incl. the lobe choice)
      list_lobes(wi, wl) -> [Lobe]    optional: the near-delta lobes

    Defining eval (and pdf) gives the kernel a continuous lobe; defining list_lobes near-delta
    ones. ``parameters`` = {name: phasor.param(...)} is its schema; the class docstring its
    documentation; ``presets`` a list of parameter dicts for phasor.testing.check_kernel;
    ``reciprocal`` (default True) whether f(wi→wo) = f(wo→wi). The constructor receives the
    parameters as a dict of SI values: ``__init__(self, params)``.

    Every method is about one query and gets what it needs of it (wi, wl): a kernel keeps no state
    per hit. (phasor's renderer prepares a kernel per hit; for a Python kernel that calls
    list_lobes once per hit, then sample, eval and pdf as the integrator asks.)

    Register the class with phasor.register_material(name, cls); scenes loaded afterwards in the
    same process name it like any kernel: Material "name" "x" { ... }.
    """

    parameters = {}
    presets = []
    reciprocal = True

    def __init__(self, params):
        self.params = dict(params)

    def sample(self, wi, wl, u0, u):
        """Picks a lobe with u0 and a direction in it with u = (u1, u2) (uniform in [0, 1)):
        a ScatterSample, or (wo, weight, pdf) for a continuous lobe, or None (absorbed)."""
        raise NotImplementedError(f"{type(self).__name__}.sample")

    def eval(self, wi, wo, wl):
        """The continuous lobes' value f(wi → wo) [1/sr] (no cosine): a float, or one per
        wavelength of wl. Near-delta lobes are not part of it."""
        return 0.0

    def pdf(self, wi, wo, wl):
        """The solid-angle density [1/sr] with which sample() returns wo in a continuous lobe,
        including the probability of choosing that lobe."""
        return 0.0

    def list_lobes(self, wi, wl):
        """The near-delta lobes for light from wi: a list of Lobe, in the order of their ids."""
        return []

    def __repr__(self):
        return f"{type(self).__name__}({self.params!r})"


def register_material(name, cls):
    """Registers ``cls`` (a phasor.Material subclass) as the material plug-in ``name``: scenes
    loaded from now on in this process may use it with every integrator that accepts its
    capabilities, phasor.describe("material", name) shows its schema, phasor.testing.check_kernel
    runs the kernel contract suite on it. Registering a name again replaces the class (for scenes
    loaded afterwards); a built-in kernel's name is refused."""
    if not (inspect.isclass(cls) and issubclass(cls, Material)):
        raise TypeError("register_material needs a subclass of phasor.Material")
    if not isinstance(name, str) or not name.isidentifier():
        raise ValueError(f"a material's name must be an identifier; got {name!r}")
    params = []
    for pname, spec in cls.parameters.items():
        if not isinstance(spec, dict) or "kind" not in spec:
            raise TypeError(f"{cls.__name__}.parameters[{pname!r}] must be phasor.param(...)")
        params.append((pname, spec["kind"], spec["default"], spec["min"], spec["max"], spec["min_exclusive"],
                       spec["choices"], spec["required"], spec["doc"]))
    continuous = cls.eval is not Material.eval
    near_delta = cls.list_lobes is not Material.list_lobes
    if continuous and cls.pdf is Material.pdf:
        raise TypeError(f"{cls.__name__} defines eval() but not pdf(): a continuous lobe needs both")
    doc = inspect.getdoc(cls) or ""
    _phasor._register_material(name, cls, doc.split("\n\n")[0].replace("\n", " "), params, list(cls.presets),
                               continuous, near_delta, bool(cls.reciprocal))
