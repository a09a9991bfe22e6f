#!/usr/bin/env python3
"""Writes mitsuba_bsdf_values.json: Mitsuba 3.9.1's own BSDF values, against which
kernel/tests/bsdf_mitsuba.rs checks caustic's models.

    python3 -m venv /tmp/mi-venv && /tmp/mi-venv/bin/pip install mitsuba==3.9.1
    /tmp/mi-venv/bin/python kernel/tests/data/mitsuba_bsdf_values.py           # rewrite the file
    /tmp/mi-venv/bin/python kernel/tests/data/mitsuba_bsdf_values.py --check   # compare, write nothing
    /tmp/mi-venv/bin/python kernel/tests/data/mitsuba_bsdf_values.py --fresh 7 # new random inputs

(The `scalar_rgb` variant needs nothing beyond the wheel.)

What the file holds. For each material of `MATERIALS` (the Mitsuba dictionaries that the Rust
test's `reference_material` mirrors parameter for parameter) and transport mode (`adjoint` = Mitsuba's
`TransportMode.Importance`):
  - "eval": for a direction pair, `bsdf.eval(ctx, si, wi)` (f·|cos θi|, RGB) and `bsdf.pdf(ctx, si, wi)`;
  - "sample": for random numbers `u_lobe`, `u`, `bsdf.sample(ctx, si, u_lobe, u)`: the direction,
    weight (f·cos/pdf), pdf and relative IOR.
Directions are in the local shading frame (normal +z). caustic's `wo` (towards the viewer) is Mitsuba's
`si.wi`; caustic's `wi` (towards the light) is Mitsuba's `wo`. Mitsuba's scalar variant computes in float32;
every value is written with 9 significant digits, which read back as the same float32.

Inputs. By default the script keeps the inputs of the existing file (model, mode, wo, wi, u_lobe, u)
and recomputes every output, so that the file can be regenerated without moving the test points.
Those inputs came with the first version of these values (Rust literals, before this script existed):
per material and mode six `wo` (the first always (0.9974587, 0, 0.07124705), near grazing; the refracting
models' last one below the surface), and for each `wo` two eval pairs (a `wi` uniform on the sphere and
a `wi` near a direction that `sample` returned) and two sample points (four for the Dirac-delta models).
The random generator that drew them is not recorded, so `--fresh SEED` draws new inputs the same way
with Python's `random` instead; the Rust test reads whatever the file holds.

Reproduction (`--check`, Mitsuba 3.9.1 from PyPI on x86-64 Linux): of the 360 committed rows, 341 are
reproduced bitwise and 19 differ by a few float32 ulps (at most 9e-7 relative; the tests allow 2e-3):
eval rows of plastic_nonlinear (1), rough_plastic_beckmann (4) and rough_plastic_ggx_nonlinear (3), and
sample rows of rough_plastic_beckmann (6), rough_plastic_ggx_nonlinear (3) and
rough_dielectric_beckmann_aniso adjoint (1). The committed file keeps the first values; why those rows
came out a few ulps apart then is not known (the first values may come from another build, CPU or
variant of the same release; plastic and rough plastic sum precomputed integrals, where a different
order or fused multiply-add moves the last bits). Running the script without `--check` replaces them.
"""
import argparse
import json
import math
import os
import random
import struct
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "mitsuba_bsdf_values.json")
COMMAND = "/tmp/mi-venv/bin/python kernel/tests/data/mitsuba_bsdf_values.py"


def rgb(r, g, b):
    return {"type": "rgb", "value": [r, g, b]}


# Conductor indices (a copper-like RGB), coloured reflectance/transmittance: every channel differs, so
# that a swapped channel shows. `ext_ior = 1` throughout: caustic's interfaces are against vacuum.
ETA, K = rgb(0.2, 0.9, 1.1), rgb(3.9, 2.4, 2.2)
SR, ST = rgb(0.9, 0.8, 0.7), rgb(0.6, 0.7, 0.8)

