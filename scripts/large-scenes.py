#!/usr/bin/env python3
"""Cost as the scene grows: caustic against Mitsuba 3 on generated scenes of 1M, 10M and 50M triangles.

For each size, `scenes/generate_large.py` writes a field of displaced spheres (each copy its own `ply`
shape, no instancing), then, one after the other in this run: caustic's `bench` (its scene-load time,
the time to build its buffers and BVH, their size, its render throughput, its peak host memory) and
Mitsuba in a fresh process (load time, which includes its acceleration structure, the render's
throughput after an untimed one that compiles its kernels, and its peak host memory). A scene caustic
cannot hold on the device (a buffer over the GPU's binding limit) is reported with caustic's message.

Usage (from the repository root, after `cargo build --release`):
    python3 scripts/large-scenes.py --variant cuda_ad_rgb --backend gpu        # a CUDA GPU
    python3 scripts/large-scenes.py --variant llvm_ad_rgb --backend cpu --sizes 1e6
Mitsuba is installed as `scripts/speed-vs-mitsuba.py` does it.
"""
import argparse
import importlib.util
import json
import os
import re
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def load_module(name, path):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def mitsuba_one(variant, path, spp, res):
    """Runs in its own process: prints load seconds, Msamples/s and peak resident MiB as JSON."""
    import drjit as dr
    import mitsuba as mi
    mi.set_variant(variant)
    start = time.perf_counter()
    scene = mi.load_file(path, spp=spp, res=res)
    dr.sync_thread()
    load = time.perf_counter() - start
    mi.render(scene, spp=spp)  # compiles the kernels
    dr.sync_thread()
    start = time.perf_counter()
    image = mi.render(scene, spp=spp)
    dr.eval(image)
    dr.sync_thread()
    seconds = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(json.dumps({"load": load, "msps": res * res * spp / seconds / 1e6, "peak": peak}))


def mitsuba(variant, path, spp, res):
    out = subprocess.run([sys.executable, __file__, "--mitsuba-one", path, "--variant", variant,
                          "--spp", str(spp), "--res", str(res)], capture_output=True, text=True)
    lines = [l for l in out.stdout.splitlines() if l.startswith("{")]
    if out.returncode != 0 or not lines:
        return {"error": (out.stderr.strip().splitlines() or ["failed"])[-1][:100]}
    return json.loads(lines[-1])


def caustic(binary, backend, path, spp, res):
    out = subprocess.run([binary, "bench", path, "--backend", backend, "--spp", str(spp), "-D", f"res={res}"],
                         capture_output=True, text=True)
    text = out.stdout + out.stderr
    scene = re.search(r"scene: (\d+) primitives \| load ([0-9.]+) s \| buffers and BVH ([0-9.]+) s \| ([0-9.]+) MiB", text)
    row = re.search(r"^\| (gpu|cpu)[^|]*\|[^|]*\|[^|]*\|[^|]*\| ([0-9.]+) \|", text, re.M)
    peak = re.search(r"peak host memory ([0-9.]+) MiB", text)
    result = {}
    if scene:
        result.update(prims=int(scene[1]), load=float(scene[2]), build=float(scene[3]), mib=float(scene[4]))
    if row:
        result["msps"] = float(row[2])
    else:
        unavailable = re.search(r"unavailable: (.*?) \|", text)
        result["error"] = (unavailable[1] if unavailable else text.strip().splitlines()[-1])[:160]
    if peak:
        result["peak"] = float(peak[1])
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--caustic", default="target/release/caustic")
    ap.add_argument("--variant", default="cuda_ad_rgb")
    ap.add_argument("--backend", default="gpu", choices=["gpu", "cpu"])
    ap.add_argument("--sizes", default="1e6,1e7,5e7", help="triangle counts")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", type=int, default=512)
    ap.add_argument("--work", default="/tmp/caustic-large", help="where the scenes are written")
    ap.add_argument("--no-mitsuba", action="store_true")
    ap.add_argument("--venv", default=".venv-mitsuba")
    ap.add_argument("--mitsuba-one", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.mitsuba_one:
        return mitsuba_one(args.variant, args.mitsuba_one, args.spp, args.res)
    if not args.no_mitsuba:
        load_module("speed", os.path.join(HERE, "speed-vs-mitsuba.py")).ensure_mitsuba(args.venv)
    generate = load_module("generate_large", os.path.join(HERE, "..", "scenes", "generate_large.py"))
    print(f"caustic {args.backend} ({args.caustic}) and Mitsuba {args.variant}, {args.res}², {args.spp} spp")
    print("| triangles | caustic: load s | BVH and buffers s | scene MiB | peak host MiB | Msamples/s "
          "| Mitsuba: load s | peak host MiB | Msamples/s | caustic / Mitsuba |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for size in args.sizes.split(","):
        [(path, _)] = generate.write(args.work, [int(float(size))])
        c = caustic(args.caustic, args.backend, path, args.spp, args.res)
        m = {"error": "not run"} if args.no_mitsuba else mitsuba(args.variant, path, args.spp, args.res)
        fmt = lambda d, k, f: f"{d[k]:{f}}" if k in d else "–"
        ratio = f"{c['msps'] / m['msps']:.2f}" if "msps" in c and "msps" in m else "–"
        cells = [fmt(c, "prims", ","), fmt(c, "load", ".2f"), fmt(c, "build", ".2f"), fmt(c, "mib", ".0f"),
                 fmt(c, "peak", ".0f"), fmt(c, "msps", ".2f") if "msps" in c else c.get("error", "–"),
                 fmt(m, "load", ".2f"), fmt(m, "peak", ".0f"),
                 fmt(m, "msps", ".2f") if "msps" in m else m.get("error", "–"), ratio]
        print("| " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
