"""Writes the textures of emitter_area.xml, emitter_spot.xml and emitter_projector.xml and renders
their references, for tests/tests/textured_emitters.rs: each scene with Mitsuba 3.9.1's path
integrator (max_depth 2), 32x32, 8192 spp; and emitter_directionalarea.xml with its ptracer
(max_depth 3, which alone sees that emitter's light), 32x32, 8192 spp.
The textures: emitter_area_tex.exr (4x4, strong colours up to 6, every texel different),
emitter_area_flat.exr (4x4, its mean everywhere: the negative control), emitter_image.exr (6x4,
colours from 0.05 to 4: the spot's and projector's image) and emitter_flat.exr (2x2, its mean).
Run: python emitters.py (with mitsuba and numpy installed; scalar_rgb takes a few minutes)."""
import os
import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))


def exr(name, pixels):
    mi.Bitmap(np.ascontiguousarray(pixels, dtype=np.float32)).write(os.path.join(here, name))


y, x = np.mgrid[0:4, 0:4]
area = np.stack([0.2 + 1.8 * x, 0.3 + 1.6 * y, 6.0 - 1.2 * (x + y) / 1.5], axis=-1) * 0.6
exr("emitter_area_tex.exr", area)
exr("emitter_area_flat.exr", np.broadcast_to(area.mean(axis=(0, 1)), area.shape))

y, x = np.mgrid[0:4, 0:6]
image = np.stack([0.05 + 0.75 * x, 0.2 + 1.2 * (y % 2) + 0.3 * x, 4.0 - 0.9 * y], axis=-1)
exr("emitter_image.exr", image)
exr("emitter_flat.exr", np.broadcast_to(image.mean(axis=(0, 1)), (2, 2, 3)))

if __name__ == "__main__" and os.environ.get("TEXTURES_ONLY") is None:
    for name in ([] if os.environ.get("DIRECTIONALAREA_ONLY") else ["emitter_area", "emitter_spot", "emitter_projector"]):
        scene = mi.load_file(os.path.join(here, name + ".xml"))
        mi.Bitmap(mi.render(scene, spp=8192, seed=1)).write(os.path.join(here, name + ".exr"))
    scene = mi.load_file(os.path.join(here, "emitter_directionalarea.xml"))
    image = mi.render(scene, spp=8192, seed=1)
    mi.Bitmap(image).write(os.path.join(here, "emitter_directionalarea.exr"))