MATERIALS = {
    "conductor": {"type": "conductor", "eta": ETA, "k": K, "specular_reflectance": rgb(1.0, 0.8, 0.6)},
    "rough_conductor_ggx_aniso": {
        "type": "roughconductor",
        "distribution": "ggx",
        "alpha_u": 0.1,
        "alpha_v": 0.4,
        "eta": ETA,
        "k": K,
        "specular_reflectance": rgb(1.0, 0.8, 0.6),
    },
    "rough_conductor_beckmann": {
        "type": "roughconductor",
        "distribution": "beckmann",
        "alpha": 0.3,
        "eta": ETA,
        "k": K,
    },
    "dielectric": {
        "type": "dielectric",
        "int_ior": 1.5,
        "ext_ior": 1.0,
        "specular_reflectance": SR,
        "specular_transmittance": ST,
    },
    "thin_dielectric": {
        "type": "thindielectric",
        "int_ior": 1.5,
        "ext_ior": 1.0,
        "specular_reflectance": SR,
        "specular_transmittance": ST,
    },
    "rough_dielectric_ggx": {
        "type": "roughdielectric",
        "distribution": "ggx",
        "alpha": 0.2,
        "int_ior": 1.5,
        "ext_ior": 1.0,
        "specular_reflectance": SR,
        "specular_transmittance": ST,
    },
    "rough_dielectric_beckmann_aniso": {
        "type": "roughdielectric",
        "distribution": "beckmann",
        "alpha_u": 0.05,
        "alpha_v": 0.3,
        "int_ior": 2.42,
        "ext_ior": 1.0,
    },
    "plastic": {"type": "plastic", "int_ior": 1.5, "ext_ior": 1.0, "diffuse_reflectance": rgb(0.3, 0.5, 0.7)},
    "plastic_nonlinear": {
        "type": "plastic",
        "int_ior": 1.9,
        "ext_ior": 1.0,
        "nonlinear": True,
        "diffuse_reflectance": rgb(0.8, 0.4, 0.1),
        "specular_reflectance": rgb(0.9, 0.7, 0.9),
    },
    "rough_plastic_beckmann": {
        "type": "roughplastic",
        "distribution": "beckmann",
        "alpha": 0.1,
        "int_ior": 1.5,
        "ext_ior": 1.0,
        "diffuse_reflectance": rgb(0.3, 0.5, 0.7),
    },
    "rough_plastic_ggx_nonlinear": {
        "type": "roughplastic",
        "distribution": "ggx",
        "alpha": 0.4,
        "int_ior": 1.9,
        "ext_ior": 1.0,
        "nonlinear": True,
        "diffuse_reflectance": rgb(0.8, 0.4, 0.1),
        "specular_reflectance": rgb(0.9, 0.7, 0.9),
    },
}

# The (material, adjoint) runs of each kind, in file order; `--fresh` draws inputs for these. The smooth
# Dirac-delta models have no eval rows (their eval and pdf are zero everywhere).
DELTA = {"conductor", "dielectric", "thin_dielectric"}
REFRACTING = {"dielectric", "thin_dielectric", "rough_dielectric_ggx", "rough_dielectric_beckmann_aniso"}
RUNS = [(m, adj) for m in MATERIALS for adj in ([False, True] if m in REFRACTING else [False])]
GRAZING_WO = [0.9974587, 0.0, 0.07124705]


def f32(x):
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def decimal(x, single=True):
    """`x` in 9 significant digits, enough to read back the same float32, without trailing zeros.
    Outputs are rounded to float32 first (what Mitsuba computed); inputs are written as read, so that
    regenerating the file keeps their digits (the first inputs were doubles printed to 9 digits)."""
    x = f32(x) if single else float(x)
    if x == 0.0:
        return "-0.0" if math.copysign(1.0, x) < 0 else "0.0"
    s = "%.9g" % x
    if "e" not in s and "." not in s:
        s += ".0"
    return s


def bsdf_of(name, cache={}):
    if name not in cache:
        cache[name] = mi.load_dict(MATERIALS[name])
    return cache[name]


def context(adjoint):
    return mi.BSDFContext(mi.TransportMode.Importance if adjoint else mi.TransportMode.Radiance)


def interaction(wo):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wo)
    return si


def eval_row(model, adjoint, wo, wi):
    b, ctx, si = bsdf_of(model), context(adjoint), interaction(wo)
    f = b.eval(ctx, si, mi.Vector3f(*wi))
    pdf = b.pdf(ctx, si, mi.Vector3f(*wi))
    return {"model": model, "adjoint": adjoint, "wo": wo, "wi": wi, "f": list(f), "pdf": pdf}


def sample_row(model, adjoint, wo, u_lobe, u):
    b, ctx, si = bsdf_of(model), context(adjoint), interaction(wo)
    bs, weight = b.sample(ctx, si, u_lobe, mi.Point2f(*u))
    return {
        "model": model,
        "adjoint": adjoint,
        "wo": wo,
        "u_lobe": u_lobe,
        "u": u,
        "wi": list(bs.wo),
        "weight": list(weight),
        "pdf": bs.pdf,
        "eta": bs.eta,
    }


def fresh_inputs(seed):
    """New inputs drawn as the first ones were (see the header), with Python's `random`."""
    rng = random.Random(seed)

    def sphere():
        z = 1.0 - 2.0 * rng.random()
        r, phi = math.sqrt(max(0.0, 1.0 - z * z)), 2.0 * math.pi * rng.random()
        return [f32(r * math.cos(phi)), f32(r * math.sin(phi)), f32(z)]

    def above():
        w = sphere()
        return [w[0], w[1], abs(w[2])]

    def normalised(v):
        n = math.sqrt(sum(c * c for c in v))
        return [f32(c / n) for c in v]

    evals, samples = [], []
    for model, adjoint in RUNS:
        wos = [GRAZING_WO] + [above() for _ in range(5)]
        if model in REFRACTING:
            wos[-1] = [wos[-1][0], wos[-1][1], -wos[-1][2]]
        for wo in wos:
            for _ in range(4 if model in DELTA else 2):
                u = [f32(rng.random()), f32(rng.random())]
                samples.append((model, adjoint, wo, f32(rng.random()), u))
            if model in DELTA:
                continue
            evals.append((model, adjoint, wo, sphere()))
            # Near a sampled direction, where the value is large and the lobe's shape matters.
            s = sample_row(model, adjoint, wo, f32(rng.random()), [f32(rng.random()), f32(rng.random())])
            if s["pdf"] > 0.0:
                jitter = sphere()
                near = normalised([s["wi"][k] + 0.05 * jitter[k] for k in range(3)])
            else:
                near = sphere()
            evals.append((model, adjoint, wo, near))
    return evals, samples


