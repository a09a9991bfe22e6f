"""Renders mask_cards.exr, the reference of tests/tests/mask.rs: mask_cards.xml with Mitsuba 3.9.1's
volpath integrator (its path integrator is biased on masks: see kernel/src/mask.rs), 32x32, 16384 spp.
Run: python mask_cards.py (with mitsuba installed; scalar_rgb takes about half a minute)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "mask_cards.xml"), integrator="volpath", spp="16384")
mi.Bitmap(mi.render(scene, seed=1)).write(os.path.join(here, "mask_cards.exr"))
