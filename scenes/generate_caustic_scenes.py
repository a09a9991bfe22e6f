#!/usr/bin/env python3
"""Writes the geometry of caustic's light-transport scenes (plain Python, no dependencies):

- scenes/meshes/goblet.obj: a goblet lathed from a closed profile (foot, stem, bowl with a wall of
  finite thickness), a watertight solid for `glasses.xml`;
- scenes/meshes/lens.obj: a biconvex lens (two spherical caps meeting at a sharp rim) for
  `lightguide.xml`;
- scenes/meshes/prism.obj: an equilateral triangular prism (apex +y, axis z) for `prism.xml`;
- scenes/meshes/pool-water.ply: the wavy water surface of `pool.xml` (a height field of a few sines,
  with its exact normals), whose caustic on the pool's floor is seen through the water;
- scenes/meshes/water-glass-*.obj: a glass of water for `water-glass.xml`, as its three interfaces
  (glass and air, glass and water, water and air), each with the medium its normals point into.

Run from the repository root: python3 scenes/generate_caustic_scenes.py
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def lathe(profile, segments):
    """Revolves a closed profile [(r, z), ...] that starts and ends on the axis (r = 0) about +z.
    Returns vertices, faces (0-based triangles) of a watertight surface whose outside is on the
    profile's left when it is walked from its first point to its last (outward for a counter-clockwise
    profile seen with r to the right and z up)."""
    verts = []
    ring_of = []
    for r, z in profile:
        if r == 0.0:
            ring_of.append([len(verts)] * segments)
            verts.append((0.0, 0.0, z))
        else:
            start = len(verts)
            for k in range(segments):
                phi = 2.0 * math.pi * k / segments
                verts.append((r * math.cos(phi), r * math.sin(phi), z))
            ring_of.append([start + k for k in range(segments)])
    faces = []
    for i in range(len(profile) - 1):
        a, b = ring_of[i], ring_of[i + 1]
        for k in range(segments):
            k1 = (k + 1) % segments
            quad = [a[k], a[k1], b[k1], b[k]]
            for tri in ((quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])):
                if len(set(tri)) == 3:
                    faces.append(tri)
    return verts, faces


def write_obj(path, verts, faces, comment):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(f"# {comment}\n# written by scenes/generate_caustic_scenes.py\n")
        for v in verts:
            f.write("v %.6f %.6f %.6f\n" % v)
        for a, b, c in faces:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


def goblet_profile(n_bowl=24):
    """Closed profile of a goblet 1.0 tall: foot, stem, bowl outside, rim, bowl inside."""
    pts = [(0.0, 0.0), (0.32, 0.0), (0.33, 0.015), (0.30, 0.03), (0.06, 0.05), (0.035, 0.08),
           (0.03, 0.30), (0.04, 0.36)]
    # Bowl outside: from the stem's top to the rim, a half-ellipse-like curve.
    wall = 0.012
    outer = []
    for i in range(1, n_bowl + 1):
        t = i / n_bowl
        angle = -0.5 * math.pi + t * 0.5 * math.pi * 1.08
        r = 0.30 * math.cos(angle) + 0.02
        z = 0.62 + 0.30 * math.sin(angle) + 0.08 * t
        outer.append((max(r, 0.045), z))
    pts += outer
    rim_r, rim_z = outer[-1]
    # Rounded rim, then the inside going back down, offset inwards by the wall's thickness.
    pts.append((rim_r - wall * 0.5, rim_z + wall * 0.4))
    inner = [(max(r - wall, 0.0), z + wall * 0.2) for r, z in reversed(outer)]
    inner = [(r, z) for r, z in inner if r > 0.03]
    pts += inner
    pts.append((0.0, inner[-1][1] - 0.01))
    return pts


def lens(radius=0.5, thickness=0.22, rings=24, segments=96):
    """A symmetric biconvex lens of aperture `radius` along +z, centred at the origin."""
    half = thickness / 2.0
    # Sphere radius R of a cap of height `half` over a disk of `radius`: R = (radius² + half²) / (2·half).
    big_r = (radius * radius + half * half) / (2.0 * half)
    profile = [(0.0, -half)]
    for i in range(1, rings + 1):
        r = radius * i / rings
        profile.append((r, -half + (big_r - math.sqrt(big_r * big_r - r * r))))
    for i in range(rings - 1, 0, -1):
        r = radius * i / rings
        profile.append((r, half - (big_r - math.sqrt(big_r * big_r - r * r))))
    profile.append((0.0, half))
    return lathe(profile, segments)


def prism(side=0.8, height=1.0):
    """A closed equilateral prism: the triangle (side `side`, centroid at the origin, apex towards +y)
    extruded from z = -height/2 to +height/2, faces wound outwards."""
    h = side * math.sqrt(3.0) / 2.0
    tri = [(-side / 2.0, -h / 3.0), (side / 2.0, -h / 3.0), (0.0, 2.0 * h / 3.0)]  # counter-clockwise
    verts = [(x, y, -height / 2.0) for x, y in tri] + [(x, y, height / 2.0) for x, y in tri]
    faces = [(0, 2, 1), (3, 4, 5)]  # bottom (facing -z), top (facing +z)
    for i in range(3):
        j = (i + 1) % 3
        faces += [(i, j, j + 3), (i, j + 3, i + 3)]
    return verts, faces


def write_obj_normals(path, verts, normals, faces, comment):
    """As `write_obj`, with one normal per vertex (smooth shading)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(f"# {comment}\n# written by scenes/generate_caustic_scenes.py\n")
        for v in verts:
            f.write("v %.5f %.5f %.5f\n" % v)
        for n in normals:
            f.write("vn %.5f %.5f %.5f\n" % n)
        for a, b, c in faces:
            f.write(f"f {a + 1}//{a + 1} {b + 1}//{b + 1} {c + 1}//{c + 1}\n")


