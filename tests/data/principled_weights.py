"""Renders principled_weights.exr, the reference of tests/tests/principled_weights.rs:
principled_weights.xml with Mitsuba 3.9.1's path integrator, 48x24, 32768 spp.
Run: python principled_weights.py (with mitsuba installed; scalar_rgb takes about a minute on 2 cores)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "principled_weights.xml"))
mi.Bitmap(mi.render(scene, spp=32768, seed=1)).write(os.path.join(here, "principled_weights.exr"))
