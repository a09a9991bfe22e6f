"""Renders principled.exr, the reference of tests/tests/principled.rs: principled.xml with Mitsuba
3.9.1's path integrator, 48x24, 65536 spp.
Run: python principled.py (with mitsuba installed; scalar_rgb takes about two minutes on 2 cores)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "principled.xml"))
mi.Bitmap(mi.render(scene, spp=65536, seed=1)).write(os.path.join(here, "principled.exr"))
