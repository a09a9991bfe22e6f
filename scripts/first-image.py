#!/usr/bin/env python3
"""First image of a scene, whole process, caustic beside Mitsuba 3 in one run: what a user waits for
between typing the command and having the image file, with every compile cache removed first (cold)
and again with the caches that run left (warm).

For each scene: caustic `render SCENE --spp N -o out.exr` with the default backend (`auto`: on a
machine with a GPU, a CPU stand-in renders while the GPU's pipelines are built; `backend::create_starting`)
and, with --gpu-only, with `--backend gpu` too (the GPU alone, waiting for its build); Mitsuba 3
(`--variant`, `cuda_ad_rgb` by default) in a fresh Python process that loads the scene, renders N spp
and writes the EXR. "Cold" removes `~/.cache/caustic/modules` (pruned kernel modules; `pruned`, where an
older build kept them), `~/.cache/caustic/variants` (pipeline trial decisions),
`~/.cache/nvidia` and `~/.nv` (the NVIDIA driver's shader cache) before caustic's run and `~/.drjit`
(Dr.Jit's kernel cache) before Mitsuba's; "warm" runs the same command again at once.

Prints one Markdown table: seconds until the image file exists, caustic's whole process in brackets
(with `auto`, a process whose CPU completed the image then waits for the GPU's build to end, so that
the next render uses it), and Mitsuba's time over caustic's time to its image (above 1: caustic
first). Mitsuba's process ends as its image is written. Usage (from the repository root, on the machine measured):
    python3 scripts/first-image.py --caustic target/release/caustic --shared ../shared
    python3 scripts/first-image.py --scenes scenes/cbox/cbox.xml,docs/scenes/bsdf_dielectric_glass.xml --gpu-only
Scenes are Mitsuba scene files, relative to SHARED/scenes/mitsuba (or absolute).
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

# caustic's run-time caches only (`backend::module_cache`, `backend::variant`): its build caches
# live beside them in ~/.cache/caustic and are kept.
CAUSTIC_CACHES = [
    "~/.cache/caustic/pruned",
    "~/.cache/caustic/modules",
    "~/.cache/caustic/variants",
    "~/.cache/nvidia",
    "~/.nv",
]
MITSUBA_CACHES = ["~/.drjit"]

MITSUBA_RENDER = """
import sys, mitsuba as mi
mi.set_variant(sys.argv[1])
scene = mi.load_file(sys.argv[2])
mi.Bitmap(mi.render(scene, spp=int(sys.argv[3]))).write(sys.argv[4])
"""


def clear(paths):
    for p in paths:
        shutil.rmtree(os.path.expanduser(p), ignore_errors=True)


def timed(command, out=None):
    """Seconds the whole process took (None, its last lines printed, where it failed), and the
    seconds until `out` existed (outputs are renamed into place once complete), polled every 10 ms."""
    if out and os.path.exists(out):
        os.remove(out)
    t = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    written = None
    while process.poll() is None:
        if written is None and out and os.path.exists(out):
            written = time.perf_counter() - t
        time.sleep(0.01)
    seconds = time.perf_counter() - t
    log = process.stdout.read()
    if process.returncode != 0:
        print(f"failed ({process.returncode}): {' '.join(command)}\n{log[-800:]}", file=sys.stderr)
        return None, written
    return seconds, written if written is not None else seconds


def fmt(x):
    return "-" if x is None else f"{x:.1f}"


def ratio(m, c):
    return "-" if m is None or c is None else f"{m / c:.2f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--caustic", default="target/release/caustic")
    ap.add_argument("--shared", default="../shared")
    ap.add_argument(
        "--scenes",
        default="scenes/cbox/cbox.xml,docs/scenes/bsdf_dielectric_glass.xml,"
        "docs/scenes/bsdf_roughconductor_copper.xml,docs/scenes/shape_ply_bunny.xml",
    )
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--variant", default="cuda_ad_rgb")
    ap.add_argument("--python", default=sys.executable, help="a Python with mitsuba installed")
    ap.add_argument("--gpu-only", action="store_true", help="also time caustic with --backend gpu (cold)")
    args = ap.parse_args()
    scratch = tempfile.mkdtemp(prefix="first-image-")
    header = "| scene | Mitsuba cold | caustic cold | Mitsuba / caustic | Mitsuba warm | caustic warm | Mitsuba / caustic |"
    if args.gpu_only:
        header += " caustic GPU alone, cold |"
    rows = [header, "|" + "---|" * (header.count("|") - 1)]
    for scene in args.scenes.split(","):
        path = os.path.join(args.shared, "scenes/mitsuba", scene)
        name = os.path.splitext(os.path.basename(scene))[0]
        out = os.path.join(scratch, f"{name}.exr")
        caustic = [args.caustic, "render", path, "--spp", str(args.spp), "-q", "-o", out]
        mitsuba = [args.python, "-c", MITSUBA_RENDER, args.variant, path, str(args.spp), out]
        clear(MITSUBA_CACHES)
        (m_cold, _), (m_warm, _) = timed(mitsuba), timed(mitsuba)
        clear(CAUSTIC_CACHES)
        c_cold, c_cold_image = timed(caustic, out)
        c_warm, c_warm_image = timed(caustic, out)
        row = [
            name,
            fmt(m_cold),
            f"{fmt(c_cold_image)} ({fmt(c_cold)})",
            ratio(m_cold, c_cold_image),
            fmt(m_warm),
            f"{fmt(c_warm_image)} ({fmt(c_warm)})",
            ratio(m_warm, c_warm_image),
        ]
        if args.gpu_only:
            clear(CAUSTIC_CACHES)
            row.append(fmt(timed(caustic + ["--backend", "gpu"])[0]))
        rows.append("| " + " | ".join(row) + " |")
        print(rows[-1], file=sys.stderr, flush=True)
    shutil.rmtree(scratch, ignore_errors=True)
    print("\n".join(rows))


if __name__ == "__main__":
    main()
