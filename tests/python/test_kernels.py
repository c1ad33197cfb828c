# SPDX-License-Identifier: Apache-2.0
"""Kernels written in Python: registration, use from a .wscene by grt and ray (equal to the C++
Lambertian they copy), exceptions, and the kernel contract suite (phasor.testing.check_kernel)."""
import math

import numpy as np
import pytest

import phasor



def concentric_disc(u1, u2):
    """Shirley & Chiu's concentric map of [0,1)² to the unit disc (as core/render/sampling.h)."""
    a, b = 2 * u1 - 1, 2 * u2 - 1
    if a == 0 and b == 0:
        return 0.0, 0.0
    if abs(a) > abs(b):
        r, phi = a, math.pi / 4 * (b / a)
    else:
        r, phi = b, math.pi / 2 - math.pi / 4 * (a / b)
    return r * math.cos(phi), r * math.sin(phi)


class Lambert(phasor.Material):
    """A Lambertian reflector written in Python (the C++ `diffuse` kernel's formulas)."""

    parameters = {"albedo": phasor.param("number", 0.5, min=0, max=1, doc="directional-hemispherical reflectance")}
    presets = [{"albedo": 0.5}, {"albedo": 1.0}]

    def __init__(self, params):
        super().__init__(params)
        self.albedo = params["albedo"]

    def sample(self, wi, wl, u0, u):
        if wi[2] == 0:
            return None
        x, y = concentric_disc(*u)
        z = math.sqrt(max(0.0, 1 - x * x - y * y))
        if z == 0:
            return None
        return phasor.ScatterSample((x, y, z if wi[2] > 0 else -z), self.albedo, z / math.pi)

    def eval(self, wi, wo, wl):
        return self.albedo / math.pi if wi[2] * wo[2] > 0 else 0.0

    def pdf(self, wi, wo, wl):
        return abs(wo[2]) / math.pi if wi[2] * wo[2] > 0 else 0.0


phasor.register_material("py_lambert", Lambert)

SCENE = """wscene 2
Define kernel = "py"
Material "py_lambert" "py" { albedo = 0.5 }
Material "diffuse" "cpp" { reflectance = 0.5 }
Shape "sphere" "ball" { radius = 1 m  material = select($kernel == "py", @py, @cpp) }
Shape "rectangle" "floor" { to_world = [scale(4), translate([0 0 -1] m)]  material = select($kernel == "py", @py, @cpp) }
Shape "rectangle" "panel" { to_world = [rotate(90 deg, [1 0 0]), translate([0 3 0] m)] }
Light "area" { shape = @panel  radiance = 2 W/m^2/sr }
Detector "perspective" "cam" { to_world = lookat([0 -2 5] m, [0 0 0] m, [0 0 1])  resolution = [12 12] }
"""


@pytest.mark.parametrize("integrator", ["grt", "ray", "sample_solve"])
def test_python_kernel_renders_as_the_cpp_kernel_it_copies(integrator):
    py = phasor.load_string(SCENE).render(integrator, spp=4, progress=False)
    cpp = phasor.load_string(SCENE, defines={"kernel": "cpp"}).render(integrator, spp=4, progress=False)
    assert py["intensity"].max() > 0
    # The same random numbers, the same formulas: equal up to rounding.
    np.testing.assert_allclose(py.array, cpp.array, rtol=1e-5, atol=1e-7)


def test_registered_kernel_is_a_plugin(phasor_bin=None):
    assert any(p["name"] == "py_lambert" for p in phasor.plugins("material"))
    d = phasor.describe("material", "py_lambert")
    assert d["doc"].startswith("A Lambertian reflector written in Python")
    albedo = d["parameters"][0]
    assert (albedo["name"], albedo["default"], albedo["range"]["max"]) == ("albedo", 0.5, 1.0)
    with pytest.raises(phasor.SceneError, match="did you mean 'albedo'"):
        phasor.load_string(SCENE.replace("albedo = 0.5", "albdo = 0.5"))
    with pytest.raises(phasor.SceneError, match="albedo"):
        phasor.load_string(SCENE.replace("albedo = 0.5", "albedo = 2"))
    with pytest.raises(ValueError, match="built-in"):
        phasor.register_material("diffuse", Lambert)

    class NoPdf(phasor.Material):
        def sample(self, wi, wl, u0, u):
            return None

        def eval(self, wi, wo, wl):
            return 0.0
    with pytest.raises(TypeError, match="pdf"):
        phasor.register_material("py_nopdf", NoPdf)


