"""Renders nested_blend.exr, a reference of tests/tests/blend.rs: nested_blend.xml with Mitsuba
3.9.1's path integrator, 48x24, 65536 spp.
Run: python nested_blend.py (with mitsuba installed; scalar_rgb takes about 90 seconds on 2 cores)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "nested_blend.xml"))
mi.Bitmap(mi.render(scene, spp=65536, seed=1)).write(os.path.join(here, "nested_blend.exr"))
