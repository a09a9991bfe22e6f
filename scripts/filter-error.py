#!/usr/bin/env python3
"""Error per sample for every reconstruction filter: caustic's two films against Mitsuba 3.

Scene: tests/data/filters.xml (a checkered floor and a sphere under a uniform sky: sharp edges
everywhere, where filters differ most), at --res pixels. For each of Mitsuba's filters, Mitsuba
renders a reference (--ref-spp, kept in --scratch), then both renderers render --spp samples per
pixel with --seeds seeds: caustic with its splatting film (the default) and with filter importance
sampling (`--film fis`), Mitsuba with its `hdrfilm`. The table gives each one's mean squared error
against the reference, averaged over the seeds, and caustic's over Mitsuba's.

Usage (from the repository root, after `cargo build --release`):
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 \\
        python3 scripts/filter-error.py --binary target/release/caustic --variant llvm_ad_rgb
"""
import argparse
import os
import subprocess

import numpy as np

FILTERS = ["box", "tent", "gaussian", "mitchell", "catmullrom", "lanczos"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary", default="target/release/caustic")
    parser.add_argument("--variant", default="llvm_ad_rgb")
    parser.add_argument("--backend", default="cpu")
    parser.add_argument("--res", type=int, default=32)
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--seeds", type=int, default=8)
    parser.add_argument("--ref-spp", type=int, default=16384)
    parser.add_argument("--scratch", default="/tmp/caustic-filter-error")
    args = parser.parse_args()

    import drjit as dr
    import mitsuba as mi
    mi.set_variant(args.variant)
    os.makedirs(args.scratch, exist_ok=True)
    scene_path = os.path.join(os.path.dirname(__file__), "..", "tests", "data", "filters.xml")

    def mse(a, b):
        return float(((np.asarray(a, np.float64)[..., :3] - np.asarray(b, np.float64)[..., :3]) ** 2).mean())

    print(f"# filters.xml at {args.res}x{args.res}, {args.spp} spp, {args.seeds} seeds; references "
          f"{args.ref_spp} spp (Mitsuba {mi.__version__} {args.variant}); caustic {args.backend}")
    print("filter | Mitsuba MSE | caustic splat MSE | caustic fis MSE | splat / Mitsuba | fis / Mitsuba")
    for name in FILTERS:
        params = {"filter": name, "res": str(args.res), "spp": str(args.spp)}
        scene = mi.load_file(scene_path, **params)
        ref_path = os.path.join(args.scratch, f"ref_{name}_{args.res}_{args.ref_spp}.exr")
        if not os.path.exists(ref_path):
            # In slices of 1024 spp with distinct seeds (one long render can exceed a kernel's size).
            slices = max(1, args.ref_spp // 1024)
            total = None
            for s in range(slices):
                image = np.asarray(mi.render(scene, spp=args.ref_spp // slices, seed=10_000 + s), np.float64)
                total = image if total is None else total + image
            mi.Bitmap((total / slices).astype(np.float32)).write(ref_path)
        reference = np.asarray(mi.Bitmap(ref_path), np.float64)
        m = np.mean([mse(mi.render(scene, spp=args.spp, seed=seed), reference) for seed in range(args.seeds)])
        dr.sync_thread()
        caustic = {}
        for film in ["splat", "fis"]:
            errors = []
            for seed in range(args.seeds):
                out = os.path.join(args.scratch, f"caustic_{name}_{film}.exr")
                defines = sum((["-D", f"{k}={v}"] for k, v in params.items()), [])
                subprocess.run([args.binary, "render", scene_path, *defines, "--backend", args.backend, "--film", film,
                                "--seed", str(seed), "-o", out, "-q"], check=True, capture_output=True)
                errors.append(mse(mi.Bitmap(out), reference))
            caustic[film] = float(np.mean(errors))
        print(f"{name} | {m:.3e} | {caustic['splat']:.3e} | {caustic['fis']:.3e} | "
              f"{caustic['splat'] / m:.2f} | {caustic['fis'] / m:.2f}", flush=True)


if __name__ == "__main__":
    main()
