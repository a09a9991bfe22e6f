"""Renders the references of tests/tests/filters.rs: filters.xml with each reconstruction filter that has
negative lobes (filters_mitchell.exr, filters_catmullrom.exr, filters_lanczos.exr), Mitsuba 3.9.1's
scalar_rgb variant, 32x32, 16384 spp.
Run: python filters.py (with mitsuba installed; about 25 s a filter)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
for name in ["mitchell", "catmullrom", "lanczos"]:
    scene = mi.load_file(os.path.join(here, "filters.xml"), filter=name, spp="16384")
    mi.Bitmap(mi.render(scene, seed=1)).write(os.path.join(here, f"filters_{name}.exr"))
