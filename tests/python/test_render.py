# SPDX-License-Identifier: Apache-2.0
"""Rendering from Python: equal to the program bit for bit, images as numpy views, writers and
display, Ctrl-C, lifetimes and memory."""
import _thread
import gc
import os
import signal
import struct
import subprocess
import threading
import time
import warnings

import numpy as np
import pytest

import phasor
from conftest import SCENES, VALIDATION


def cli_render(phasor_bin, scene, out, *args):
    subprocess.run([phasor_bin, "render", str(scene), "-o", str(out), "--quiet", *args], check=True)
    return phasor.read_image(out)


def bits(a):
    return np.ascontiguousarray(a).view(np.uint32)


@pytest.mark.parametrize("scene,integrator,spp,seed,sampler", [
    (SCENES / "small.wscene", "ray", 4, 3, "sobol"),
    (SCENES / "small.wscene", "grt", 3, 7, "independent"),
    (VALIDATION / "double_slit.wscene", "grt", 2, 1, "sobol"),  # a radiometric sensor plane, one row
])
def test_render_equals_the_programs_exr_bit_for_bit(tmp_path, phasor_bin, scene, integrator, spp, seed, sampler):
    cli = cli_render(phasor_bin, scene, tmp_path / "cli.exr", "--integrator", integrator, "--spp", str(spp),
                     "--seed", str(seed), "--sampler", sampler)
    image = phasor.load(scene).render(integrator, spp=spp, seed=seed, sampler=sampler, progress=False)
    assert image.channels == cli.channels
    assert np.array_equal(bits(image.array), bits(cli.array))
    # The EXR Python writes holds the same pixels and the same metadata (but the times measured).
    image.write(tmp_path / "py.exr")
    again = phasor.read_image(tmp_path / "py.exr")
    assert np.array_equal(bits(again.array), bits(cli.array))
    a, b = dict(again.metadata), dict(cli.metadata)
    for m in (a, b):
        del m["phasor:render_seconds"], m["phasor:work_estimate_seconds"], m["DateTime"]
    assert a == b
    assert image.metadata["phasor:spp_reached"] == str(spp) and image.metadata["phasor:seed"] == str(seed)
    assert image.metadata["phasor:cancelled"] == "false"


def test_channels_are_views_without_copies(small_scene):
    image = phasor.load(small_scene).render(spp=2, progress=False)
    assert image.channels[:5] == ["R", "G", "B", "intensity", "variance"]
    i = image["intensity"]
    assert i.dtype == np.float32 and i.shape == (32, 32) == image.shape
    assert not i.flags.writeable and not i.flags.owndata
    assert np.shares_memory(i, image.array)
    assert np.array_equal(i, image.array[:, :, 3])
    assert np.asarray(image).shape == (32, 32, len(image.channels))
    assert i.max() > 0
    with pytest.raises(KeyError, match="channels: R, G, B"):
        image["Z"]


def test_display_png_and_srgb_are_the_programs(tmp_path, phasor_bin, small_scene):
    cli_render(phasor_bin, small_scene, tmp_path / "cli.exr", "--spp", "2")
    image = phasor.load(small_scene).render(spp=2, progress=False)
    png = image._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", png[16:24]) == (32, 32)
    assert png == (tmp_path / "cli.png").read_bytes()
    srgb = image.to_srgb()
    assert srgb.dtype == np.uint8 and srgb.shape == (32, 32, 3)
    decoded = phasor.read_image(tmp_path / "cli.png").array[:, :, :3]
    assert np.array_equal(np.rint(decoded * 255).astype(np.uint8), srgb)
    image.write(tmp_path / "py.png")
    assert (tmp_path / "py.png").read_bytes() == png
    with pytest.raises(ValueError, match=".exr"):
        image.write(tmp_path / "x.tif")


def test_radiometric_display_is_false_colour(tmp_path):
    image = phasor.load(VALIDATION / "gaussian_beam_aperture.wscene").render(spp=1, progress=False)
    assert image.radiometric
    srgb = image.to_srgb()
    assert srgb.shape == (image.height, image.width, 3)
    assert image._repr_png_()[:4] == b"\x89PNG"


def test_render_options_are_checked(small_scene):
    scene = phasor.load(small_scene)
    with pytest.raises(ValueError, match="spp"):
        scene.render(spp=0)
    with pytest.raises(ValueError, match="unknown sampler 'sobl'; did you mean 'sobol'"):
        scene.render(sampler="sobl")
    with pytest.raises(phasor.SceneError, match="unknown integrator 'gtr'.*did you mean 'grt'"):
        scene.render("gtr")


def test_progress_callable_and_render_warnings(small_scene):
    seen = []
    phasor.load(small_scene).render(spp=4, progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1] == (4, 4)
    dark = 'wscene 2\nShape "sphere" { radius = 1 m }\nDetector "perspective" { resolution = [4 4] }\n'
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        image = phasor.load_string(dark).render(spp=1, progress=False)
    found = [x for x in w if issubclass(x.category, phasor.RenderWarning)]
    assert found and "black" in str(found[0].message)
    assert image.warnings == [str(found[0].message)]


def interrupt_after(seconds, how):
    def fire():
        time.sleep(seconds)
        fire.at = time.monotonic()
        if how == "interrupt_main":
            _thread.interrupt_main()
        else:
            os.kill(os.getpid(), signal.SIGINT)
    t = threading.Thread(target=fire, daemon=True)
    t.start()
    return fire