def write_ply_normals(path, verts, normals, faces):
    """Binary little-endian PLY with per-vertex normals (the pool's 65k triangles in 1.6 MB, where OBJ
    text takes 4.3 MB)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    header = ("ply\nformat binary_little_endian 1.0\ncomment written by scenes/generate_caustic_scenes.py\n"
              f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        for v, n in zip(verts, normals):
            f.write(struct.pack("<6f", *v, *n))
        for a, b, c in faces:
            f.write(struct.pack("<B3i", 3, a, b, c))


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def pool_water(size=2.0, level=0.45, n=180):
    """The water's surface over [-size/2, size/2]²: a height field of four sines (amplitudes 1.5-3 mm,
    wavelengths 13-20 cm on a 2 m pool), normals +z (into the air above), exact from its gradient.
    Its curvature, about a·k² ≈ 5 per metre, focuses the sun's light near the floor 0.45 below, so
    the caustic is a sharp web (a lens of curvature κ between air and water focuses at 1/(κ(1 - 1/n)))."""
    waves = [(0.003, 30.0, 10.0, 0.3), (0.0025, -12.0, 34.0, 1.1), (0.002, 38.0, -22.0, 2.0), (0.0015, 20.0, 41.0, 0.7)]
    verts, normals, faces = [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x = size * (i / n - 0.5)
            y = size * (j / n - 0.5)
            z, dzdx, dzdy = level, 0.0, 0.0
            for a, kx, ky, phase in waves:
                z += a * math.sin(kx * x + ky * y + phase)
                dzdx += a * kx * math.cos(kx * x + ky * y + phase)
                dzdy += a * ky * math.cos(kx * x + ky * y + phase)
            verts.append((x, y, z))
            normals.append(normalize((-dzdx, -dzdy, 1.0)))
    for j in range(n):
        for i in range(n):
            a, b = j * (n + 1) + i, j * (n + 1) + i + 1
            c, d = a + n + 1, b + n + 1
            faces += [(a, b, d), (a, d, c)]  # counter-clockwise seen from +z: normals up
    return verts, normals, faces


def lathe_smooth(polylines, segments):
    """Revolves polylines [(r, z), ...] about +z, each a smooth surface of its own (a sharp corner is
    where one polyline ends and the next begins, at the same point). Each face's normal points to the
    right of the polyline walked from its first point to its last, seen with r to the right and z up;
    vertex normals are the polyline's own, averaged over its two segments at inner points."""
    verts, normals, faces = [], [], []
    for line in polylines:
        seg_n = []
        for (r0, z0), (r1, z1) in zip(line, line[1:]):
            dr, dz = r1 - r0, z1 - z0
            length = math.hypot(dr, dz)
            seg_n.append((dz / length, -dr / length))  # right of the walking direction
        rings = []
        for i, (r, z) in enumerate(line):
            adj = [seg_n[k] for k in (i - 1, i) if 0 <= k < len(seg_n)]
            nr, nz = sum(a for a, _ in adj), sum(b for _, b in adj)
            length = math.hypot(nr, nz)
            nr, nz = nr / length, nz / length
            if r == 0.0:
                rings.append([len(verts)] * segments)
                verts.append((0.0, 0.0, z))
                normals.append((0.0, 0.0, 1.0 if nz > 0 else -1.0))
                continue
            start = len(verts)
            for k in range(segments):
                phi = 2.0 * math.pi * k / segments
                c, s_ = math.cos(phi), math.sin(phi)
                verts.append((r * c, r * s_, z))
                normals.append((nr * c, nr * s_, nz))
            rings.append([start + k for k in range(segments)])
        for i in range(len(line) - 1):
            a, b = rings[i], rings[i + 1]
            nr, nz = seg_n[i]
            for k in range(segments):
                k1 = (k + 1) % segments
                for tri in ((a[k], a[k1], b[k1]), (a[k], b[k1], b[k])):
                    if len(set(tri)) < 3:
                        continue
                    p0, p1, p2 = (verts[t] for t in tri)
                    face_n = cross(sub(p1, p0), sub(p2, p0))
                    centre = ((p0[0] + p1[0] + p2[0]) / 3.0, (p0[1] + p1[1] + p2[1]) / 3.0)
                    phi = math.atan2(centre[1], centre[0])
                    want = (nr * math.cos(phi), nr * math.sin(phi), nz)
                    faces.append(tri if dot(face_n, want) > 0.0 else (tri[0], tri[2], tri[1]))
    return verts, normals, faces


