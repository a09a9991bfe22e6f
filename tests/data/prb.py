"""Renders the reference of tests/tests/integrators.rs's prb test from prb.xml with Mitsuba 3.9.1's
`prb` integrator (an AD integrator: it needs an llvm or cuda variant), 32x24, 65536 spp: prb.exr.
Run: DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 python prb.py (Debian's libllvm19)."""
import os
import mitsuba as mi

mi.set_variant("llvm_ad_rgb")
here = os.path.dirname(os.path.abspath(__file__))
scene = mi.load_file(os.path.join(here, "prb.xml"))
assert "max_depth = 6" in str(scene.integrator()), scene.integrator()
image = mi.render(scene, spp=65536, seed=1)
mi.Bitmap(image).write(os.path.join(here, "prb.exr"))
