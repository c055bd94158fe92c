"""compare, sweep, accuracy and devices: the same dicts as the clrt binary's --json, key for key."""

import numpy as np

import clrt
from conftest import DEMO, same_keys, scene_path

# The keys whose values differ from run to run (times, the moment, the cache's state; PoCL sizes a CPU's
# memory from what is free when a process first asks).
VOLATILE = ("_ms", "timestamp_utc", "cached", "time_source", "gflops", "mrays_per_s", "ns_per_sphere_test",
            "speedup", "kernel", "frame", "_sd", "_mean", "_min", "_max", "_n", "_bytes")


def stable(d):
    """The JSON values that do not depend on timing."""
    if isinstance(d, dict):
        return {k: stable(v) for k, v in d.items() if not any(v_ in k for v_ in VOLATILE)}
    if isinstance(d, list):
        return [stable(v) for v in d]
    return d


def test_compare_is_clrt_compare_json(run_json, device):
    py = clrt.compare(DEMO, 80, 60, device=device, depth=2, fail_percent=0.05)
    cli = run_json(["compare", DEMO, "--width", "80", "--height", "60", "--depth", "2", "--fail-percent", "0.05"],
                   with_device=True)
    assert list(py) == list(cli)  # the same keys in the same order
    assert same_keys(py, cli) == []
    assert stable(py) == stable(cli)
    assert py["verdict"] == "pass" and py["pixels"] == 80 * 60


def test_compare_an_image_file(run, run_json, tmp_path):
    out = str(tmp_path / "i.png")
    run(["render", DEMO, "-o", out, "--quiet", "--width", "64", "--height", "48"], with_device=True)
    py = clrt.compare(DEMO, image=out)
    cli = run_json(["compare", DEMO, "--image", out])
    assert same_keys(py, cli) == [] and stable(py) == stable(cli)
    assert py["width"] == 64 and py["hit_flip_pixels"] is None


def test_sweep_is_clrt_sweep_json(run_json, device):
    py = clrt.sweep(DEMO, 64, 48, depths=range(0, 2), repeat=1, device=device)
    cli = run_json(["sweep", DEMO, "--width", "64", "--height", "48", "--depths", "0:1", "--repeat", "1"],
                   with_device=True)
    assert same_keys(py, cli) == []
    assert [list(r) for r in py["rows"]] == [list(r) for r in cli["rows"]]
    assert [r["depth"] for r in py["rows"]] == [0, 1]
    assert stable(py["rows"]) == stable(cli["rows"])


def test_accuracy_is_clrt_accuracy_json(run_json, device):
    scenes = [DEMO, scene_path("cgfs-camera.json")]
    py = clrt.accuracy(scenes, 64, 48, variants=["robust", "naive"], repeat=1, device=device)
    cli = run_json(["accuracy"] + scenes + ["--width", "64", "--height", "48", "--variants", "robust,naive",
                                            "--repeat", "1"], with_device=True)
    assert same_keys(py, cli) == []
    assert [(r["scene"], r["variant"]) for r in py["rows"]] == [(r["scene"], r["variant"]) for r in cli["rows"]]
    assert stable(py["rows"]) == stable(cli["rows"])


def test_devices_is_clrt_devices_json(run_json):
    py = clrt.devices()
    cli = run_json(["devices"])
    assert same_keys(py, cli) == []
    assert stable(py) == stable(cli)
    assert sum(d["default"] for d in py["devices"]) == 1


def test_rows_make_a_table():
    rows = clrt.sweep(DEMO, 48, 48, depths=(0, 1), repeat=1)["rows"]
    assert all(set(rows[0]) == set(r) for r in rows)
    assert np.isfinite([r["kernel_ms_median"] for r in rows]).all()
