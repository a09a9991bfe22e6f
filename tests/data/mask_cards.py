"""Renders the references of tests/tests/mask.rs from mask_cards.xml with Mitsuba 3.9.1's volpath
integrator (its path and direct integrators are biased on masks: see kernel/src/mask.rs), 32x32,
16384 spp: mask_cards.exr (max_depth 4) and mask_cards_direct.exr (max_depth 2, the estimand of
`direct`). Run: python mask_cards.py (with mitsuba installed; scalar_rgb takes about a minute)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))
for max_depth, name in [("4", "mask_cards.exr"), ("2", "mask_cards_direct.exr")]:
    scene = mi.load_file(
        os.path.join(here, "mask_cards.xml"), integrator="volpath", spp="16384", max_depth=max_depth
    )
    mi.Bitmap(mi.render(scene, seed=1)).write(os.path.join(here, name))