class Exploding(Lambert):
    """A Lambertian whose sample raises after a few calls (for the test of exceptions)."""

    calls = 0

    def sample(self, wi, wl, u0, u):
        Exploding.calls += 1
        if Exploding.calls > 50:
            raise ValueError("kernel exploded on purpose")
        return super().sample(wi, wl, u0, u)


phasor.register_material("py_exploding", Exploding)


@pytest.mark.parametrize("integrator", ["grt", "ray"])
def test_an_exception_in_a_python_kernel_stops_the_render_with_it(integrator):
    scene = phasor.load_string(SCENE.replace('"py_lambert"', '"py_exploding"'))
    Exploding.calls = 0
    with pytest.raises(ValueError, match="kernel exploded on purpose"):
        scene.render(integrator, spp=64, progress=False)
    # The process goes on, and so does rendering.
    assert phasor.load_string(SCENE).render(integrator, spp=1, progress=False).width == 12


def test_an_exception_in_the_constructor_is_a_scene_error():
    class Picky(Lambert):
        def __init__(self, params):
            raise ValueError("no albedo above 0.4")
    phasor.register_material("py_picky", Picky)
    with pytest.raises(phasor.SceneError, match="no albedo above 0.4") as e:
        phasor.load_string(SCENE.replace('"py_lambert"', '"py_picky"'))
    assert e.value.line == 3


# ---- the kernel contract suite ---------------------------------------------------------------------

QUICK = dict(wavelengths=["550nm"], sample_scale=0.05)  # 7 incident directions, 5 % of the samples


def test_contract_suite_passes_a_correct_python_kernel():
    report = phasor.testing.check_kernel("py_lambert", [{"albedo": 0.5}], **QUICK)
    assert report.passed and bool(report)
    assert len(report.cases) == 7 and report.cases[0] == "py_lambert_p0_550nm_in0"
    checks = report.checks
    assert {"Chi2SamplingMatchesPdf", "PdfIntegratesToAtMostOne", "SampleWeightMatchesEval", "WhiteFurnace",
            "Reciprocal", "FiniteEverywhere", "NearDeltaListing", "LobeMaskSplitsSampleAndEval"} <= set(checks)
    assert checks["Chi2SamplingMatchesPdf"]["passed"] == 7


class PdfTwiceTooLarge(Lambert):
    """A Lambertian whose pdf() states twice the density its sample() draws from."""

    def pdf(self, wi, wo, wl):
        return 2 * super().pdf(wi, wo, wl)


class TooBright(Lambert):
    """A Lambertian reflecting more than arrives (consistent sample, eval and pdf; albedo 1.2)."""

    parameters = {"albedo": phasor.param("number", 1.2, min=0, max=2, doc="reflectance (wrongly above 1)")}


phasor.register_material("py_pdf_twice", PdfTwiceTooLarge)
phasor.register_material("py_too_bright", TooBright)


def test_contract_suite_fails_a_kernel_whose_pdf_is_off_by_two():
    with pytest.raises(phasor.KernelContractError) as e:
        phasor.testing.check_kernel("py_pdf_twice", [{"albedo": 0.5}], **QUICK)
    assert isinstance(e.value, AssertionError)
    failed = e.value.report.failed_checks()
    assert {"Chi2SamplingMatchesPdf", "PdfIntegratesToAtMostOne", "SampleWeightMatchesEval"} <= set(failed)
    assert "pdf reported by Sample differs from Pdf()" in str(e.value)


