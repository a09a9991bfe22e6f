"""Renders irradiancemeter_rectangle.exr and irradiancemeter_sphere.exr, the references of
tests/tests/irradiancemeter.rs: irradiancemeter.xml with the meter on a rectangle and on a sphere,
Mitsuba 3.9.1's path integrator, 1 pixel, 2^22 spp as the mean (in f64) of 64 renders of 2^16 spp:
one render of 2^22 spp came out 2-5% too bright (1.209 for 1.184 in red, the mean of three seeds at
2^20), as Mitsuba sums one pixel's samples in f32, whose spacing at 5e6 is 0.5.
Run: python irradiancemeter.py (with mitsuba installed; scalar_rgb takes about ten seconds each)."""
import os
import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
RENDERS, SPP = 64, 1 << 16
for meter in ["rectangle", "sphere"]:
    scene = mi.load_file(os.path.join(here, "irradiancemeter.xml"), meter=meter)
    total = np.zeros((1, 1, 3))
    for seed in range(RENDERS):
        total += np.array(mi.render(scene, spp=SPP, seed=seed + 1), dtype=np.float64)
    mean = (total / RENDERS).astype(np.float32)
    print(meter, mean.ravel())
    mi.Bitmap(mean).write(os.path.join(here, f"irradiancemeter_{meter}.exr"))