def water_glass(radius=0.3, height=0.85, wall=0.02, bottom=0.06, level=0.58):
    """A tumbler of glass (outer `radius`, `wall` thick, a `bottom` of glass) filled with water up to
    `level`, as its three interfaces. Each is one mesh whose normals point into the medium named
    second: glass|air (outside, rim, inside above the water), glass|water, water|air (the surface)."""
    inner = radius - wall
    glass_air = [
        [(0.0, 0.0), (radius - 0.01, 0.0)],
        [(radius - 0.01, 0.0), (radius, 0.01)],
        [(radius, 0.01), (radius, height)],
        [(radius, height), (radius - wall / 2.0, height + wall / 2.0), (inner, height)],
        [(inner, height), (inner, level)],
    ]
    glass_water = [[(inner, level), (inner, bottom + 0.01)], [(inner, bottom + 0.01), (inner - 0.01, bottom)],
                   [(inner - 0.01, bottom), (0.0, bottom)]]
    water_air = [[(inner, level), (0.0, level)]]
    return [lathe_smooth(p, 192) for p in (glass_air, glass_water, water_air)]


if __name__ == "__main__":
    v, f = lathe(goblet_profile(), 96)
    write_obj(os.path.join(HERE, "meshes", "goblet.obj"), v, f, "goblet: lathed glass solid, 1 unit tall")
    v, f = lens()
    write_obj(os.path.join(HERE, "meshes", "lens.obj"), v, f, "biconvex lens, aperture radius 0.5")
    v, f = prism()
    write_obj(os.path.join(HERE, "meshes", "prism.obj"), v, f, "equilateral prism, side 0.8, height 1")
    v, n, f = pool_water()
    write_ply_normals(os.path.join(HERE, "meshes", "pool-water.ply"), v, n, f)
    for name, (v, n, f) in zip(("glass-air", "glass-water", "water-air"), water_glass()):
        write_obj_normals(os.path.join(HERE, "meshes", f"water-glass-{name}.obj"), v, n, f,
                          f"glass of water, the {name} interface: normals into the {name.split('-')[1]}")
    print("wrote scenes/meshes/goblet.obj, lens.obj, prism.obj, pool-water.ply and water-glass-*.obj")
