"""Renders the references of tests/tests/thin_null.rs from thin_null.xml with Mitsuba 3.9.1's volpath
integrator (which lets a thin dielectric's transmission, a null lobe, through without counting a
bounce, and attenuates shadow rays by it; its path integrator does neither), 32x24, 16384 spp:
thin_null.exr (max_depth 3), thin_null_depth2.exr (max_depth 2, what caustic's direct renders) and
thin_null_clear.exr (max_depth 3, panes of index 1: no reflection, for light tracing).
Run: python thin_null.py (with mitsuba installed; scalar_rgb takes about 20 s)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
for name, depth, ior in [("thin_null", "3", None), ("thin_null_depth2", "2", None), ("thin_null_clear", "3", "1")]:
    panes = {"pane_ior": ior, "ball_ior": ior} if ior else {}
    scene = mi.load_file(
        os.path.join(here, "thin_null.xml"), integrator="volpath", max_depth=depth, spp="16384", **panes
    )
    mi.Bitmap(mi.render(scene, seed=1)).write(os.path.join(here, f"{name}.exr"))
