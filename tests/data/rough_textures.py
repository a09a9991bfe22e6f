"""Renders rough_textures.exr, the reference of tests/tests/rough_textures.rs: rough_textures.xml with
Mitsuba 3.9.1's scalar_rgb variant, 32x32, 16384 spp.
Run: python rough_textures.py (with mitsuba installed; about a minute)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "rough_textures.xml"), spp="16384")
mi.Bitmap(mi.render(scene, seed=1)).write(os.path.join(here, "rough_textures.exr"))
