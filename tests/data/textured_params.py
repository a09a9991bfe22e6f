"""Writes the bitmaps of textured_params.xml (2x2 checks of eta, k and pplastic's eta, and 1x1 bitmaps
of their means for the negative control) and renders textured_params.exr, the reference of
tests/tests/textured_params.rs, with Mitsuba 3.9.1's scalar_rgb variant, 48x48, 16384 spp.
Run: python textured_params.py (with mitsuba and numpy installed; a few minutes)."""
import os
import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))

# Two values per bitmap, on the diagonals of a 2x2 image.
checks = {
    "eta": ([0.2, 0.45, 1.4], [1.6, 0.9, 0.35]),
    "k": ([3.6, 2.4, 1.8], [1.2, 2.6, 3.4]),
    "ppeta": ([1.1, 1.1, 1.1], [2.8, 2.8, 2.8]),
}
for name, (a, b) in checks.items():
    a, b = np.array(a, dtype=np.float32), np.array(b, dtype=np.float32)
    image = np.array([[a, b], [b, a]], dtype=np.float32)
    mi.Bitmap(image).write(os.path.join(here, f"textured_params_{name}_checks.exr"))
    mean = ((a + b) / 2).reshape(1, 1, 3)
    mi.Bitmap(mean).write(os.path.join(here, f"textured_params_{name}_mean.exr"))

scene = mi.load_file(os.path.join(here, "textured_params.xml"), spp="16384")
mi.Bitmap(mi.render(scene, seed=1)).write(os.path.join(here, "textured_params.exr"))
