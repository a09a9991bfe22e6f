#!/usr/bin/env python3
"""Writes principled_values.json: Mitsuba 3.9.1's own `principled` BSDF values, against which
kernel/tests/bsdf_principled.rs checks caustic's model (`kernel/src/bsdf/principled.rs`).

    /tmp/mi-venv/bin/python kernel/tests/data/principled_values.py   # (re)write the file

Rows have the fields of mitsuba_bsdf_values.json (that script's header explains them): "eval" rows
hold `bsdf.eval` (f·|cos θi|, RGB) and `bsdf.pdf` for caustic's (wo, wi) = Mitsuba's (si.wi, wo);
"sample" rows `bsdf.sample` for (u_lobe, u). Inputs are drawn from Python's `random` with a fixed
seed, so that running the script again writes the same file. Per material and mode: eight `wo`
(the first near grazing; for the transmissive materials the last two below the surface), and for
each two eval pairs (a `wi` uniform on the sphere, and one near a direction `sample` returned) and
three sample points. `MATERIALS` is mirrored parameter for parameter by the Rust test's
`principled_material`.
"""
import json
import math
import os
import random
import struct

import mitsuba as mi

mi.set_variant("scalar_rgb")

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "principled_values.json")


def rgb(r, g, b):
    return {"type": "rgb", "value": [r, g, b]}


MATERIALS = {
    # Every default: base 0.5, roughness 0.5, specular 0.5 (eta 1.5).
    "default": {"type": "principled"},
    "metal": {
        "type": "principled",
        "base_color": rgb(0.9, 0.6, 0.3),
        "metallic": 0.8,
        "roughness": 0.3,
        "anisotropic": 0.5,
        "spec_tint": 0.4,
    },
    "glass": {
        "type": "principled",
        "base_color": rgb(0.9, 0.8, 0.7),
        "spec_trans": 0.9,
        "eta": 1.45,
        "roughness": 0.2,
    },
    "everything": {
        "type": "principled",
        "base_color": rgb(0.8, 0.3, 0.2),
        "metallic": 0.3,
        "spec_trans": 0.4,
        "specular": 0.6,
        "roughness": 0.4,
        "anisotropic": 0.2,
        "spec_tint": 0.5,
        "sheen": 0.7,
        "sheen_tint": 0.5,
        "clearcoat": 0.8,
        "clearcoat_gloss": 0.6,
        "flatness": 0.3,
    },
    "coat_and_rates": {
        "type": "principled",
        "base_color": rgb(0.2, 0.4, 0.8),
        "roughness": 0.7,
        "sheen": 1.0,
        "clearcoat": 1.0,
        "clearcoat_gloss": 0.9,
        "main_specular_sampling_rate": 0.5,
        "clearcoat_sampling_rate": 2.0,
        "diffuse_reflectance_sampling_rate": 0.7,
    },
    # eta < 1: the Schlick terms switch to the refracted cosine.
    "eta_below_one": {
        "type": "principled",
        "base_color": rgb(0.7, 0.7, 0.5),
        "spec_trans": 0.5,
        "eta": 0.8,
        "roughness": 0.3,
        "clearcoat": 0.5,
    },
}
TRANSMISSIVE = {"glass", "everything", "eta_below_one"}
GRAZING_WO = [0.9974587, 0.0, 0.07124705]


def f32(x):
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def interaction(wo):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wo)
    return si


def context(adjoint):
    return mi.BSDFContext(mi.TransportMode.Importance if adjoint else mi.TransportMode.Radiance)


def main():
    rng = random.Random(13)

    def sphere():
        z = 1.0 - 2.0 * rng.random()
        r, phi = math.sqrt(max(0.0, 1.0 - z * z)), 2.0 * math.pi * rng.random()
        return [f32(r * math.cos(phi)), f32(r * math.sin(phi)), f32(z)]

    def normalised(v):
        n = math.sqrt(sum(c * c for c in v))
        return [f32(c / n) for c in v]

    evals, samples = [], []
    for name, params in MATERIALS.items():
        b = mi.load_dict(params)
        for adjoint in [False, True] if name in TRANSMISSIVE else [False]:
            ctx = context(adjoint)
            wos = [GRAZING_WO] + [[w[0], w[1], abs(w[2])] for w in (sphere() for _ in range(7))]
            if name in TRANSMISSIVE:
                wos[-1][2] = -wos[-1][2]
                wos[-2][2] = -wos[-2][2]

            def sample(wo, u_lobe, u):
                bs, weight = b.sample(ctx, interaction(wo), u_lobe, mi.Point2f(*u))
                return {"model": name, "adjoint": adjoint, "wo": wo, "u_lobe": u_lobe, "u": u,
                        "wi": [f32(c) for c in bs.wo], "weight": [f32(c) for c in weight],
                        "pdf": f32(bs.pdf), "eta": f32(bs.eta)}

            def evaluate(wo, wi):
                si = interaction(wo)
                f = b.eval(ctx, si, mi.Vector3f(*wi))
                return {"model": name, "adjoint": adjoint, "wo": wo, "wi": wi,
                        "f": [f32(c) for c in f], "pdf": f32(b.pdf(ctx, si, mi.Vector3f(*wi)))}

            for wo in wos:
                for _ in range(3):
                    samples.append(sample(wo, f32(rng.random()), [f32(rng.random()), f32(rng.random())]))
                evals.append(evaluate(wo, sphere()))
                s = sample(wo, f32(rng.random()), [f32(rng.random()), f32(rng.random())])
                if s["pdf"] > 0.0:
                    jitter = sphere()
                    near = normalised([s["wi"][k] + 0.05 * jitter[k] for k in range(3)])
                else:
                    near = sphere()
                evals.append(evaluate(wo, near))
    data = {
        "about": "Mitsuba 3.9.1 (scalar_rgb) principled BSDF values for kernel/tests/bsdf_principled.rs, "
        "written by principled_values.py next to this file",
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
