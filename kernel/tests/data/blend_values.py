#!/usr/bin/env python3
"""Writes blend_values.json: Mitsuba 3.9.1's own `blendbsdf` values, against which
kernel/tests/bsdf_blend.rs checks caustic's blend (`kernel/src/bsdf/blend.rs`).

    /tmp/mi-venv/bin/python kernel/tests/data/blend_values.py   # (re)write the file

Rows have the fields of mitsuba_bsdf_values.json (that script's header explains them). Each blend
mixes two of that script's `MATERIALS` (imported from it, so the Rust side builds them with
`reference_material`) or `DIFFUSE` below, with `weight` the weight of the second. Inputs are drawn from
Python's `random` with a fixed seed, so that running the script again writes the same file: per blend
and mode six `wo` (the first near grazing; for the transmissive blends the last one below the
surface), two eval pairs each (a `wi` uniform on the sphere and one near a sampled direction) and four
sample points. Samples of a Dirac lobe are where caustic departs from Mitsuba on purpose (the Rust
test's `dirac_samples_diverge_as_documented`).
"""
import json
import math
import os
import random
import struct
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "blend_values.json")
sys.path.insert(0, HERE)
from mitsuba_bsdf_values import MATERIALS, rgb  # noqa: E402

DIFFUSE = {"type": "diffuse", "reflectance": rgb(0.2, 0.6, 0.4)}
CHILDREN = dict(MATERIALS, diffuse=DIFFUSE)

# name: (first, second, weight of the second, transmissive)
BLENDS = {
    "diffuse+rough_conductor": ("diffuse", "rough_conductor_ggx_aniso", 0.3, False),
    "rough_plastic+rough_dielectric": ("rough_plastic_beckmann", "rough_dielectric_ggx", 0.6, True),
    "diffuse+conductor": ("diffuse", "conductor", 0.5, False),
    "dielectric+rough_conductor": ("dielectric", "rough_conductor_beckmann", 0.25, True),
    "plastic+diffuse": ("plastic", "diffuse", 0.8, False),
}
GRAZING_WO = [0.9974587, 0.0, 0.07124705]


def f32(x):
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def interaction(wo):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wo)
    return si


def main():
    rng = random.Random(26)

    def sphere():
        z = 1.0 - 2.0 * rng.random()
        r, phi = math.sqrt(max(0.0, 1.0 - z * z)), 2.0 * math.pi * rng.random()
        return [f32(r * math.cos(phi)), f32(r * math.sin(phi)), f32(z)]

    def normalised(v):
        n = math.sqrt(sum(c * c for c in v))
        return [f32(c / n) for c in v]

    evals, samples = [], []
    for name, (first, second, weight, transmissive) in BLENDS.items():
        b = mi.load_dict({"type": "blendbsdf", "weight": weight, "a": CHILDREN[first], "b": CHILDREN[second]})
        for adjoint in [False, True] if transmissive else [False]:
            ctx = mi.BSDFContext(mi.TransportMode.Importance if adjoint else mi.TransportMode.Radiance)
            wos = [GRAZING_WO] + [[w[0], w[1], abs(w[2])] for w in (sphere() for _ in range(5))]
            if transmissive:
                wos[-1][2] = -wos[-1][2]

            def sample(wo, u_lobe, u):
                bs, w = b.sample(ctx, interaction(wo), u_lobe, mi.Point2f(*u))
                return {"model": name, "adjoint": adjoint, "wo": wo, "u_lobe": u_lobe, "u": u,
                        "wi": [f32(c) for c in bs.wo], "weight": [f32(c) for c in w],
                        "pdf": f32(bs.pdf), "eta": f32(bs.eta)}

            def evaluate(wo, wi):
                si = interaction(wo)
                f = b.eval(ctx, si, mi.Vector3f(*wi))
                return {"model": name, "adjoint": adjoint, "wo": wo, "wi": wi,
                        "f": [f32(c) for c in f], "pdf": f32(b.pdf(ctx, si, mi.Vector3f(*wi)))}

            for wo in wos:
                for _ in range(4):
                    samples.append(sample(wo, f32(rng.random()), [f32(rng.random()), f32(rng.random())]))
                evals.append(evaluate(wo, sphere()))
                s = sample(wo, f32(rng.random()), [f32(rng.random()), f32(rng.random())])
                jitter = sphere()
                near = normalised([s["wi"][k] + 0.05 * jitter[k] for k in range(3)]) if s["pdf"] > 0 else sphere()
                evals.append(evaluate(wo, near))
    data = {
        "about": "Mitsuba 3.9.1 (scalar_rgb) blendbsdf values for kernel/tests/bsdf_blend.rs, "
        "written by blend_values.py next to this file",
        "children": CHILDREN,
        "blends": {k: {"first": a, "second": b, "weight": w} for k, (a, b, w, _) in BLENDS.items()},
        "eval": evals,
        "sample": samples,
    }
    with open(OUT, "w") as f:
        json.dump(data, f, indent=None, separators=(",", ":"))
        f.write("\n")
    print("wrote %s (%d eval, %d sample rows)" % (OUT, len(evals), len(samples)))


if __name__ == "__main__":
    main()
