#!/usr/bin/env python3
"""Time to equal error: caustic against Mitsuba 3, scene by scene, side by side in one run.

For each scene of ../shared/scenes/mitsuba/SCENES.txt (or --scenes), both renderers render it at the
same samples per pixel with several seeds, warm (Mitsuba has compiled its kernels; caustic has built
and chosen its pipeline in a warm-up render), and each image is compared with the scene's Mitsuba
reference (../shared/refs/mitsuba). Per renderer the table gives the mean squared error and the
relative MSE (as `caustic compare` computes it: (a-b)^2 / (b^2 + 0.01), averaged) over the seeds, and
the render seconds (Mitsuba: `mi.render` to the synchronised image; caustic: its render loop, as its
closing line reports it; loading excluded on both sides). Since the error of an unbiased render falls
as 1/time, the time either renderer needs to reach the other's error scales as error x seconds: the
last column, (Mitsuba's relative MSE x seconds) / (caustic's), is how many times faster caustic
reaches equal error (its samples per second times its error per sample, both against Mitsuba's). The reference's
own noise adds the same small amount to both errors. The column before it, Mitsuba's seconds over caustic's
at equal spp, is the throughput ratio alone (a diagnostic: what the error per sample makes of it is the
last column).

`--film splat,fis` renders caustic with each film in the same run, against the same Mitsuba renders.
`--reference-spp N` has Mitsuba render each reference at N spp in the run (seed 1000000, cached in
--scratch), so that none needs carrying to the machine that runs this.

Usage (from the repository root, after `cargo build --release`):
    python3 scripts/time-to-error.py --variant cuda_ad_rgb --backend gpu             # a CUDA GPU
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 \\
        python3 scripts/time-to-error.py --variant llvm_ad_rgb --backend cpu --spp 16
    python3 scripts/time-to-error.py --scenes cbox,shape_ply_bunny --film fis        # caustic's other film
    python3 scripts/time-to-error.py --film splat,fis --reference-spp 2048             # both, own references
    python3 scripts/time-to-error.py --scenes cbox --peer-curve /tmp/curves          # Mitsuba's curve for
        caustic convergence SCENE REF.exr --peer /tmp/curves/cbox/mitsuba.csv --plot cbox.svg

Needs `import mitsuba` (pip install mitsuba==3.9.1) and numpy.
"""
import argparse
import math
import os
import re
import subprocess
import time

import numpy as np

from mitsuba_scenes import scene_list


def errors(image, reference):
    """(MSE, relative MSE) of an RGB image against the reference."""
    a = np.asarray(image, dtype=np.float64)[..., :3]
    b = np.asarray(reference, dtype=np.float64)[..., :3]
    if a.shape != b.shape:
        raise ValueError(f"image {a.shape} against reference {b.shape}")
    d2 = (a - b) ** 2
    return float(d2.mean()), float((d2 / (b * b + 1e-2)).mean())


def load_exr(mi, path):
    return np.asarray(mi.Bitmap(path), dtype=np.float32)


def mitsuba_side(mi, dr, path, spp, seeds, reference):
    scene = mi.load_file(path, spp=spp)
    image = mi.render(scene, spp=spp, seed=0)  # compiles the kernels
    dr.eval(image)
    dr.sync_thread()
    results = []
    for seed in seeds:
        # Once untimed with this seed (a seed could be baked into a kernel), then timed.
        dr.eval(mi.render(scene, spp=spp, seed=seed))
        dr.sync_thread()
        start = time.perf_counter()
        image = mi.render(scene, spp=spp, seed=seed)
        dr.eval(image)
        dr.sync_thread()
        seconds = time.perf_counter() - start
        results.append((seconds,) + errors(image, reference))
    return results