def test_contract_suite_fails_a_kernel_with_energy_above_one():
    report = phasor.testing.check_kernel("py_too_bright", [{"albedo": 1.2}], raise_on_failure=False, **QUICK)
    assert not report
    assert report.failed_checks() == ["WhiteFurnace"]
    assert "carries more energy than it received" in str(report)


def test_contract_suite_on_a_cpp_kernel_and_bad_arguments():
    assert phasor.testing.check_kernel("diffuse", wavelengths=[550e-9], incidents=[0, 5], sample_scale=0.05)
    with pytest.raises(ValueError, match="TestPresets"):
        phasor.testing.check_kernel("diffuse", [{"reflectance": 0.5}])
    with pytest.raises(ValueError, match="did you mean 'diffuse'"):
        phasor.testing.check_kernel("difuse")
    with pytest.raises(ValueError, match="not one of the suite's"):
        phasor.testing.check_kernel("py_lambert", wavelengths=["500nm"])


def test_registering_a_name_again_replaces_the_class_for_new_scenes_only():
    class Dark(Lambert):
        """A Lambertian reflecting a tenth of its albedo."""

        def __init__(self, params):
            super().__init__(params)
            self.albedo *= 0.1

    phasor.register_material("py_again", Lambert)
    text = SCENE.replace('"py_lambert"', '"py_again"')
    before = phasor.load_string(text)
    phasor.register_material("py_again", Dark)
    after = phasor.load_string(text)
    a = before.render(spp=2, progress=False)["intensity"].sum()
    b = after.render(spp=2, progress=False)["intensity"].sum()
    assert b < 0.5 * a  # the new class for the new scene, the old one's instances for the old
    assert before.render(spp=2, progress=False)["intensity"].sum() == a


# ---- a near-delta kernel: its lobes listed once per prepared query ----------------------------------

class Mirror(phasor.Material):
    """A mirror reflecting a fraction R of the light into one near-delta lobe."""

    parameters = {"R": phasor.param("number", 0.8, min=0, max=1, doc="reflectance")}
    presets = [{"R": 0.8}]
    listed = 0  # list_lobes calls (all instances)

    def __init__(self, params):
        super().__init__(params)
        self.r = params["R"]

    def direction(self, wi):
        return (-wi[0], -wi[1], wi[2])

    def list_lobes(self, wi, wl):
        Mirror.listed += 1
        return [phasor.Lobe(7, self.direction(wi), self.r, 1.0)]

    def sample(self, wi, wl, u0, u):
        return phasor.ScatterSample(self.direction(wi), self.r, 1.0, lobe=7, near_delta=True)


class BackScatter(Mirror):
    """A wrong mirror: it lists (and samples) the light back towards wi, against the law of reflection."""

    def direction(self, wi):
        return wi


phasor.register_material("py_mirror", Mirror)
phasor.register_material("py_back_scatter", BackScatter)


def test_contract_suite_on_a_near_delta_python_kernel():
    assert phasor.testing.check_kernel("py_mirror", **QUICK)
    report = phasor.testing.check_kernel("py_back_scatter", [{"R": 0.8}], raise_on_failure=False, **QUICK)
    assert not report and "NearDeltaListing" in report.failed_checks()


def test_probe_of_a_near_delta_python_kernel_lists_its_lobes_once(tmp_path):
    library = tmp_path / "mirror.wscene"
    library.write_text('wscene 2\nMaterial "py_mirror" "m" { R = 0.8 }\n')
    before = Mirror.listed
    p = phasor.probe(library, "m", "35deg", "550nm")
    # One query, prepared once: its lobe is listed once and read back from the prepared kernel.
    assert Mirror.listed - before == 1
    assert not p.continuous and p.R == 0.8 and p.T == 0
    (lobe,) = p.lobes
    assert lobe["order"] == 7 and lobe["name"] == "7" and lobe["kind"] == "reflection"
    assert lobe["theta_o"] == pytest.approx(math.radians(35), abs=1e-12) and lobe["efficiency"] == 0.8
