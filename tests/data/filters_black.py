"""Renders the references of tests/tests/filters.rs's black-background test: filters_black.xml with
each filter with negative lobes and the Gaussian as a control (filters_black_lanczos.exr,
filters_black_mitchell.exr, filters_black_catmullrom.exr, filters_black_gaussian.exr), Mitsuba 3.9.1's
scalar_rgb variant, 32x32, 65536 spp: the mean of 64 renders of 1024 spp (seeds 0 to 63), summed in
float64. One render of 65536 spp would not do: scalar_rgb accumulates its film in float32, and a pixel
inside the emitting rectangle (radiance 4, 3, 1.5 everywhere its Lanczos filter reaches, so exactly
that in any weighted mean) came out with green 3.0003 at 4096 spp, 3.0025 at 16384 and 3.0090 at
65536 in one render; at 1024 spp it is 2.9999.
Prints each image's most negative luminance and how many pixels lie below -0.01.
Run: python filters_black.py (with mitsuba and numpy installed; about 20 s a filter)."""
import os
import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
RENDERS, SPP = 64, 1024
for name in ["lanczos", "mitchell", "catmullrom", "gaussian"]:
    scene = mi.load_file(os.path.join(here, "filters_black.xml"), filter=name, spp=str(SPP))
    total = np.zeros((32, 32, 3))
    for seed in range(RENDERS):
        total += np.array(mi.render(scene, seed=seed), dtype=np.float64)
    image = (total / RENDERS).astype(np.float32)
    mi.Bitmap(image).write(os.path.join(here, f"filters_black_{name}.exr"))
    luminance = image.astype(np.float64) @ np.array([0.2126, 0.7152, 0.0722])
    print(f"{name}: min luminance {luminance.min():.4f}, {(luminance < -0.01).sum()} pixels below -0.01")
