#!/usr/bin/env python3
"""Writes the geometry of caustic's light-transport scenes (plain Python, no dependencies):

- scenes/meshes/goblet.obj: a goblet lathed from a closed profile (foot, stem, bowl with a wall of
  finite thickness), a watertight solid for `glasses.xml`;
- scenes/meshes/lens.obj: a biconvex lens (two spherical caps meeting at a sharp rim) for
  `lightguide.xml`;
- scenes/meshes/prism.obj: an equilateral triangular prism (apex +y, axis z) for `prism.xml`.

Run from the repository root: python3 scenes/generate_caustic_scenes.py
"""
import math
import os

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


if __name__ == "__main__":
    v, f = lathe(goblet_profile(), 96)
    write_obj(os.path.join(HERE, "meshes", "goblet.obj"), v, f, "goblet: lathed glass solid, 1 unit tall")
    v, f = lens()
    write_obj(os.path.join(HERE, "meshes", "lens.obj"), v, f, "biconvex lens, aperture radius 0.5")
    v, f = prism()
    write_obj(os.path.join(HERE, "meshes", "prism.obj"), v, f, "equilateral prism, side 0.8, height 1")
    print("wrote scenes/meshes/goblet.obj, lens.obj and prism.obj")
