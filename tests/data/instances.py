"""Renders instances.exr, the reference of tests/tests/instances.rs: instances.xml with Mitsuba
3.9.1's path integrator, 32x32, 16384 spp.
Run: python instances.py (with mitsuba installed; scalar_rgb takes about half a minute)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "instances.xml"))
mi.Bitmap(mi.render(scene, spp=16384, seed=1)).write(os.path.join(here, "instances.exr"))