@pytest.mark.parametrize("how", ["interrupt_main", "signal"])
def test_keyboard_interrupt_stops_a_render_and_keeps_the_partial_image(how):
    scene = phasor.load(SCENES / "slow.wscene")  # each pass takes long (tests/app/sigint.sh)
    fire = interrupt_after(2.0, how)
    with pytest.raises(phasor.RenderCancelled) as e:
        scene.render(progress=False)
    latency = time.monotonic() - fire.at
    assert latency < 3.0, f"stopped {latency:.2f} s after Ctrl-C"  # the program's bound (sigint.sh)
    assert isinstance(e.value, KeyboardInterrupt)
    image = e.value.image
    assert image is not None and image.metadata["phasor:cancelled"] == "true"
    assert int(image.metadata["phasor:spp_reached"]) < 64
    if image.metadata["phasor:spp_reached"] != image.metadata["phasor:spp_max"]:
        assert "samples" in image
    # The interpreter's own Ctrl-C handling is unchanged afterwards.
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_keyboard_interrupt_in_render_many():
    fire = interrupt_after(2.0, "interrupt_main")
    with pytest.raises(phasor.RenderCancelled) as e:
        phasor.sweep(SCENES / "slow.wscene", "unused", [1, 2], permissive=True, progress=False)
    assert time.monotonic() - fire.at < 3.0
    assert len(e.value.images) == 2 and e.value.images[1] is None
    assert e.value.image is e.value.images[0]


def test_render_many_and_sweep(small_scene):
    scene = phasor.load(small_scene)
    images = scene.render_many([{"size": "0.5m"}, {"size": 1.5}], spp=1, progress=False)
    assert [i.scene.defines for i in images] == [{"size": "0.5m"}, {"size": 1.5}]
    small, large = (float(i["intensity"].astype(np.float64).sum()) for i in images)
    assert large > small  # the bigger ball fills more of the image
    same = phasor.sweep(small_scene, "size", ["0.5m", 1.5], spp=1, progress=False)
    for a, b in zip(images, same):
        assert np.array_equal(bits(a.array), bits(b.array))
    with pytest.raises(phasor.SceneError, match="must be a length"):
        phasor.sweep(small_scene, "size", ["1m", "2"], spp=1, progress=False)


def test_sweep_builds_geometry_once(tmp_path):
    """Variants that differ in a material share one mesh and one BVH; one that changes the mesh's
    transform builds its own; the cleared cache starts again."""
    (tmp_path / "s.wscene").write_text("""wscene 2
Define grey = 0.5
Define size = 0.3
Material "diffuse" "paint" { reflectance = $grey }
Shape "subdivision" "blob" { cage = "cube"  levels = 2  material = @paint  to_world = scale($size) }
Shape "rectangle" "panel" { to_world = lookat(eye = [0 2 1] m, target = [0 0 0] m, up = [0 0 1]) }
Light "area" "lamp" { shape = @panel  radiance = 1 W/m^2/sr }
Detector "perspective" "cam" { resolution = [8 6]  to_world = lookat(eye = [0 1 3] m, target = [0 0 0] m, up = [0 1 0]) }
""")
    phasor.geometry_cache(clear=True)
    grey = phasor.sweep(tmp_path / "s.wscene", "grey", [0.2, 0.4, 0.8], spp=1, progress=False)
    assert phasor.geometry_cache() == {"mesh_builds": 2, "mesh_reuses": 4, "bvh_builds": 1, "bvh_reuses": 2}
    for image, g in ((grey[0], 0.2), (grey[2], 0.8)):
        phasor.geometry_cache(clear=True)  # as a process that renders this value alone
        fresh = phasor.load(tmp_path / "s.wscene", {"grey": g}).render(spp=1, progress=False)
        assert np.array_equal(bits(image.array), bits(fresh.array))
    phasor.geometry_cache(clear=True)
    phasor.sweep(tmp_path / "s.wscene", "size", [0.3, 0.4], spp=1, progress=False)
    assert phasor.geometry_cache(clear=True)["mesh_builds"] == 3  # the panel, and the blob twice
    assert phasor.geometry_cache() == {"mesh_builds": 0, "mesh_reuses": 0, "bvh_builds": 0, "bvh_reuses": 0}


def test_images_keep_their_scene_alive(small_scene):
    intensity = phasor.load(small_scene).render(spp=1, progress=False)["intensity"]
    image = phasor.load(small_scene).render(spp=1, progress=False)
    gc.collect()
    assert intensity.sum() == image["intensity"].sum()  # the view's image is alive
    again = image.scene.render(spp=1, progress=False)   # so is the image's scene
    assert np.array_equal(bits(again.array), bits(image.array))


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_load_render_cycles_do_not_leak(small_scene):
    def cycle():
        image = phasor.load(small_scene).render(spp=1, progress=False)
        return float(image["intensity"][0, 0])
    for _ in range(10):  # caches, allocator pools, TBB's threads
        cycle()
    gc.collect()
    before = rss_bytes()
    for _ in range(100):
        cycle()
    gc.collect()
    grown = rss_bytes() - before
    assert grown < 10 * 2**20, f"100 load/render cycles grew the process by {grown / 2**20:.1f} MB"
