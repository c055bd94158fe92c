"""Fixtures of the Python module's tests (CTest test `python`): the clrt binary they compare with, the device,
and readers for the files it writes. Run by CTest with PYTHONPATH=BUILD/python, CLRT_BINARY and
CLRT_CACHE_DIR set (python/CMakeLists.txt); by hand:

    PYTHONPATH=build/python CLRT_BINARY=build/clrt /usr/bin/python3 -m pytest -q python/tests
"""

import json
import os
import struct
import subprocess
import zlib

import numpy as np
import pytest

import clrt

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DEMO = os.path.join(ROOT, "scenes", "cgfs-demo.json")


def pytest_configure(config):
    # Sizes that are not square give clrt's warning (pixels are not square); tests that look for it use
    # pytest.warns.
    config.addinivalue_line("filterwarnings", "ignore::clrt.Warning")


def scene_path(name):
    return os.path.join(ROOT, "scenes", name)


@pytest.fixture(scope="session")
def clrt_binary():
    path = os.environ.get("CLRT_BINARY", os.path.join(ROOT, "build", "clrt"))
    if not os.access(path, os.X_OK):
        pytest.skip("no clrt binary (set CLRT_BINARY)")
    return path


@pytest.fixture(scope="session")
def device():
    """The device spec of the OpenCL tests (CLRT_TEST_DEVICE, as the Catch2 tests take it), or None."""
    return os.environ.get("CLRT_TEST_DEVICE") or None


@pytest.fixture(scope="session")
def run(clrt_binary, device):
    """run(args, device_option=True) -> CompletedProcess of the clrt binary (text output)."""

    def _run(args, check=True, with_device=False):
        argv = [clrt_binary] + list(args)
        if with_device and device:
            argv += ["--device", device]
        p = subprocess.run(argv, capture_output=True, text=True)
        if check and p.returncode != 0:
            raise AssertionError("%s: status %d\n%s" % (" ".join(argv), p.returncode, p.stderr))
        return p

    return _run


@pytest.fixture(scope="session")
def run_json(run):
    def _run_json(args, with_device=False):
        return json.loads(run(list(args) + ["--json", "--quiet"], with_device=with_device).stdout)

    return _run_json


def cli_error(proc):
    """The message of `clrt: error: MESSAGE`, the last line of stderr."""
    line = proc.stderr.strip().splitlines()[-1]
    assert line.startswith("clrt: error: "), proc.stderr
    return line[len("clrt: error: "):]


def read_ppm(path):
    """A binary PPM (P6, maxval 255) as uint8 (H, W, 3); clrt writes '# key=value' comments in its header."""
    data = open(path, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    assert fields[0] == b"P6" and fields[3] == b"255"
    w, h = int(fields[1]), int(fields[2])
    return np.frombuffer(data[pos + 1:pos + 1 + w * h * 3], np.uint8).reshape(h, w, 3)


def read_pfm(path):
    """A colour PFM (PF, little-endian) as float32 (H, W, 3), row 0 at the top."""
    data = open(path, "rb").read()
    parts = data.split(b"\n", 3)
    assert parts[0] == b"PF" and float(parts[2]) < 0
    w, h = map(int, parts[1].split())
    return np.frombuffer(parts[3][:w * h * 12], "<f4").reshape(h, w, 3)[::-1]


def decode_png(data):
    """An 8-bit RGB, non-interlaced PNG (as clrt writes them) as uint8 (H, W, 3)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, colour, interlace) == (8, 2, 0)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = w * 3
    out = np.zeros((h, stride), np.int32)
    prev = np.zeros(stride, np.int32)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = np.frombuffer(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)], np.uint8).astype(np.int32)
        cur = np.zeros(stride, np.int32)
        for x in range(stride):
            a = cur[x - 3] if x >= 3 else 0
            b = prev[x]
            c = prev[x - 3] if x >= 3 else 0
            if f == 0:
                p = 0
            elif f == 1:
                p = a
            elif f == 2:
                p = b
            elif f == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[x] = (line[x] + p) & 0xFF
        out[y] = cur
        prev = cur
    return out.astype(np.uint8).reshape(h, w, 3)


def same_keys(a, b, where="$"):
    """The key paths where two JSON values differ in shape (keys of objects, recursively; lists by their first
    element): [] when they have the same keys everywhere."""
    if isinstance(a, dict) and isinstance(b, dict):
        diff = ["%s.%s" % (where, k) for k in sorted(set(a) ^ set(b))]
        for k in set(a) & set(b):
            diff += same_keys(a[k], b[k], "%s.%s" % (where, k))
        return diff
    if isinstance(a, list) and isinstance(b, list) and a and b:
        return same_keys(a[0], b[0], where + "[0]")
    return []
