"""Writes the PLY meshes of tests/tests/mesh_attribute.rs and renders their references with Mitsuba
3.9.1's path integrator (scalar_rgb), 64x64, 2048 spp: mesh_attribute.exr (mesh_attribute.xml) and
mesh_attribute_instanced.exr (of mesh_attribute_placed.xml: mesh_attribute_instanced.xml says why).
mesh_attribute.ply: a 4x4-vertex grid of 18 triangles in [-1, 1]^2 (z = 0) with float vertex colours
(r g b: `vertex_color`), a one-channel face property `wear_x` (`face_wear`) and a three-channel one
`tint_r tint_g tint_b` (`face_tint_color`), all from a fixed pseudo-random sequence.
mesh_attribute_mean.ply: the same grid with every attribute replaced by its mean (the negative control).
Run: python mesh_attribute.py (with mitsuba installed)."""
import os
import random

here = os.path.dirname(os.path.abspath(__file__))
N = 4
rng = random.Random(7)
verts = [(-1 + 2 * i / (N - 1), -1 + 2 * j / (N - 1)) for j in range(N) for i in range(N)]
colors = [tuple(round(rng.uniform(0.05, 0.95), 4) for _ in range(3)) for _ in verts]
faces = []
for j in range(N - 1):
    for i in range(N - 1):
        a, b, c, d = j * N + i, j * N + i + 1, (j + 1) * N + i + 1, (j + 1) * N + i
        faces += [(a, b, c), (a, c, d)]
wear = [round(rng.uniform(0.05, 0.95), 4) for _ in faces]
tint = [tuple(round(rng.uniform(0.05, 0.95), 4) for _ in range(3)) for _ in faces]


def mean(rows):
    return tuple(round(sum(r[k] for r in rows) / len(rows), 6) for k in range(len(rows[0])))


def write(name, colors, wear, tint):
    lines = ["ply", "format ascii 1.0", f"element vertex {len(verts)}",
             "property float x", "property float y", "property float z",
             "property float r", "property float g", "property float b",
             f"element face {len(faces)}", "property list uchar int vertex_indices",
             "property float wear_x", "property float tint_r", "property float tint_g", "property float tint_b",
             "end_header"]
    lines += [f"{x} {y} 0 {c[0]} {c[1]} {c[2]}" for (x, y), c in zip(verts, colors)]
    lines += [f"3 {f[0]} {f[1]} {f[2]} {w} {t[0]} {t[1]} {t[2]}" for f, w, t in zip(faces, wear, tint)]
    with open(os.path.join(here, name), "w") as out:
        out.write("\n".join(lines) + "\n")


write("mesh_attribute.ply", colors, wear, tint)
m = mean(colors)
write("mesh_attribute_mean.ply", [m] * len(colors), [mean([(w,) for w in wear])[0]] * len(faces),
      [mean(tint)] * len(faces))

if __name__ == "__main__":
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    # Mitsuba's instances read wrong attributes (mesh_attribute_instanced.xml says why): the
    # instanced scene's reference is the same meshes placed as plain shapes.
    for scene_name, out in [("mesh_attribute", "mesh_attribute"), ("mesh_attribute_placed", "mesh_attribute_instanced")]:
        scene = mi.load_file(os.path.join(here, scene_name + ".xml"))
        mi.Bitmap(mi.render(scene, spp=2048, seed=1)).write(os.path.join(here, out + ".exr"))
