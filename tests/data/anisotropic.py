"""Writes uv_sphere.obj (a sphere of 32x16 quads with texture coordinates and normals, no tangents)
and renders the reference of tests/tests/anisotropic.rs from anisotropic.xml with Mitsuba 3.9.1's
scalar_rgb variant, 40x30, 16384 spp: anisotropic.exr.
Run: python anisotropic.py (with mitsuba installed; about a minute)."""
import math
import os
import mitsuba as mi

here = os.path.dirname(os.path.abspath(__file__))
nu, nv = 32, 16
lines = ["# A unit UV sphere for anisotropic.xml, written by anisotropic.py"]
for j in range(nv + 1):
    for i in range(nu + 1):
        u, v = i / nu, j / nv
        phi, theta = 2 * math.pi * u, math.pi * v
        x, y, z = math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)
        lines += [f"v {x:.6f} {y:.6f} {z:.6f}", f"vt {u:.6f} {1 - v:.6f}", f"vn {x:.6f} {y:.6f} {z:.6f}"]
row = nu + 1
for j in range(nv):
    for i in range(nu):
        a, b, c, d = j * row + i + 1, j * row + i + 2, (j + 1) * row + i + 2, (j + 1) * row + i + 1
        if j > 0:
            lines.append(f"f {a}/{a}/{a} {d}/{d}/{d} {b}/{b}/{b}")
        if j < nv - 1:
            lines.append(f"f {b}/{b}/{b} {d}/{d}/{d} {c}/{c}/{c}")
with open(os.path.join(here, "uv_sphere.obj"), "w") as f:
    f.write("\n".join(lines) + "\n")

mi.set_variant("scalar_rgb")
scene = mi.load_file(os.path.join(here, "anisotropic.xml"), spp="16384")
mi.Bitmap(mi.render(scene, seed=1)).write(os.path.join(here, "anisotropic.exr"))
