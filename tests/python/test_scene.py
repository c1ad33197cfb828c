# SPDX-License-Identifier: Apache-2.0
"""Loading scenes from Python: defines, diagnostics as SceneError / SceneWarning, quantities,
plug-ins and their schemas."""
import subprocess
import warnings

import pytest

import phasor
from conftest import SCENES, VALIDATION


def test_load_gives_the_scene_and_its_settings(small_scene):
    scene = phasor.load(small_scene)
    assert scene.path == str(small_scene)
    assert scene.detector["width"] == 32 and scene.detector["height"] == 32
    assert scene.detector["radiometric"] is False
    assert scene.integrator == "ray"  # no Integrator in the file: the default, as the program
    assert scene.settings["spp"] == 16
    assert "ball" in [e["name"] for e in scene.entities]


def test_defines_as_text_and_as_si_numbers():
    text = """wscene 2
Define size = 1 m
Define albedo = 0.5
Material "diffuse" "white" { reflectance = $albedo }
Shape "sphere" "ball" { radius = $size  material = @white }
Light "point" { position = [0 3 0] m  intensity = 1 W/sr }
Detector "perspective" "cam" { to_world = lookat([0 0 5] m, [0 0 0] m, [0 1 0])  resolution = [8 8] }
"""
    a = phasor.load_string(text, defines={"size": "150cm"})
    b = phasor.load_string(text, defines={"size": 1.5})  # SI: metres
    assert a.defines == {"size": "150cm"}
    assert b.defines == {"size": 1.5}
    # Equal scenes render equal images.
    ia, ib = (s.render(spp=1, progress=False) for s in (a, b))
    assert ia["intensity"].max() > 0 and (ia.array == ib.array).all()
    # A length given where a number is defined, and a number without unit text: errors.
    with pytest.raises(phasor.SceneError) as e:
        phasor.load_string(text, defines={"albedo": "2 m"})
    assert "must be a plain number" in e.value.message
    with pytest.raises(phasor.SceneError) as e:
        phasor.load_string(text, defines={"size": "2"})
    assert "must be a length" in e.value.message


def test_define_that_matches_nothing(small_scene):
    with pytest.raises(phasor.SceneError) as e:
        phasor.load(small_scene, defines={"szie": "2m"})
    assert "does not override any Define" in e.value.message
    assert "did you mean 'size'" in e.value.message
    # permissive: a warning instead
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        phasor.load(small_scene, defines={"szie": "2m"}, permissive=True)
    assert any(issubclass(x.category, phasor.SceneWarning) and "szie" in str(x.message) for x in w)


BROKEN = """wscene 2
Material "diffuse" "white" { reflectance = 0.5 }
Shape "sphere" "ball" { radius = 1 m  material = @whtie }
Shape "spehre" "other" { radius = 1 m }
Detector "perspective" "cam" { resolution = [8 8]  fvo = 40 deg }
"""


def test_scene_error_has_every_error_with_its_location(tmp_path, phasor_bin):
    path = tmp_path / "broken.wscene"
    path.write_text(BROKEN)
    with pytest.raises(phasor.SceneError) as e:
        phasor.load(path)
    err = e.value
    # The first error's location and message, and every error as the program reports them.
    assert (err.file, err.line) == (str(path), 3)
    assert err.column > 0 and "whtie" in err.message
    assert err.error_count == len(err.errors) == 3
    assert [d.line for d in err.errors] == [3, 4, 5]
    assert all(d.severity == "error" and d.file == str(path) for d in err.errors)
    assert "did you mean \"sphere\"" in err.errors[1].message
    assert "did you mean 'fov'" in err.errors[2].message
    # str(e) is what `phasor check` prints on stderr (without colour).
    cli = subprocess.run([phasor_bin, "check", str(path)], capture_output=True, text=True)
    assert cli.returncode == 1
    assert str(err) == cli.stderr.rstrip("\n")
    assert str(err).endswith(f"3 errors in '{path}'")


def test_scene_error_from_text_and_parse_errors():
    with pytest.raises(phasor.SceneError) as e:
        phasor.load_string('wscene 2\nShape "sphere" { radius = 1 m m }\n', name="inline.wscene")
    assert e.value.file == "inline.wscene" and e.value.line == 2
    with pytest.raises(phasor.SceneError) as e:
        phasor.load(SCENES / "no_such_scene.wscene")
    assert "no_such_scene.wscene" in str(e.value)
    assert isinstance(e.value, phasor.PhasorError)


def test_warnings_go_through_python_warnings():
    text = 'wscene 2\nShape "sphere" { radius = 1 m }\nDetector "perspective" { resolution = [4 4] }\n'
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        phasor.load_string(text, name="dark.wscene")
    found = [x for x in w if issubclass(x.category, phasor.SceneWarning)]
    assert len(found) == 1 and "no light" in str(found[0].message)
    d = found[0].message.diagnostic
    assert d.file == "dark.wscene" and d.severity == "warning"
    # strict: the warning is an error
    with pytest.raises(phasor.SceneError, match="no light"):
        phasor.load_string(text, name="dark.wscene", strict=True)
    with pytest.raises(ValueError):
        phasor.load_string(text, strict=True, permissive=True)


def test_defines_of_every_kind():
    scene = phasor.load(VALIDATION / "thin_film.wscene",
                        defines={"film_material": "Cu2O", "theta": "70deg", "thickness": 1.2e-7})
    assert scene.defines["thickness"] == 1.2e-7
    with pytest.raises(TypeError):
        phasor.load(VALIDATION / "thin_film.wscene", defines={"theta": [1, 2]})


def test_quantities():
    assert phasor.quantity("550nm") == pytest.approx(550e-9, rel=1e-15)
    assert phasor.quantity("30 deg", "angle") == pytest.approx(0.5235987755982988)
    assert phasor.quantity(0.25, "length") == 0.25
    with pytest.raises(ValueError, match="length"):
        phasor.quantity("30 deg", "length")
    with pytest.raises(ValueError, match="unknown kind"):
        phasor.quantity("1 m", "lenght")


def test_plugins_and_describe(phasor_bin):
    every = phasor.plugins()
    assert {"family": "integrator", "name": "grt"} .items() <= next(p for p in every if p["name"] == "grt").items()
    assert set(phasor.families()) == {p["family"] for p in every}
    materials = phasor.plugins("kernels")  # as `phasor list kernels`
    assert materials and all(p["family"] == "material" for p in materials)
    listed = subprocess.run([phasor_bin, "list", "material"], capture_output=True, text=True, check=True).stdout
    assert [p["name"] for p in materials] == [line.split(" — ")[0].strip() for line in listed.splitlines()[1:]]
    with pytest.raises(ValueError, match="did you mean 'light'"):
        phasor.plugins("ligths")

    d = phasor.describe("material", "dielectric")
    assert d["family"] == "material" and d["name"] == "dielectric" and d["doc"]
    cli = subprocess.run([phasor_bin, "describe", "material", "dielectric"], capture_output=True, text=True, check=True)
    assert d["text"] == cli.stdout
    sphere = phasor.describe("sphere")
    radius = next(p for p in sphere["parameters"] if p["name"] == "radius")
    assert radius["kind"] == "number" and radius["unit"] == "m" and radius["doc"]
    assert isinstance(radius["default"], float)
    assert radius["range"]["min"] is not None
    render = phasor.describe("Render")
    spp = next(p for p in render["parameters"] if p["name"] == "spp")
    assert spp["default"] == 16 and spp["kind"] == "integer"
    with pytest.raises(ValueError, match="did you mean 'sphere'"):
        phasor.describe("shape", "spher")
