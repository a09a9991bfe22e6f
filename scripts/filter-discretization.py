#!/usr/bin/env python3
"""Mitsuba 3's scalar variants weight each splat by a tabulated filter, caustic's film by the filter
itself: what that does at an edge.

Mitsuba's `ReconstructionFilter::eval_discretized` (scalar variants; the JIT variants call `eval`)
reads a table of MI_FILTER_RESOLUTION = 31 values w(r·i/31), i = 0..30, at index ⌊31·|x|/r⌋: the
filter's value at the inner end of each bin of width r/31. caustic's splatting film
(`film_splat::add` through `film::filter_weight`) weights by the mean of w over each of 64 bins
across [-r, r], which is the filter to within a few 1e-4 here.

Scene: an orthographic camera, 32x4 pixels, over an emitting rectangle of radiance 1 whose edge runs
down the image at x = 16.3 pixels, black beyond it. The image then depends on x alone: pixel p is
∫ w(p + ½ − s)·[s < 16.3] ds / ∫ w(p + ½ − s) ds over s in [0, 32] (samples drawn uniformly over the
image, Mitsuba's sample_border = false, and the weights summed per pixel). The table prints, for the
pixels next to the edge, Mitsuba's render (--renders renders of 1024 spp, averaged in float64: one
render of many more samples drifts, scalar_rgb's film summing in float32), that formula with
Mitsuba's table and with the exact filter, and caustic's render (--spp).

Usage (from the repository root, after `cargo build --release -p caustic`), with Mitsuba 3 installed:
    python3 scripts/filter-discretization.py --binary target/release/caustic --filter lanczos

Measured (Mitsuba 3.9.1, lanczos, 64x1024 spp; caustic 16384 spp): pixel 15 renders 1.0377 in
Mitsuba (its table predicts 1.0377, the exact filter 1.0536) and 1.0518 in caustic; pixel 16, 0.3185
(0.3191; 0.3043) and 0.3041.
"""
import argparse
import os
import subprocess
import tempfile

import mitsuba as mi
import numpy as np

SCENE = """<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="2"/></integrator>
    <sensor type="orthographic">
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="1024"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="32"/><integer name="height" value="4"/>
            <rfilter type="{filter}"/>
        </film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale x="5" y="5"/><translate x="{shift}" y="0" z="0"/></transform>
        <emitter type="area"><rgb name="radiance" value="1, 1, 1"/></emitter>
    </shape>
</scene>
"""
EDGE = 16.3  # pixels from the image's left border: the image spans x in [-1, 1], 16 pixels a unit


def lanczos(x, lobes=3):
    x = np.abs(x)
    return np.where(x < lobes, np.sinc(x) * np.sinc(x / lobes), 0.0)


def mitchell_netravali(x, b, c):
    x = np.abs(x)
    inner = ((12 - 9 * b - 6 * c) * x**3 + (-18 + 12 * b + 6 * c) * x**2 + (6 - 2 * b)) / 6
    outer = ((-b - 6 * c) * x**3 + (6 * b + 30 * c) * x**2 + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6
    return np.where(x < 1, inner, np.where(x < 2, outer, 0.0))


def gaussian(x, stddev=0.5):
    r = 4 * stddev
    return np.where(np.abs(x) < r, np.maximum(0, np.exp(-x**2 / (2 * stddev**2)) - np.exp(-r**2 / (2 * stddev**2))), 0)


FILTERS = {  # name: (w, radius), Mitsuba's defaults
    "lanczos": (lanczos, 3.0),
    "mitchell": (lambda x: mitchell_netravali(x, 1 / 3, 1 / 3), 2.0),
    "catmullrom": (lambda x: mitchell_netravali(x, 0.0, 0.5), 2.0),
    "gaussian": (gaussian, 2.0),
}


def mitsuba_table(w, r):
    """Mitsuba's eval_discretized: w(r·i/31) at index ⌊31·|x|/r⌋, 0 from index 31."""
    values = np.array([w(r * i / 31) for i in range(31)] + [0.0], dtype=np.float32)
    return lambda x: values[np.minimum((np.abs(x) * np.float32(31 / r)).astype(int), 31)]


def predicted(w):
    s = (np.arange(32 * 4096) + 0.5) / 4096
    out = []
    for p in range(32):
        weights = w(p + 0.5 - s)
        out.append((weights * (s < EDGE)).sum() / weights.sum())
    return np.array(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default="target/release/caustic")
    ap.add_argument("--filter", default="lanczos", choices=sorted(FILTERS))
    ap.add_argument("--renders", type=int, default=64, help="Mitsuba's renders of 1024 spp")
    ap.add_argument("--spp", type=int, default=16384, help="caustic's samples per pixel")
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    w, r = FILTERS[args.filter]
    with tempfile.TemporaryDirectory() as scratch:
        xml = os.path.join(scratch, "edge.xml")
        with open(xml, "w") as f:
            f.write(SCENE.format(filter=args.filter, shift=-1 + EDGE / 16 - 5))
        scene = mi.load_file(xml)
        total = sum(np.array(mi.render(scene, seed=s), dtype=np.float64) for s in range(args.renders))
        mitsuba = (total / args.renders)[..., 0].mean(0)
        out = os.path.join(scratch, "caustic.exr")
        subprocess.run([args.binary, "render", xml, "--backend", "cpu", "--spp", str(args.spp), "-o", out],
                       check=True, capture_output=True)
        caustic = np.array(mi.Bitmap(out), dtype=np.float64)[..., 0].mean(0)
    table, exact = predicted(mitsuba_table(w, r)), predicted(w)
    print(f"{args.filter}, edge at x = {EDGE} px; Mitsuba {args.renders}x1024 spp, caustic {args.spp} spp")
    print(f"{'pixel':>5} {'Mitsuba':>9} {'its table':>10} {'exact w':>9} {'caustic':>9}")
    for p in range(int(EDGE - r) - 1, int(EDGE + r) + 2):
        print(f"{p:>5} {mitsuba[p]:9.5f} {table[p]:10.5f} {exact[p]:9.5f} {caustic[p]:9.5f}")


if __name__ == "__main__":
    main()
