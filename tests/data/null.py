"""Renders the reference of tests/tests/null_bsdf.rs from null.xml with Mitsuba 3.9.1's volpath
integrator (its path integrator stops shadow rays at null surfaces: biased, as on masks), 32x24,
16384 spp: null.exr. Run: python null.py (with mitsuba installed; scalar_rgb takes seconds)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "null.xml"), integrator="volpath", spp="16384")
mi.Bitmap(mi.render(scene, seed=1)).write(os.path.join(here, "null.exr"))
