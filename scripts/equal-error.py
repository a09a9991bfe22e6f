#!/usr/bin/env python3
"""Time to equal error from `caustic convergence --csv` files: the error one integrator (the baseline,
`path` by default) reaches at its last point, and the seconds each integrator's curve needs to reach
it, so that curves measured in one call (or in calls on one machine, one CSV per call, merged by
integrator) are compared as the user sees them: error against time.

For each error column (net relative MSE and net MSE where the reference had a variance, else relative
MSE and RMSE): `first`, where the curve first falls to the target (log-log interpolation between its
points), and `stays`, from where on every later point of the curve is at or below it, which a rare
bright sample (a firefly that lifts one point above the target again) moves later. Past a curve's last
point the time is extrapolated as error ∝ 1/seconds (marked `~`); `<=` where its first point (from
4 spp on) is already below. The ratio is the baseline's seconds over the integrator's.

Usage: python3 scripts/equal-error.py [--baseline path] SCENE.csv [SCENE-part2.csv ...]
(files named `NAME-partK.csv` are merged into one scene NAME).
"""
import argparse
import csv
import math
from collections import defaultdict


def interpolate(a, b, target):
    (t0, e0), (t1, e1) = a, b
    if e1 <= 0:
        return t1
    x = math.log(t0) + (math.log(target) - math.log(e0)) * (math.log(t1) - math.log(t0)) / (
        math.log(e1) - math.log(e0)
    )
    return math.exp(x)


def first(curve, target):
    if curve[0][1] <= target:
        return "<=", curve[0][0]
    for a, b in zip(curve, curve[1:]):
        if b[1] <= target < a[1]:
            return "", interpolate(a, b, target)
    t, e = curve[-1]
    return "~", t * e / target


def stays(curve, target):
    above = [i for i, (_, e) in enumerate(curve) if e > target]
    if not above:
        return "<=", curve[0][0]
    i = above[-1]
    if i == len(curve) - 1:
        t, e = curve[-1]
        return "~", t * e / target
    return "", interpolate(curve[i], curve[i + 1], target)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv", nargs="+")
    parser.add_argument("--baseline", default="path")
    args = parser.parse_args()
    scenes = defaultdict(list)
    for f in args.csv:
        name = f.rsplit("/", 1)[-1].rsplit(".", 1)[0].split("-part")[0]
        scenes[name].append(f)
    for scene, files in scenes.items():
        rows = defaultdict(list)
        for f in files:
            with open(f) as fh:
                for r in csv.DictReader(fh):
                    rows[r["integrator"]].append(r)
        if args.baseline not in rows:
            print(f"== {scene}: no {args.baseline} curve")
            continue
        net = all(r.get("net_rel_mse") for rs in rows.values() for r in rs)
        cols = ["net_rel_mse", "net_mse"] if net else ["rel_mse", "rmse"]
        base = rows[args.baseline][-1]
        t_base = float(base["seconds"])
        print(
            f"== {scene}: {args.baseline} at {base['spp']} spp, {t_base:.2f} s: "
            + ", ".join(f"{c} {float(base[c]):.4g}" for c in cols)
        )
        for name, rs in rows.items():
            last = rs[-1]
            out = [f"{name:5s} {last['spp']:>6} spp {float(last['seconds']):7.2f} s"]
            for c in cols:
                target = float(base[c])
                curve = [(float(r["seconds"]), float(r[c])) for r in rs if int(r["spp"]) >= 4]
                if target <= 0 or not curve:
                    out.append(f"{c}: n/a")
                    continue
                (m1, t1), (m2, t2) = first(curve, target), stays(curve, target)
                out.append(
                    f"{c} {float(last[c]):.4g}: first {m1}{t1:.3g} s ({t_base / t1:.3g}x), "
                    f"stays {m2}{t2:.3g} s ({t_base / t2:.3g}x)"
                )
            print("  " + " | ".join(out))


if __name__ == "__main__":
    main()
