"""Renders pplastic.exr, the reference of tests/tests/pplastic.rs: pplastic.xml with Mitsuba 3.9.1's
path integrator (scalar_rgb: pplastic's unpolarized code), 48x24, 65536 spp.
Run: python pplastic.py (with mitsuba installed; scalar_rgb takes about 90 seconds on 2 cores)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "pplastic.xml"))
mi.Bitmap(mi.render(scene, spp=65536, seed=1)).write(os.path.join(here, "pplastic.exr"))