def mitsuba_curve(mi, dr, path, max_spp, folder):
    """Mitsuba's renders at 1, 2, 4, ... max_spp spp, each timed warm, listed in folder/mitsuba.csv as
    `caustic convergence --peer` reads them."""
    os.makedirs(folder, exist_ok=True)
    rows = ["spp,seconds,image"]
    spp = 1
    while True:
        scene = mi.load_file(path, spp=spp)
        dr.eval(mi.render(scene, spp=spp, seed=0))  # compiles this spp's kernels
        dr.sync_thread()
        start = time.perf_counter()
        image = mi.render(scene, spp=spp, seed=1)
        dr.eval(image)
        dr.sync_thread()
        seconds = time.perf_counter() - start
        name = f"mitsuba_{spp}.exr"
        mi.Bitmap(image).write(os.path.join(folder, name))
        rows.append(f"{spp},{seconds:.6f},{name}")
        if spp >= max_spp:
            break
        spp = min(2 * spp, max_spp)
    with open(os.path.join(folder, "mitsuba.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")


def reference_image(mi, dr, path, name, args):
    """The scene's reference: ../shared's, or with --reference-spp Mitsuba's own render at that spp,
    made once and kept in the scratch folder."""
    if not args.reference_spp:
        return load_exr(mi, os.path.join(args.shared, "refs/mitsuba", name + ".exr"))
    cached = os.path.join(args.scratch, f"reference-{name}-{args.reference_spp}.exr")
    if not os.path.exists(cached):
        scene = mi.load_file(path, spp=args.reference_spp)
        image = mi.render(scene, spp=args.reference_spp, seed=1_000_000)
        dr.eval(image)
        mi.Bitmap(image).write(cached)
    return load_exr(mi, cached)


def caustic_render(binary, backend, film, path, spp, seed, out):
    cmd = [binary, "render", path, "--backend", backend, "--film", film, "--spp", str(spp),
           "--seed", str(seed), "-o", out, "-q"]
    # A scene whose sampler reads `$spp` without a default (sensor_thinlens) needs it given, as
    # Mitsuba's side gives it to `load_file`.
    with open(path) as f:
        if "$spp" in f.read():
            cmd += ["-D", f"spp={spp}"]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {done.stderr.strip()[-400:]}")
    line = done.stdout.strip().splitlines()[-1]
    found = re.search(r"\| ([0-9.]+) s \|", line)
    if not found:
        raise RuntimeError(f"no seconds in caustic's closing line: {line!r}")
    return float(found.group(1)), line


WARM_UPS = 8  # warm-up renders at most, while the pipeline trial stays undecided


def caustic_side(mi, binary, backend, film, path, spp, seeds, reference, scratch, warm_spp):
    out = os.path.join(scratch, "caustic.exr")
    # Warm-up: the GPU backend prunes and compiles its kernel for the scene and times its candidate
    # pipelines, then keeps its choice (host/src/backend/variant.rs): the timed renders use it. A
    # render too short for the trial keeps its measurements and the next resumes them: warm up again
    # until it has decided (a cheap scene's timed renders otherwise ran the slower candidates too).
    for _ in range(WARM_UPS):
        _, line = caustic_render(binary, backend, film, path, warm_spp, 10_000, out)
        if "undecided" not in line:
            break
    results, line = [], ""
    for seed in seeds:
        seconds, line = caustic_render(binary, backend, film, path, spp, seed, out)
        results.append((seconds,) + errors(load_exr(mi, out), reference))
    return results, line.split(" | ")[0]


def mean(values):
    return sum(values) / len(values)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary", default="target/release/caustic")
    parser.add_argument("--variant", default="cuda_ad_rgb")
    parser.add_argument("--backend", default="gpu", choices=["gpu", "cpu", "auto"])
    parser.add_argument("--film", default="splat", help="caustic's film: splat, fis, or both (splat,fis)")
    parser.add_argument("--reference-spp", type=int, help="render each reference with Mitsuba at this spp")
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "../../shared"))
    parser.add_argument("--scenes", help="comma-separated scene names (default: all of SCENES.txt)")
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--warm-spp", type=int, default=256, help="caustic's warm-up render")
    parser.add_argument("--scratch", default="/tmp/caustic-time-to-error")
    parser.add_argument("--csv", help="also write the table here")
    parser.add_argument("--peer-curve", help="also write Mitsuba's renders at 1, 2, 4, ... spp for "
                        "`caustic convergence --peer` to DIR/<scene>/mitsuba.csv")
    args = parser.parse_args()

    import drjit as dr
    import mitsuba as mi
    mi.set_variant(args.variant)
    os.makedirs(args.scratch, exist_ok=True)
    seeds = list(range(1, args.seeds + 1))
    names = args.scenes.split(",") if args.scenes else None
    films = args.film.split(",")
    if any(f not in ("splat", "fis") for f in films):
        parser.error(f"--film: splat, fis or splat,fis, not {args.film}")
    header = ("scene", "film", "spp", "caustic MSE", "Mitsuba MSE", "MSE ratio", "caustic relMSE", "Mitsuba relMSE",
              "caustic s", "Mitsuba s", "throughput, Mitsuba s / caustic s", "time to equal error, Mitsuba / caustic")
    rows = []
    reference_note = f"references by Mitsuba at {args.reference_spp} spp" if args.reference_spp else "shared references"
    print(f"# caustic {args.backend} ({args.film} film) against Mitsuba {mi.__version__} {args.variant}, "
          f"{args.spp} spp, seeds {seeds}, {reference_note}", flush=True)
    print(" | ".join(header), flush=True)
    for name, relative in scene_list(args.shared, names):
        path = os.path.join(args.shared, "scenes/mitsuba", relative)
        try:
            reference = reference_image(mi, dr, path, name, args)
            m = mitsuba_side(mi, dr, path, args.spp, seeds, reference)
            sides = [(film,) + caustic_side(mi, args.binary, args.backend, film, path, args.spp, seeds, reference,
                                            args.scratch, max(args.warm_spp, args.spp)) for film in films]
            if args.peer_curve:
                mitsuba_curve(mi, dr, path, args.spp, os.path.join(args.peer_curve, name))
        except Exception as e:  # a scene one side cannot render is reported, the rest go on
            print(f"{name} | failed: {e}", flush=True)
            continue
        m_s, m_mse, m_rel = (mean([r[i] for r in m]) for i in range(3))
        for film, c, backend in sides:
            c_s, c_mse, c_rel = (mean([r[i] for r in c]) for i in range(3))
            # Time to equal relative MSE: error x time is constant for each renderer.
            speedup = (m_rel * m_s) / (c_rel * c_s)
            row = (name, film, args.spp, c_mse, m_mse, c_mse / m_mse, c_rel, m_rel, c_s, m_s, m_s / c_s, speedup)
            rows.append(row)
            print(f"{name} | {film} | {args.spp} | {c_mse:.3e} | {m_mse:.3e} | {c_mse / m_mse:.2f} | {c_rel:.3e} | "
                  f"{m_rel:.3e} | {c_s:.3f} | {m_s:.3f} | {m_s / c_s:.2f} | {speedup:.2f}   ({backend})", flush=True)
    for film in films:
        mine = [r for r in rows if r[1] == film]
        if mine:
            geo = lambda i: math.exp(mean([math.log(r[i]) for r in mine]))
            print(f"{film} film, geometric mean over {len(mine)} scenes: MSE ratio (caustic / Mitsuba, equal spp) "
                  f"{geo(5):.2f}, throughput (Mitsuba s / caustic s) {geo(10):.2f}, time to equal error "
                  f"(Mitsuba / caustic) {geo(11):.2f}", flush=True)
    if args.csv:
        with open(args.csv, "w") as f:
            f.write(",".join(header) + "\n")
            for r in rows:
                f.write(",".join(str(x) for x in r) + "\n")


if __name__ == "__main__":
    main()
