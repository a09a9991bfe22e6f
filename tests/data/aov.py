"""Writes aov_mesh.obj (a smooth low-poly sphere, 8 x 5 segments, with vertex normals and texture
coordinates: its shading normals differ from its facets') and renders the references of
tests/tests/aov.rs: aov.exr, aov.xml with Mitsuba 3.9.1's aov integrator (every AOV type caustic
computes, a path integrator nested), 64x48, 4096 spp; aov_depth.exr, the same scene with Mitsuba's
depth integrator, 4096 spp; and aov_normalmap.exr, aov_normalmap.xml (normalmap.xml's scene with
shading normals, albedo and shape indices), 48x36, 1024 spp. The EXR channel names are Mitsuba's
own (the film's bitmap written as it is).
Run: python aov.py (with mitsuba installed; scalar_rgb took 64 s on a shared 2-core machine)."""
import math
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))


def write_mesh(path, segments=8, rings=5, radius=0.35):
    """A UV sphere: rings of vertices between the poles, one triangle per pole cell, two per other."""
    lines = []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))
            lines.append("v %.6f %.6f %.6f" % tuple(radius * c for c in n))
            lines.append("vn %.6f %.6f %.6f" % n)
            lines.append("vt %.6f %.6f" % (j / segments, i / rings))
    index = lambda i, j: i * (segments + 1) + j + 1
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = index(i, j), index(i, j + 1), index(i + 1, j), index(i + 1, j + 1)
            if i > 0:
                lines.append("f %d/%d/%d %d/%d/%d %d/%d/%d" % (a, a, a, c, c, c, b, b, b))
            if i < rings - 1:
                lines.append("f %d/%d/%d %d/%d/%d %d/%d/%d" % (b, b, b, c, c, c, d, d, d))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    write_mesh(os.path.join(here, "aov_mesh.obj"))
    scene = mi.load_file(os.path.join(here, "aov.xml"))
    mi.render(scene, spp=4096, seed=1)
    scene.sensors()[0].film().bitmap().write(os.path.join(here, "aov.exr"))
    depth = mi.load_dict({"type": "depth"})
    mi.render(scene, integrator=depth, spp=4096, seed=1)
    scene.sensors()[0].film().bitmap().write(os.path.join(here, "aov_depth.exr"))
    mapped = mi.load_file(os.path.join(here, "aov_normalmap.xml"))
    mi.render(mapped, spp=1024, seed=1)
    mapped.sensors()[0].film().bitmap().write(os.path.join(here, "aov_normalmap.exr"))
