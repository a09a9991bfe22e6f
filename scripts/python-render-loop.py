#!/usr/bin/env python3
"""What a render costs from Python against the command line's render loop (issue 35's 5% budget).

Python: one Scene, rendered once untimed (backend and pipelines), then --repeats renders timed each
whole, from the call to the numpy array (the pass loop, reading the image back, developing it,
converting it to an array). Command line: `caustic bench`, whose timed render is the pass loop and
the read-back on a warmed-up backend, run --repeats times. Each side keeps its best; printed, not
asserted.

Usage (from the repository root, after `cargo build --release` and `pip install ./python`):
    python3 scripts/python-render-loop.py                               # Cornell box, CPU
    python3 scripts/python-render-loop.py --backend gpu --spp 256 -D res=512
"""
import argparse
import os
import re
import subprocess
import sys
import time


def cli_seconds(binary, scene, defines, backend, spp):
    command = [binary, "bench", scene, "--backend", backend, "--spp", str(spp)]
    for d in defines:
        command += ["-D", d]
    out = subprocess.run(command, capture_output=True, text=True)
    rows = [l for l in out.stdout.splitlines() if l.startswith("| ") and not l.startswith("| backend")]
    cells = rows[0].split("|") if rows else []
    if len(cells) < 6 or not re.fullmatch(r"\s*[0-9.]+\s*", cells[4]):
        sys.exit(f"caustic bench failed:\n{out.stdout}{out.stderr}")
    return float(cells[4]), cells[1].strip()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene", nargs="?", default="scenes/cornell-box.xml")
    ap.add_argument("-D", dest="defines", action="append", default=[], help="name=value, as the CLI's -D")
    ap.add_argument("--backend", default="cpu", choices=["cpu", "gpu"])
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--caustic", default=os.path.join(os.environ.get("CARGO_TARGET_DIR", "target"), "release", "caustic"))
    args = ap.parse_args()

    import caustic

    params = dict(d.split("=", 1) for d in args.defines)
    scene = caustic.load_file(args.scene, **params)
    scene.render(spp=args.spp, backend=args.backend, progress=False)
    python = []
    cli = []
    described = ""
    # Interleaved, so that both sides see the same machine (other load, clocks).
    for _ in range(args.repeats):
        start = time.perf_counter()
        scene.render(spp=args.spp, seed=1, backend=args.backend, progress=False)
        python.append(time.perf_counter() - start)
        seconds, described = cli_seconds(args.caustic, args.scene, args.defines, args.backend, args.spp)
        cli.append(seconds)
    best_python, best_cli = min(python), min(cli)
    print(f"{args.scene} | {scene.width}x{scene.height} | {args.spp} spp | {described}")
    print("| side | best of {0} (s) | all (s) |".format(args.repeats))
    print("|---|---|---|")
    print(f"| command line (bench) | {best_cli:.4f} | {' '.join(f'{s:.4f}' for s in cli)} |")
    print(f"| Python (Scene.render) | {best_python:.4f} | {' '.join(f'{s:.4f}' for s in python)} |")
    print(f"Python / command line: {best_python / best_cli:.3f}")


if __name__ == "__main__":
    main()
