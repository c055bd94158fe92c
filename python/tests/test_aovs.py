"""AOV layers: Renderer(aovs=...) gives `clrt render --aov`'s layers as numpy arrays (read back from its EXR
with oiiotool), the values worked out by hand for one sphere, and the CLI's errors."""

import re
import shutil
import subprocess

import numpy as np
import pytest

import clrt
from conftest import DEMO, cli_error, scene_path

GLASS = scene_path("glass.json")
ALL = "depth,normal,albedo,id"


def exr_channels(path):
    """{channel name: (H, W) float64} of an EXR, read with `oiiotool --dumpdata` (9 decimals a value)."""
    text = subprocess.run(["oiiotool", "-v", "--dumpdata", str(path)], capture_output=True, text=True,
                          check=True).stdout
    names = re.search(r"channel list: (.*)", text).group(1).split(", ")
    pixels = {}
    for x, y, values in re.findall(r"Pixel \((\d+), (\d+)\): ([^\n]*)", text):
        pixels[int(y), int(x)] = [float(v) for v in values.split()]
    h, w = max(pixels)[0] + 1, max(k[1] for k in pixels) + 1
    return {name: np.array([[pixels[y, x][i] for x in range(w)] for y in range(h)]) for i, name in
            enumerate(names)}


def test_layers_are_the_cli_exr_layers(run, tmp_path, device):
    if not shutil.which("oiiotool"):
        pytest.skip("oiiotool not installed")
    options = {"aspect": "image", "device": device}
    img = clrt.Renderer(GLASS, 24, 18, aovs=ALL, **options).render()
    assert sorted(img.aovs) == ["albedo", "depth", "id", "normal"]
    assert img.info["aovs"] == ALL
    assert img.aovs["depth"].shape == (18, 24) and img.aovs["depth"].dtype == np.float32
    assert img.aovs["normal"].shape == (18, 24, 3) and img.aovs["albedo"].shape == (18, 24, 3)
    assert img.aovs["id"].shape == (18, 24) and img.aovs["id"].dtype == np.int32
    out = tmp_path / "g.exr"
    run(["render", GLASS, "--width", "24", "--height", "18", "--aspect", "image", "--aov", ALL, "-o", str(out)],
        with_device=True)
    ch = exr_channels(out)
    # The same kernel on the same device: the same float32 values, printed with 9 decimals (so within 1e-9
    # plus one part in 1e8); a miss's +inf and -1 exactly.
    close = dict(rtol=1e-8, atol=1e-9)
    assert np.array_equal(np.isinf(ch["Z"]), img.aovs["id"] < 0)
    hit = img.aovs["id"] >= 0
    assert hit.any() and (~hit).any()
    assert np.allclose(ch["Z"][hit], img.aovs["depth"][hit], **close)
    assert np.all(np.isinf(img.aovs["depth"][~hit]))
    for k, axis in enumerate("XYZ"):
        assert np.allclose(ch["N." + axis], img.aovs["normal"][..., k], **close)
    for k, c in enumerate("RGB"):
        assert np.allclose(ch["albedo." + c], img.aovs["albedo"][..., k], **close)
        assert np.allclose(ch[c], np.asarray(img)[..., k], **close)  # the colour too
    assert np.array_equal(ch["id"], img.aovs["id"])
    assert np.all(ch["A"] == 1)


def test_one_sphere_straight_ahead_by_hand(device):
    # The camera at the origin looks down +z; a sphere of radius 1 at z = 5. Canvas (0, 0) is column W/2,
    # row H/2 - 1 (row 1 of 5): its ray meets the sphere at z = 4, distance 4, normal (0, 0, -1).
    scene = clrt.Scene.from_dict({"spheres": [{"center": [0, 0, 5], "radius": 1, "color": [255, 51, 0]}],
                                  "lights": [{"type": "ambient", "intensity": 1}]})
    aovs = clrt.Renderer(scene, 5, 5, aovs=["depth", "normal", "albedo", "id"], device=device).render().aovs
    # float32: a few ulps
    assert aovs["depth"][1, 2] == pytest.approx(4, rel=1e-6)
    assert aovs["normal"][1, 2] == pytest.approx([0, 0, -1], abs=1e-6)
    assert aovs["albedo"][1, 2] == pytest.approx([1, 0.2, 0], abs=1e-6)
    assert aovs["id"][1, 2] == 0
    # the corners' rays pass the sphere by
    for y, x in [(0, 0), (0, 4), (4, 0), (4, 4)]:
        assert np.isposinf(aovs["depth"][y, x]) and aovs["id"][y, x] == -1
        assert not aovs["normal"][y, x].any() and not aovs["albedo"][y, x].any()


def test_no_layers_unless_asked(device):
    img = clrt.Renderer(DEMO, 8, 8, device=device).render()
    assert img.aovs == {} and "aovs" not in img.info
    only = clrt.Renderer(DEMO, 8, 8, aovs="id", device=device).render()
    assert list(only.aovs) == ["id"]


@pytest.mark.parametrize("aovs, argv", [("depth,colour", "depth,colour"), (["id", "id"], "id,id"),
                                        ("", "")])
def test_bad_layers_have_the_cli_message(run, tmp_path, aovs, argv):
    with pytest.raises(clrt.UsageError) as e:
        clrt.Renderer(DEMO, 8, 8, aovs=aovs)
    p = run(["render", DEMO, "--width", "8", "--height", "8", "--aov", argv, "-o", str(tmp_path / "x.exr")],
            check=False)
    assert p.returncode == 2 and str(e.value) == cli_error(p)
    with pytest.raises(clrt.UsageError, match="aovs: expected"):
        clrt.Renderer(DEMO, 8, 8, aovs=3)
