"""Scenes, renders and images against the clrt binary's files and the reference."""

import os

import numpy as np
import pytest

import clrt
from conftest import DEMO, decode_png, read_pfm, read_ppm, scene_path

W, H = 96, 72  # (not square: rows and columns cannot be swapped unnoticed)


@pytest.fixture(scope="module")
def demo():
    return clrt.Scene.load(DEMO)


@pytest.fixture(scope="module")
def renderer(demo, device):
    return clrt.Renderer(demo, W, H, device=device)


def test_scene_load_and_dicts(demo):
    assert demo.name == DEMO and demo.path == DEMO
    assert (demo.spheres, demo.lights, demo.recursion_depth) == (4, 3, 3)
    d = demo.to_dict()
    assert set(d) >= {"camera", "spheres", "lights", "recursion_depth"}
    again = clrt.Scene.from_dict(d)
    assert again.name == "<dict>" and again.path is None
    assert again.to_dict() == d
    assert "4 spheres" in repr(demo)


def test_render_equals_the_cli_8bit_and_float_files(renderer, run, tmp_path):
    img = renderer.render()
    assert isinstance(img, np.ndarray) and isinstance(img, clrt.Image)
    assert img.shape == (H, W, 3) and img.dtype == np.float32
    assert img.info["depth"] == 3 and img.info["width"] == W and img.info["device"] == renderer.device
    ppm, pfm, png = (str(tmp_path / n) for n in ("x.ppm", "x.pfm", "x.png"))
    size = ["--width", str(W), "--height", str(H)]
    for out in (ppm, pfm, png):
        run(["render", DEMO, "-o", out, "--quiet"] + size, with_device=True)
    u8 = img.to_uint8()
    assert u8.dtype == np.uint8 and u8.shape == (H, W, 3)
    assert np.array_equal(u8, read_ppm(ppm)), "8-bit image differs from clrt render's PPM"
    assert np.array_equal(u8, decode_png(open(png, "rb").read())), "8-bit image differs from clrt render's PNG"
    assert np.array_equal(np.asarray(img), read_pfm(pfm)), "float image differs from clrt render's PFM"
    assert np.array_equal(u8, clrt.to_uint8(np.asarray(img)))


def test_depths_and_repeated_renders(renderer, run, tmp_path):
    first = renderer.render(depth=1)
    again = renderer.render(depth=1)
    assert np.array_equal(first, again)
    out = str(tmp_path / "d1.pfm")
    run(["render", DEMO, "-o", out, "--quiet", "--depth", "1", "--width", str(W), "--height", str(H)],
        with_device=True)
    assert np.array_equal(np.asarray(first), read_pfm(out))
    assert not np.array_equal(first, renderer.render(depth=3))


def test_options_reach_the_kernel(demo, run, device, tmp_path):
    img = clrt.Renderer(demo, 64, 64, device=device, precision="naive", spp=2, accel="bvh").render(depth=2)
    out = str(tmp_path / "o.pfm")
    run(["render", DEMO, "-o", out, "--quiet", "--width", "64", "--height", "64", "--precision", "naive",
         "--spp", "2", "--accel", "bvh", "--depth", "2"], with_device=True)
    assert np.array_equal(np.asarray(img), read_pfm(out))
    assert img.info["spp"] == 2 and img.info["precision"] == "naive"


def test_ray_cut_and_budget_are_render_s(demo, run, device, tmp_path):
    # Without the weight cut-off the image is --no-ray-cut's, file for file.
    img = clrt.Renderer(demo, 64, 64, device=device, ray_cut=False).render(depth=5)
    out = str(tmp_path / "c.pfm")
    run(["render", DEMO, "-o", out, "--quiet", "--width", "64", "--height", "64", "--depth", "5", "--no-ray-cut"],
        with_device=True)
    assert np.array_equal(np.asarray(img), read_pfm(out))
    # A budget below the frame's worst case is refused before any work, with render's message.
    with pytest.raises(clrt.Error, match="--ray-budget"):
        clrt.Renderer(demo, 64, 64, device=device, ray_budget=1).render(depth=5)
    with pytest.raises(clrt.Error, match="--ray-budget must be in"):
        clrt.Renderer(demo, 64, 64, device=device, ray_budget=0.5)


def test_reference_equals_the_cli_reference_engine(demo, run, tmp_path):
    ref = clrt.reference(demo, W, H)
    assert ref.info["device"] == "host (scalar double)"
    out = str(tmp_path / "r.pfm")
    run(["render", DEMO, "-o", out, "--quiet", "--engine", "reference", "--width", str(W), "--height", str(H)])
    assert np.array_equal(np.asarray(ref), read_pfm(out))


def test_opencl_agrees_with_the_reference(renderer, demo):
    img = renderer.render().to_uint8().astype(int)
    ref = clrt.reference(demo, W, H).to_uint8().astype(int)
    off = (np.abs(img - ref).max(axis=2) > 1).mean()
    assert off <= 0.0005  # compare.hpp's tolerance (0.05 %)


def test_a_scene_from_a_dict_renders_as_its_file(demo, device, tmp_path):
    d = demo.to_dict()
    d["spheres"][0]["color"] = [0, 0, 255]
    path = tmp_path / "blue.json"
    path.write_text(__import__("json").dumps(d))
    a = clrt.Renderer(clrt.Scene.from_dict(d), 48, 48, device=device).render()
    b = clrt.Renderer(str(path), 48, 48, device=device).render()
    assert np.array_equal(a, b)


def test_canvas_rule_round_trips_every_tie():
    # Every half level and its float neighbours: to_uint8 of the stored value is the canvas rule of the
    # kernel's float (clamp, round half to even), as the 8-bit files hold it.
    halves = np.arange(-2, 258, 0.5, dtype=np.float32)
    c = np.concatenate([halves, np.nextafter(halves, np.float32(-1e9)), np.nextafter(halves, np.float32(1e9)),
                        np.random.default_rng(1).uniform(-10, 300, 100000).astype(np.float32),
                        np.array([np.nan, np.inf, -np.inf], np.float32)])
    stored = (c.astype(np.float64) * (1.0 / 255.0)).astype(np.float32)  # what the files and arrays hold
    want = np.nan_to_num(np.rint(np.clip(c.astype(np.float64), 0, 255)), nan=0).astype(np.uint8)
    assert np.array_equal(clrt.to_uint8(stored), want)


def test_image_wrapper_shows_as_png_and_saves(renderer, tmp_path):
    img = renderer.render()
    png = img._repr_png_()
    assert np.array_equal(decode_png(png), img.to_uint8())
    assert img[:, :, 0]._repr_png_() is None  # (a slice is no RGB picture)
    assert (img * 2).info == img.info
    assert isinstance(img.mean(), np.float32) and not isinstance(img.max(), clrt.Image)
    img.save(tmp_path / "s.pfm")
    assert np.array_equal(read_pfm(str(tmp_path / "s.pfm")), np.asarray(img))
    img.save(tmp_path / "s.ppm")
    assert np.array_equal(read_ppm(str(tmp_path / "s.ppm")), img.to_uint8())
