#!/usr/bin/env python3
"""Throughput of caustic against Mitsuba 3, scene by scene, side by side in one run.

For each scene of ../shared/scenes/mitsuba/SCENES.txt (or --scenes), interleaved: Mitsuba renders it
once to compile its kernels, then twice timed; caustic's `bench` (which warms up and times its render
loop alone) runs twice; each side keeps its best. The table gives both throughputs in Msamples/s and
caustic's ratio; the last line the geometric mean. Only the render loops are timed, not loading.

Samples per second are a diagnostic: a user waits for an image of a given error, and caustic's and
Mitsuba's samples need not be worth the same. `scripts/time-to-error.py` measures what a speed claim
rests on, time to equal error against one reference, with this ratio beside it (its throughput
column), side by side in one run.

Usage (from the repository root, after `cargo build --release`):
    python3 scripts/speed-vs-mitsuba.py --variant cuda_ad_rgb --backend gpu      # a CUDA GPU
    python3 scripts/speed-vs-mitsuba.py --variant llvm_ad_rgb --backend cpu      # CPU against CPU
    python3 scripts/speed-vs-mitsuba.py --scenes cbox,bsdf_dielectric_glass --spp 64

Mitsuba comes from the package registry: without `import mitsuba` working, the script makes a venv
(.venv-mitsuba, or --venv) and installs mitsuba==3.9.1 there, then re-runs itself with it. The llvm
variant needs libLLVM: Debian's `libllvm19`; DRJIT_LIBLLVM_PATH is set to it when found.
"""
import argparse
import glob
import math
import os
import re
import subprocess
import sys
import time

from mitsuba_scenes import scene_list

MITSUBA_VERSION = "3.9.1"


def ensure_mitsuba(venv):
    try:
        import mitsuba  # noqa: F401
        return
    except ImportError:
        pass
    python = os.path.join(venv, "bin", "python")
    if os.environ.get("CAUSTIC_SPEED_REEXEC"):
        sys.exit("mitsuba does not import even in " + venv)
    if not os.path.exists(python):
        subprocess.check_call([sys.executable, "-m", "venv", venv])
    subprocess.check_call([python, "-m", "pip", "install", "-q", f"mitsuba=={MITSUBA_VERSION}", "numpy"])
    os.environ["CAUSTIC_SPEED_REEXEC"] = "1"
    os.execv(python, [python] + sys.argv)


def mitsuba_throughput(mi, dr, path, spp, rounds):
    # `spp` fills a scene's `$spp` (sensor_thinlens has no default for it); other scenes ignore it.
    scene = mi.load_file(path, spp=spp)
    sensor = scene.sensors()[0]
    w, h = sensor.film().crop_size()
    mi.render(scene, spp=spp)  # compiles the kernels
    dr.sync_thread()
    best = 0.0
    for _ in range(rounds):
        start = time.perf_counter()
        image = mi.render(scene, spp=spp)
        dr.eval(image)
        dr.sync_thread()
        best = max(best, w * h * spp / (time.perf_counter() - start) / 1e6)
    return best


