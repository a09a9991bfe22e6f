#!/usr/bin/env python3
"""Writes pplastic_values.json: Mitsuba 3.9.1's own `pplastic` BSDF values (scalar_rgb: the
unpolarized code), against which kernel/tests/bsdf_pplastic.rs checks caustic's model
(`kernel/src/bsdf/pplastic.rs`).

    /tmp/mi-venv/bin/python kernel/tests/data/pplastic_values.py   # (re)write the file

Rows have the fields of mitsuba_bsdf_values.json (that script's header explains them). Inputs are
drawn from Python's `random` with a fixed seed, so that running the script again writes the same file.
Per material (its values do not depend on the transport mode, so only radiance is tested): eight
`wo` (the first near grazing, the last one below the surface, where it is black), for each two eval
pairs (a `wi` uniform on the sphere, and one near a direction `sample` returned) and three sample
points. `MATERIALS` is mirrored parameter for parameter by the Rust test's `pplastic_material`.
"""
import json
import math
import os
import random
import struct

import mitsuba as mi

mi.set_variant("scalar_rgb")

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "pplastic_values.json")


def rgb(r, g, b):
    return {"type": "rgb", "value": [r, g, b]}


MATERIALS = {
    # Every default: Beckmann, alpha 0.1, polypropylene over air, diffuse 0.5, specular 1.
    "default": {"type": "pplastic"},
    "ggx_aniso": {
        "type": "pplastic",
        "distribution": "ggx",
        "alpha_u": 0.05,
        "alpha_v": 0.3,
        "diffuse_reflectance": rgb(0.2, 0.4, 0.9),
        "specular_reflectance": rgb(0.9, 0.7, 0.5),
        "eta": 1.7,
    },
    "rough_beckmann": {
        "type": "pplastic",
        "alpha": 0.5,
        "int_ior": 1.33,
        "ext_ior": 1.1,
        "diffuse_reflectance": rgb(0.8, 0.3, 0.1),
    },
}
GRAZING_WO = [0.9974587, 0.0, 0.07124705]


def f32(x):
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def interaction(wo):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wo)
    return si


def main():
    rng = random.Random(17)

    def sphere():
        z = 1.0 - 2.0 * rng.random()
        r, phi = math.sqrt(max(0.0, 1.0 - z * z)), 2.0 * math.pi * rng.random()
        return [f32(r * math.cos(phi)), f32(r * math.sin(phi)), f32(z)]

    def normalised(v):
        n = math.sqrt(sum(c * c for c in v))
        return [f32(c / n) for c in v]

    evals, samples = [], []
    ctx = mi.BSDFContext(mi.TransportMode.Radiance)
    for name, params in MATERIALS.items():
        b = mi.load_dict(params)
        wos = [GRAZING_WO] + [[w[0], w[1], abs(w[2])] for w in (sphere() for _ in range(7))]
        wos[-1][2] = -wos[-1][2]

        def sample(wo, u_lobe, u):
            bs, weight = b.sample(ctx, interaction(wo), u_lobe, mi.Point2f(*u))
            return {"model": name, "adjoint": False, "wo": wo, "u_lobe": u_lobe, "u": u,
                    "wi": [f32(c) for c in bs.wo], "weight": [f32(c) for c in weight],
                    "pdf": f32(bs.pdf), "eta": f32(bs.eta)}

        def evaluate(wo, wi):
            si = interaction(wo)
            f = b.eval(ctx, si, mi.Vector3f(*wi))
            return {"model": name, "adjoint": False, "wo": wo, "wi": wi,
                    "f": [f32(c) for c in f], "pdf": f32(b.pdf(ctx, si, mi.Vector3f(*wi)))}

        for wo in wos:
            for _ in range(3):
                samples.append(sample(wo, f32(rng.random()), [f32(rng.random()), f32(rng.random())]))
            evals.append(evaluate(wo, sphere()))
            s = sample(wo, f32(rng.random()), [f32(rng.random()), f32(rng.random())])
            jitter = sphere()
            near = normalised([s["wi"][k] + 0.05 * jitter[k] for k in range(3)]) if s["pdf"] > 0 else sphere()
            evals.append(evaluate(wo, near))
    data = {
        "about": "Mitsuba 3.9.1 (scalar_rgb) pplastic BSDF values for "
        "kernel/tests/bsdf_pplastic.rs, written by pplastic_values.py next to this file",
        "materials": MATERIALS,
        "eval": evals,
        "sample": samples,
    }
    with open(OUT, "w") as f:
        json.dump(data, f, indent=None, separators=(",", ":"))
        f.write("\n")
    print("wrote %s (%d eval, %d sample rows)" % (OUT, len(evals), len(samples)))


if __name__ == "__main__":
    main()