def committed_inputs(data):
    evals = [(r["model"], r["adjoint"], r["wo"], r["wi"]) for r in data["eval"]]
    samples = [(r["model"], r["adjoint"], r["wo"], r["u_lobe"], r["u"]) for r in data["sample"]]
    return evals, samples


INPUTS = {"eval": {"model", "adjoint", "wo", "wi"}, "sample": {"model", "adjoint", "wo", "u_lobe", "u"}}


def dump(evals, samples):
    def value(v, single):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(value(c, single) for c in v) + "]"
        return decimal(v, single)

    def row(r, kind):
        return "{" + ", ".join('"%s": %s' % (k, value(v, k not in INPUTS[kind])) for k, v in r.items()) + "}"

    about = (
        "Mitsuba 3.9.1 (scalar_rgb) BSDF values for kernel/tests/bsdf_mitsuba.rs; "
        "mitsuba_bsdf_values.py (next to this file) says what each field is and wrote them."
    )
    lines = ["{", '"about": %s,' % json.dumps(about), '"regenerate": %s,' % json.dumps(COMMAND)]
    # The Mitsuba dictionaries, for the reader: the Rust test builds its materials itself.
    lines.append('"materials": {')
    lines.append(",\n".join("%s: %s" % (json.dumps(k), json.dumps(v)) for k, v in MATERIALS.items()))
    lines.append("},")
    lines.append('"eval": [')
    lines.append(",\n".join(row(r, "eval") for r in evals))
    lines.append("],")
    lines.append('"sample": [')
    lines.append(",\n".join(row(r, "sample") for r in samples))
    lines.append("]")
    lines.append("}")
    return "\n".join(lines) + "\n"


def close(a, b, rel, abs_):
    return abs(a - b) <= abs_ + rel * max(abs(a), abs(b))


def compare(old, new):
    """Differences between the committed and the recomputed rows: bitwise, and at the Rust test's
    tolerances (eval 2e-3 rel + 1e-6 abs; sample wi 1e-3/1e-4, weight and pdf 3e-3/1e-5 and 1e-6)."""
    exact = within = 0
    out = []
    for kind, fields in [("eval", {"f": (2e-3, 1e-6), "pdf": (2e-3, 1e-6)}),
                         ("sample", {"wi": (1e-3, 1e-4), "weight": (3e-3, 1e-5), "pdf": (3e-3, 1e-6),
                                     "eta": (0.0, 0.0)})]:
        for i, (o, n) in enumerate(zip(old[kind], new[kind])):
            same = all(f32_list(o[k]) == f32_list(n[k]) for k in fields)
            ok = all(all(close(a, b, *tol) for a, b in zip(f32_list(o[k]), f32_list(n[k])))
                     for k, tol in fields.items())
            exact += same
            within += ok and not same
            if not ok:
                out.append("%s[%d] %s adjoint=%s: committed %s, Mitsuba %s" % (
                    kind, i, o["model"], o["adjoint"], {k: o[k] for k in fields}, {k: n[k] for k in fields}))
    return exact, within, out


def f32_list(v):
    return [f32(c) for c in (v if isinstance(v, list) else [v])]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--check", action="store_true", help="compare with the file, write nothing")
    p.add_argument("--fresh", type=int, metavar="SEED", help="draw new inputs instead of the file's")
    p.add_argument("--out", default=OUT)
    args = p.parse_args()
    old = json.load(open(OUT)) if os.path.exists(OUT) else None
    if args.fresh is not None:
        evals, samples = fresh_inputs(args.fresh)
    else:
        evals, samples = committed_inputs(old)
    new = {
        "eval": [eval_row(*i) for i in evals],
        "sample": [sample_row(*i) for i in samples],
    }
    if old is not None and args.fresh is None:
        exact, within, bad = compare(old, new)
        total = len(old["eval"]) + len(old["sample"])
        print("%d of %d rows reproduced bitwise, %d more within the test's tolerances, %d not"
              % (exact, total, within, len(bad)))
        for line in bad:
            print("  " + line)
        if args.check:
            sys.exit(1 if bad else 0)
    if not args.check:
        open(args.out, "w").write(dump(new["eval"], new["sample"]))
        print("wrote %s (%d eval, %d sample rows)" % (args.out, len(new["eval"]), len(new["sample"])))


if __name__ == "__main__":
    main()
