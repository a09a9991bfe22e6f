#!/usr/bin/env python3
"""The CPU backend's parallel efficiency: the same render on 1, 2, 4, ... threads, in one run.

For each scene, `caustic bench SCENE --backend cpu --spp N` runs with RAYON_NUM_THREADS set to each
thread count in turn, and the sweep is repeated --rounds times (rounds interleaved, so that a machine
that slows down mid-run slows every count alike). Each bench warms up first; its timed line gives
Msamples/s. The table gives the mean Msamples/s per count, the speed-up over one thread and the
efficiency (speed-up / threads), then each round's efficiency at the largest count.

Usage (from the repository root, after `cargo build --release`):
    python3 scripts/cpu-threads.py                                   # cbox and glass, 1..all cores
    python3 scripts/cpu-threads.py --threads 1,2,4,8,16 --rounds 3 --scenes cbox
    python3 scripts/cpu-threads.py --scenes cbox,scenes/caustic-sphere.xml --integrator ibpt
"""
import argparse
import os
import re
import statistics
import subprocess

from mitsuba_scenes import scene_list

# The bench's timed line: | backend | WxH | spp | seconds | Msamples/s |
ROW = re.compile(r"^\| cpu .*\| (\d+)x(\d+) \| (\d+) \| ([0-9.]+) \| ([0-9.]+) \|$")


def bench(binary, path, defines, spp, threads, integrator=None):
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    cmd = [binary, "bench", path, "--backend", "cpu", "--spp", str(spp)]
    if integrator:
        cmd += ["--integrator", integrator]
    for d in defines:
        cmd += ["-D", d]
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        m = ROW.match(line.strip())
        if m:
            # From the seconds (three decimals), not the printed rate (two: 0.12 could be 0.115).
            w, h, n, seconds = int(m.group(1)), int(m.group(2)), int(m.group(3)), float(m.group(4))
            if seconds == 0:
                raise RuntimeError(f"the timed render took under a millisecond; raise --spp: {' '.join(cmd)}")
            return w * h * n / seconds / 1e6
    raise RuntimeError(f"no timed line in the output of {' '.join(cmd)}:\n{out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default="target/release/caustic")
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "../../shared"))
    parser.add_argument(
        "--scenes",
        default="cbox,bsdf_dielectric_glass",
        help="comma-separated shared scene names, or paths of scene files (ending in .xml)",
    )
    parser.add_argument("--integrator", help="in place of each scene's own (as `caustic bench --integrator`)")
    parser.add_argument("--threads", help="comma-separated counts (default: 1, 2, 4, ... and all cores)")
    parser.add_argument("--spp", type=int, default=8, help="samples per pixel of each timed render")
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("-D", dest="defines", action="append", default=[], help="passed to caustic")
    args = parser.parse_args()

    cores = os.cpu_count() or 1
    if args.threads:
        counts = [int(t) for t in args.threads.split(",")]
    else:
        counts = [1 << k for k in range(cores.bit_length()) if 1 << k < cores] + [cores]
    names = args.scenes.split(",")
    shared = [n for n in names if not n.endswith(".xml")]
    # (Only where a shared scene is named: `scene_list` of no names lists them all, and needs --shared.)
    paths = {n: os.path.join(args.shared, "scenes/mitsuba", r) for n, r in scene_list(args.shared, shared)} if shared else {}
    paths.update({n: n for n in names if n.endswith(".xml")})
    print(f"cores: {cores}; {args.rounds} rounds; {args.spp} spp per render")
    for name in names:
        rates = {c: [] for c in counts}
        for _ in range(args.rounds):
            for c in counts:
                rates[c].append(bench(args.binary, paths[name], args.defines, args.spp, c, args.integrator))
        one = statistics.mean(rates[counts[0]]) / counts[0]
        print(f"\n{name}, {args.spp} spp" + (f", {args.integrator}" if args.integrator else ""))
        print("| threads | Msamples/s (rounds) | mean | speed-up | efficiency |")
        print("|---|---|---|---|---|")
        for c in counts:
            mean = statistics.mean(rates[c])
            each = ", ".join(f"{r:.3f}" for r in rates[c])
            print(f"| {c} | {each} | {mean:.3f} | {mean / one:.2f} | {100 * mean / one / c:.0f}% |")
        last = counts[-1]
        per_round = ", ".join(f"{100 * b / a / last * counts[0]:.0f}%" for a, b in zip(rates[counts[0]], rates[last]))
        print(f"efficiency at {last} threads per round: {per_round}")


if __name__ == "__main__":
    main()