def caustic_throughput(binary, backend, path, spp, rounds, env=None, log=None):
    """caustic's best throughput, and the pipeline each round timed (the GPU backend names its path
    loop and workgroup size: a trial chooses them per scene, `host/src/backend/variant.rs`)."""
    best, pipelines = 0.0, []
    environment = dict(os.environ, **(env or {}))
    if log:
        environment["CAUSTIC_TRIAL_LOG"] = "1"
    for round in range(rounds):
        out = subprocess.run([binary, "bench", path, "--backend", backend, "--spp", str(spp),
                              "-D", f"spp={spp}"], capture_output=True, text=True, env=environment)
        if log:
            with open(f"{log}-{round + 1}.log", "w") as f:
                f.write(out.stdout + out.stderr)
        rows = [l for l in out.stdout.splitlines() if l.startswith("| ") and not l.startswith("| backend")]
        numbers = [re.findall(r"[0-9.]+", r.split("|")[5]) for r in rows if len(r.split("|")) > 5]
        if not numbers or not numbers[0]:
            sys.exit(f"caustic bench failed on {path}:\n{out.stdout}{out.stderr}")
        best = max(best, float(numbers[0][0]))
        pipeline = re.search(r"(plain|regenerating) loop in ([0-9]+x[0-9]+)", rows[0])
        pipelines.append(f"{pipeline[1]} {pipeline[2]}" if pipeline else "-")
    return best, " / ".join(dict.fromkeys(pipelines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "../../shared"))
    ap.add_argument("--caustic", default="target/release/caustic")
    ap.add_argument("--variant", default="cuda_ad_rgb")
    ap.add_argument("--backend", default="gpu", choices=["gpu", "cpu"])
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--scenes", default="", help="comma-separated scene names (default: all 23)")
    ap.add_argument("--venv", default=".venv-mitsuba")
    ap.add_argument("--baseline-env", default="", metavar="NAME=VALUE[,NAME=VALUE]",
                    help="also time caustic with these environment variables (e.g. CAUSTIC_WORKGROUP=8x8), "
                         "interleaved, in a column of its own")
    ap.add_argument("--log", default="", metavar="DIR",
                    help="keep each caustic bench's output, with its trial's passes, in DIR/SCENE-ROUND.log")
    args = ap.parse_args()
    ensure_mitsuba(args.venv)
    if "llvm" in args.variant and "DRJIT_LIBLLVM_PATH" not in os.environ:
        found = sorted(glob.glob("/usr/lib/x86_64-linux-gnu/libLLVM.so.1*") + glob.glob("/usr/lib/llvm-*/lib/libLLVM*.so*"))
        if found:
            os.environ["DRJIT_LIBLLVM_PATH"] = found[-1]
    import drjit as dr
    import mitsuba as mi
    mi.set_variant(args.variant)
    shared = os.path.realpath(args.shared)
    scenes = scene_list(shared, [s for s in args.scenes.split(",") if s])
    print(f"caustic {args.backend} ({args.caustic}) against Mitsuba {mi.__version__} {args.variant}, "
          f"{args.spp} spp, best of {args.rounds}, interleaved")
    baseline = dict(kv.split("=", 1) for kv in args.baseline_env.split(",") if kv)
    extra = f" | caustic with {args.baseline_env} | its ratio | its pipeline" if baseline else ""
    print(f"| scene | Mitsuba Msamples/s | caustic Msamples/s | caustic / Mitsuba | caustic's pipeline{extra} |")
    print("|---|---|---|---|---|" + ("---|---|---|" if baseline else ""))
    ratios, baseline_ratios = [], []
    for name, rel in scenes:
        path = os.path.join(shared, "scenes/mitsuba", rel)
        m = mitsuba_throughput(mi, dr, path, args.spp, args.rounds)
        log = None
        if args.log:
            os.makedirs(args.log, exist_ok=True)
            log = os.path.join(args.log, name)
        c, pipeline = caustic_throughput(args.caustic, args.backend, path, args.spp, args.rounds, log=log)
        ratios.append(c / m)
        row = f"| {name} | {m:.2f} | {c:.2f} | {c / m:.2f} | {pipeline} |"
        if baseline:
            b, pipeline = caustic_throughput(args.caustic, args.backend, path, args.spp, args.rounds, baseline,
                                             log and log + "-baseline")
            baseline_ratios.append(b / m)
            row += f" {b:.2f} | {b / m:.2f} | {pipeline} |"
        print(row, flush=True)
    geo = lambda rs: math.exp(sum(math.log(r) for r in rs) / len(rs))
    print(f"geometric mean of caustic / Mitsuba over {len(ratios)} scenes: {geo(ratios):.2f} "
          "(samples per second; time to equal error: scripts/time-to-error.py)")
    if baseline:
        print(f"geometric mean with {args.baseline_env}: {geo(baseline_ratios):.2f}")


if __name__ == "__main__":
    main()
