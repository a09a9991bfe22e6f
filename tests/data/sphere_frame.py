"""Renders sphere_frame.exr, the reference of tests/tests/sphere_frame.rs: sphere_frame.xml with
Mitsuba 3.9.1's path integrator, 96x48, 16384 spp.
Run: python sphere_frame.py (with mitsuba installed; scalar_rgb takes about two minutes on 2 cores)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "sphere_frame.xml"))
mi.Bitmap(mi.render(scene, spp=16384, seed=1)).write(os.path.join(here, "sphere_frame.exr"))
