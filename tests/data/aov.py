"""Renders aov.exr and aov_depth.exr, the references of tests/tests/aov.rs: aov.xml with Mitsuba
3.9.1's aov integrator (every AOV type caustic computes, a path integrator nested), 64x48, 4096 spp,
and the same scene with Mitsuba's depth integrator, 4096 spp. The EXR channel names are Mitsuba's own
(the film's bitmap written as it is).
Run: python aov.py (with mitsuba installed; scalar_rgb took 57 s on a shared 2-core machine)."""
import os
import mitsuba as mi

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))

if __name__ == "__main__":
    scene = mi.load_file(os.path.join(here, "aov.xml"))
    mi.render(scene, spp=4096, seed=1)
    scene.sensors()[0].film().bitmap().write(os.path.join(here, "aov.exr"))
    depth = mi.load_dict({"type": "depth"})
    mi.render(scene, integrator=depth, spp=4096, seed=1)
    scene.sensors()[0].film().bitmap().write(os.path.join(here, "aov_depth.exr"))
