"""Writes the textures of normalmap.xml and renders normalmap.exr, the reference of
tests/tests/normalmap.rs: normalmap.xml with Mitsuba 3.9.1's path integrator, 48x36, 16384 spp;
and normalmap_ptracer.exr, the same with its ptracer (max_depth 4), 8192 spp (a normal map is not
reciprocal, so light tracing renders another image).
The textures: normalmap_normals.png (16x16 RGB, waves of the tangent-space normal along u and v,
(n + 1) / 2 in 8 bits), normalmap_flat.png (1x1, the untilted normal: the negative control) and
normalmap_height.png (16x16 grey, a height of crossed sines).
Run: python normalmap.py (with mitsuba and numpy installed; scalar_rgb takes a few minutes)."""
import os
import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))


def png(name, pixels):
    mi.Bitmap(np.ascontiguousarray(pixels)).write(os.path.join(here, name))


# Waves: the normal leans along u and along v by up to 0.6 (x from sin(2pi u), y from cos(2pi v)).
n = 16
y, x = np.mgrid[0:n, 0:n] + 0.5
normal = np.zeros((n, n, 3))
normal[..., 0] = 0.6 * np.sin(2 * np.pi * x / n)
normal[..., 1] = 0.6 * np.cos(2 * np.pi * y / n)
normal /= np.sqrt(1.0 + (normal ** 2).sum(axis=2))[..., None]
normal[..., 2] = np.sqrt(1.0 - normal[..., 0] ** 2 - normal[..., 1] ** 2)
png("normalmap_normals.png", np.round((normal + 1.0) * 0.5 * 255.0).astype(np.uint8))
png("normalmap_flat.png", np.array([[[128, 128, 255]]], dtype=np.uint8))

height = 0.5 + 0.25 * (np.sin(2 * np.pi * x / n) + np.sin(4 * np.pi * y / n))
png("normalmap_height.png", np.round(height * 255.0).astype(np.uint8)[..., None])

if __name__ == "__main__" and os.environ.get("TEXTURES_ONLY") is None:
    scene = mi.load_file(os.path.join(here, "normalmap.xml"))
    mi.Bitmap(mi.render(scene, spp=16384, seed=1)).write(os.path.join(here, "normalmap.exr"))
    ptracer = mi.load_dict({"type": "ptracer", "max_depth": 4})
    image = mi.render(scene, integrator=ptracer, spp=8192, seed=1)
    mi.Bitmap(image).write(os.path.join(here, "normalmap_ptracer.exr"))
