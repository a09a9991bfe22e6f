#!/usr/bin/env python3
"""Writes the large-scene benchmark (BENCHMARKS.md, "Large scenes"): a field of displaced spheres, each
a copy of one bumpy icosphere mesh (20 480 triangles) placed as its own `ply` shape with its own
transform, so both caustic and Mitsuba hold every triangle (no instancing). Plain Python, deterministic.

    python3 scenes/generate_large.py [--instanced] OUT_DIR [TRIANGLES ...]      # default: 1e6 1e7 5e7

writes OUT_DIR/blob.ply and OUT_DIR/large-<n>.xml for each triangle count n (rounded up to whole copies).
With `--instanced`, the same field as `instance`s of three shapegroups (the mesh once per colour), in
OUT_DIR/large-<n>-instanced.xml: the same image, with the mesh stored once per group.
The scenes take `-D spp=...` and `-D res=...` (defaults 16 and 512); lit by a constant sky and a
rectangle light, path tracer at depth 6, three diffuse colours.
"""
import math
import os
import random
import struct
import sys

LEVELS = 5  # 20 * 4^5 = 20 480 triangles per copy


def icosphere(levels):
    t = (1 + 5 ** 0.5) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [normalised(v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        midpoint = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                va, vb = verts[a], verts[b]
                verts.append(normalised(tuple((x + y) / 2 for x, y in zip(va, vb))))
                midpoint[key] = len(verts) - 1
            return midpoint[key]

        refined = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            refined += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = refined
    return verts, faces


def normalised(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def displaced(v):
    """The unit sphere pushed in and out by a few smooth bumps (radius 0.8 to 1.2)."""
    x, y, z = v
    r = 1 + 0.12 * math.sin(5 * x + 1) * math.sin(4 * y + 2) * math.sin(6 * z) + 0.08 * math.sin(9 * (x + y + z))
    return (x * r, y * r, z * r)


def write_ply(path, verts, faces):
    with open(path, "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {len(verts)}\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        for v in verts:
            f.write(struct.pack("<3f", *v))
        for a, b, c in faces:
            f.write(struct.pack("<B3i", 3, a, b, c))


def write_scene(path, copies, seed=7, instanced=False):
    rng = random.Random(seed)
    side = math.ceil(math.sqrt(copies))
    spacing = 2.6
    extent = side * spacing
    shapes = []
    for i in range(copies):
        gx, gz = i % side, i // side
        x = (gx - (side - 1) / 2) * spacing + rng.uniform(-0.4, 0.4)
        z = (gz - (side - 1) / 2) * spacing + rng.uniform(-0.4, 0.4)
        s = rng.uniform(0.8, 1.1)
        placed = (f'    <shape type="instance">\n        <ref id="g{i % 3}"/>\n' if instanced else
                  f'    <shape type="ply">\n        <string name="filename" value="blob.ply"/>\n'
                  f'        <ref id="m{i % 3}"/>\n')
        shapes.append(
            placed + f'        <transform name="to_world">\n'
            f'            <rotate y="1" angle="{rng.uniform(0, 360):.3f}"/>\n'
            f'            <scale value="{s:.4f}"/>\n'
            f'            <translate x="{x:.4f}" y="{s:.4f}" z="{z:.4f}"/>\n'
            f'        </transform>\n    </shape>\n')
    eye = 0.75 * extent
    colours = [(0.7, 0.3, 0.2), (0.3, 0.6, 0.3), (0.6, 0.6, 0.65)]
    with open(path, "w") as f:
        f.write(f'<scene version="3.0.0">\n'
                f'    <default name="spp" value="16"/>\n    <default name="res" value="512"/>\n'
                f'    <integrator type="path"><integer name="max_depth" value="6"/></integrator>\n'
                f'    <sensor type="perspective">\n        <float name="fov" value="45"/>\n'
                f'        <transform name="to_world"><lookat origin="{eye:.3f}, {0.55 * extent:.3f}, {eye:.3f}" '
                f'target="0, 0, 0" up="0, 1, 0"/></transform>\n'
                f'        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>\n'
                f'        <film type="hdrfilm"><integer name="width" value="$res"/>'
                f'<integer name="height" value="$res"/><rfilter type="box"/></film>\n    </sensor>\n')
        for k, c in enumerate(colours):
            f.write(f'    <bsdf type="diffuse" id="m{k}"><rgb name="reflectance" value="{c[0]}, {c[1]}, {c[2]}"/></bsdf>\n')
            if instanced:
                f.write(f'    <shape type="shapegroup" id="g{k}"><shape type="ply">'
                        f'<string name="filename" value="blob.ply"/><ref id="m{k}"/></shape></shape>\n')
        f.write(f'    <emitter type="constant"><rgb name="radiance" value="0.4, 0.45, 0.5"/></emitter>\n'
                f'    <shape type="rectangle">\n        <transform name="to_world">'
                f'<scale value="{extent / 4:.3f}"/><rotate x="1" angle="90"/>'
                f'<translate y="{extent / 2:.3f}"/></transform>\n'
                f'        <emitter type="area"><rgb name="radiance" value="4, 3.8, 3.5"/></emitter>\n    </shape>\n'
                f'    <shape type="rectangle">\n        <transform name="to_world"><scale value="{extent:.3f}"/>'
                f'<rotate x="1" angle="-90"/></transform>\n        <ref id="m2"/>\n    </shape>\n')
        f.writelines(shapes)
        f.write("</scene>\n")


def write(out, targets, instanced=False):
    """Writes blob.ply and one scene per triangle count into `out`; returns [(path, triangles)]."""
    os.makedirs(out, exist_ok=True)
    verts, faces = icosphere(LEVELS)
    write_ply(os.path.join(out, "blob.ply"), [displaced(v) for v in verts], faces)
    written = []
    for t in targets:
        copies = -(-t // len(faces))
        suffix = "-instanced.xml" if instanced else ".xml"
        name = os.path.join(out, f"large-{t:.0e}".replace("+0", "").replace("+", "") + suffix)
        write_scene(name, copies, instanced=instanced)
        written.append((name, copies * len(faces)))
    return written


def main():
    args = sys.argv[1:]
    instanced = "--instanced" in args
    args = [a for a in args if a != "--instanced"]
    if any(a in ("-h", "--help") for a in args):
        print(__doc__)
        return
    unknown = [a for a in args if a.startswith("-")]
    if unknown:
        # (A mistyped option used to become the output directory.)
        sys.exit(f"generate_large.py: unknown option {unknown[0]}\n{__doc__}")
    if not args:
        sys.exit(__doc__)
    targets = [int(float(t)) for t in args[1:]] or [10**6, 10**7, 5 * 10**7]
    for name, triangles in write(args[0], targets, instanced):
        print(f"{name}: {triangles} triangles")


if __name__ == "__main__":
    main()
