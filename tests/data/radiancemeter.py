"""Renders radiancemeter.exr, the reference of tests/tests/radiancemeter.rs: radiancemeter.xml with
Mitsuba 3.9.1's path integrator, 1 pixel, 2^20 spp.
Run: python radiancemeter.py (with mitsuba installed; scalar_rgb takes a few seconds)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "radiancemeter.xml"))
mi.Bitmap(mi.render(scene, spp=1 << 20, seed=1)).write(os.path.join(here, "radiancemeter.exr"))
