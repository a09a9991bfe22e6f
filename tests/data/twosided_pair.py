"""Renders twosided_pair.exr, the reference of tests/tests/twosided_pair.rs: twosided_pair.xml with
Mitsuba 3.9.1's path integrator, 40x40, 16384 spp (its defaults: each side's BSDF as written).
Run: python twosided_pair.py (with mitsuba installed, e.g. /tmp/mi-venv/bin/python; scalar_rgb)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "twosided_pair.xml"))
mi.Bitmap(mi.render(scene, spp=16384, seed=1)).write(os.path.join(here, "twosided_pair.exr"))
