#!/usr/bin/python3
"""A warm clrt.Renderer.render() against `clrt bench`'s warm frame (docs/results/README.md, "Python").

    PYTHONPATH=build/python /usr/bin/python3 bench/python_frame.py build/clrt scenes/cgfs-demo.json \\
        --width 600 --height 600 --rounds 7 --repeat 10

Rounds alternate, so that background load falls on both alike: `clrt bench --float` (REPEAT warm frames of float
colour after its warm-up: what the module's frames are) in a process of its own, then REPEAT render() calls of
one warm Renderer of this process, timed around the call (the frame, the GIL's release, the array). Each round
gives both medians and their ratio, and the median time of a call beyond the C++ Renderer's own frame time
(info["frame_ms"], what clrt bench times); the summary is mean +- sd over the rounds. `--bits8` times clrt bench's
default 8-bit frames instead (what a PNG gets).
"""

import argparse
import json
import statistics
import subprocess
import time

import clrt


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("clrt")
    ap.add_argument("scene")
    ap.add_argument("--width", type=int, default=600)
    ap.add_argument("--height", type=int, default=600)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--repeat", type=int, default=10)
    ap.add_argument("--device", default=None)
    ap.add_argument("--bits8", action="store_true")
    a = ap.parse_args()

    r = clrt.Renderer(a.scene, a.width, a.height, device=a.device)
    for _ in range(3):
        r.render()  # build, first frame, and the first band sized from its rate
    cli, py, kernel_cli, kernel_py, ratio, outside = [], [], [], [], [], []
    for k in range(a.rounds):
        argv = [a.clrt, "bench", a.scene, "--width", str(a.width), "--height", str(a.height), "--repeat",
                str(a.repeat), "--no-omp", "--no-embree", "--no-reference", "--json", "--quiet"]
        argv += [] if a.bits8 else ["--float"]
        argv += ["--device", a.device] if a.device else []
        b = json.loads(subprocess.run(argv, capture_output=True, text=True, check=True).stdout)
        walls, kernels, beyond = [], [], []
        for _ in range(a.repeat):
            t = time.perf_counter()
            img = r.render()
            walls.append(1e3 * (time.perf_counter() - t))
            kernels.append(img.info["kernel_ms"])
            beyond.append(walls[-1] - img.info["frame_ms"])  # the call beyond the C++ Renderer's frame
        cli.append(b["frame"]["median_ms"])
        kernel_cli.append(b["kernel"]["median_ms"])
        py.append(statistics.median(walls))
        kernel_py.append(statistics.median(kernels))
        ratio.append(py[-1] / cli[-1])
        outside.append(statistics.median(beyond))
        print("round %d: clrt bench frame %.2f ms (kernel %.2f), render() %.2f ms (kernel %.2f), ratio %.3f"
              % (k + 1, cli[-1], kernel_cli[-1], py[-1], kernel_py[-1], ratio[-1]), flush=True)

    def ms(v):
        return "%.2f +- %.2f" % (statistics.mean(v), statistics.stdev(v) if len(v) > 1 else 0)

    print("%s, %dx%d, %s frames, N = %d rounds of %d, device %s" % (a.scene, a.width, a.height,
          "8-bit" if a.bits8 else "float", a.rounds, a.repeat, r.device))
    print("clrt bench frame (median per round): %s ms; kernel %s ms" % (ms(cli), ms(kernel_cli)))
    print("render() wall (median per round):    %s ms; kernel %s ms" % (ms(py), ms(kernel_py)))
    print("render() / clrt bench frame:         %.3f +- %.3f" % (statistics.mean(ratio),
                                                                 statistics.stdev(ratio) if len(ratio) > 1 else 0))
    print("render() beyond the Renderer's frame: %s ms" % ms(outside))


if __name__ == "__main__":
    main()
