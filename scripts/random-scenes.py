#!/usr/bin/env python3
"""Differential test against Mitsuba 3: random small scenes rendered by both, compared statistically.

Each integer seed deterministically makes one small Mitsuba 3 scene out of plugins and parameters
that docs/mitsuba.md's plugin table marks supported or partial, keeping clear of the divergences it
documents (no textured `alpha` on `roughplastic` (Mitsuba refuses it), no dispersion, no blend of a
Dirac lobe and a smooth one, no thin dielectric inside a blend (no null interface there), no
`twosided` on interpolated normals; `direct` with one emitter and one BSDF sample; null interfaces
compared with Mitsuba's `volpath`, below): a `perspective`, `thinlens` or `orthographic`
camera looking at the origin (random fov and fov_axis, or a focal length, or Mitsuba's default
lens), a 32x24 or 24x32 film with a box, tent or gaussian filter, the `path` (random max_depth,
rr_depth, hide_emitters) or `direct` integrator, a floor and 2-4 shapes (sphere, rectangle, disk,
cube, cylinder; random translate/rotate/scale) with random BSDFs (diffuse, twosided diffuse,
plastic, roughplastic, conductor, roughconductor with named or explicit IORs, dielectric,
roughdielectric, thindielectric; some reflectances a `checkerboard`), lit by one light placed to
light the floor plus up to two more (an area lamp, a shape of the scene made emissive, point, spot,
directional, constant).

Null interfaces: caustic renders `mask`, `null` and a thin dielectric's transmission as Mitsuba's
`volpath` does under every integrator (a crossing is no bounce; shadow rays, and light tracing's
camera connections, are attenuated through them), where Mitsuba's `path` counts a crossing as a
bounce and stops shadow rays there, and its `direct` stops camera rays at masks. So a scene that
holds any of them (the original generator's thindielectric included) is rendered by Mitsuba from a
copy whose integrator is `volpath`: for `path` and `ptracer` at the same max_depth, rr_depth and
hide_emitters, for `direct` at max_depth 2 (its estimand; tests/tests/mask.rs and thin_null.rs);
`volpath` renders scenes without media as `path` does. The scene line then ends `ref=volpath`.

The extended generator (the default; --no-extended gives the scenes above, draw for draw, so that
old seeds reproduce) adds, each with some probability and each left out by naming it in
--without (--help lists them): `principled` (weights left out, numbers or checkerboards;
`eta` or `specular`), `principledthin` on rectangles and disks, `pplastic`, `blendbsdf` of two
smooth one-sided BSDFs (weight a number, a checkerboard or a bitmap; blends inside, two levels
deep), spheres turned by their `to_world`, `normalmap` and `bumpmap`
(tests/data's normalmap_normals.png and normalmap_height.png) around a BSDF on shapes with uv,
`bitmap` reflectances (8- and 16-bit PNGs, a BMP; filter_type, wrap_mode, raw, to_uv),
checkerboards with unequal, turned and shifted to_uv, `obj` and `ply` meshes (their own or face
normals; uniform or unequal scales), `instance`s of one `shapegroup` (spheres under uniform
scales only; no null interface on its cylinders), area emitters whose radiance is a checkerboard of
greys or an HDR bitmap, a spot with a `texture`, `projector` (irradiance a colour, a bitmap or a checkerboard), `envmap` (two tiny EXRs
of tests/data and the shared museum.exr; `mis_compensation` except under ptracer), perspective
`principal_point_offset_x/y`, the mitchell, catmullrom and lanczos filters, the multijitter,
orthogonal and ldsampler samplers, the `ptracer` integrator (perspective and thinlens cameras);
anisotropic roughness (alpha_u and alpha_v apart, one small and one large, either sometimes a
checkerboard, oriented along dp/du on every shape) on `roughconductor`, `roughdielectric` and
`pplastic` (also inside blends), `anisotropic` among principled's and principledthin's weights
(`roughplastic` stays isotropic: Mitsuba's has no alpha_u/alpha_v); `mask` around an object's BSDF
(its normal or bump map, blend, twosided or thindielectric included; never a mask in a mask nor in
a blend, nor under a map), opacity a number, a checkerboard of two or a bitmap (its luminance); `null` on objects
(invisible but for what they do to paths' depth), on emissive objects and on area lamps (emission
seen, light passing through); and `thindielectric` mostly with a tinted specular_transmittance (an
RGB, sometimes a checkerboard or bitmap), drawn more often on rectangles and disks (panes), never
on the floor nor under a normal or bump map (--without thindielectric leaves thin dielectrics out of the extended scenes entirely,
the original generator's too). Under `ptracer` there are no masks and no `null`, and thin
dielectrics only in half the scenes (with feature "thindielectric"), there with int_ior = ext_ior
(no reflection: light tracing cannot connect a Dirac reflection to the camera); Mitsuba's `ptracer`
counts the crossing as a bounce and stops camera connections at the pane, so these are compared
with its `volpath`, and hold nothing that a light tracer renders unlike a path tracer: no normal
or bump map and no principledthin (Mitsuba's light tracer renders them unlike its path tracer, and
caustic's like its), no conductor, dielectric or plastic (no light tracer renders what the camera
sees in a Dirac reflection: seed 100's smooth silver mesh left caustic's ptracer 2.7% darker than
volpath and caustic's path, which agree).

Further kinds of the extended generator (each drawn only where its kind is on, so that --without
naming all of them gives the scenes that came before them, draw for draw): colours written as
Mitsuba's other colour forms (a `<float>` or `<spectrum value>` grey, a `λ:value` list, the `srgb`,
`uniform`, `d65` and `rawconstant` plugins) and conductors' `eta`/`k` as `.spd` files of the shared
scenes' ior folder; textured `specular_transmittance` on `dielectric` and `roughdielectric`, a
textured isotropic `alpha` (not on `roughplastic`), the dielectrics' `specular_reflectance`,
conductors' `eta` or `k` a checkerboard of numbers, more of Mitsuba's named conductors (`none`
among them) and IORs, the plastics' `ext_ior` and `pplastic`'s `eta` (a number or a checkerboard);
`twosided` around other one-sided BSDFs and `twosided` of two (never in a mask or under a map, as
caustic refuses); `flip_normals` on objects, a `to_world` written as one `matrix`, OBJ
`flip_tex_coords`; more mesh files (the binary `bunny.ply`, `matpreview.serialized` by `shape_index`,
`rectangle.obj`, `uv_sphere.obj`, and `mesh_attribute.ply`, whose diffuse or principled colour
may be one of its `mesh_attribute`s: Mitsuba's plastics refuse one, wanting its mean); objects gathered in a `merge`; bitmaps' `format` (`uint8` on 8-bit files only:
Mitsuba dithers where it rounds) and `accel`; `directionalarea` lamps (only a light tracer renders
their light: the key light under ptracer, an extra one, black, elsewhere; not under ibpt, which
refuses them); the projector's `focal_length`; cameras' `near_clip` and `far_clip` (no far clip
under ptracer: Mitsuba 3.9.1's light tracer renders an environment behind it black, its path tracer
does not; nor a near clip cutting an object: its light tracer's connections still stop there) and a crop window; a `radiancemeter` or an `irradiancemeter` (in the floor or an object; a 1x1 film, box
filter; not under light tracing, which caustic refuses for them); `direct`'s `shading_samples` or
`emitter_samples`/`bsdf_samples` (more than one emitter sample only without delta lights: Mitsuba
3.9.1's `direct` gives a delta light's samples weight 1 each, not 1/emitter_samples); caustic's
`ibpt` (perspective and thinlens cameras, nothing non-reciprocal: no normal or bump map, no
principledthin) and the `prb` family (absent `max_depth`: 6), both compared with Mitsuba's `path`
(its `volpath` with null interfaces; its scalar variants have no `prb`);
`moment` around `path` or `direct` (the first three channels of Mitsuba's image are the image); and
the `depth` integrator. Left out: caustic's own BSDFs (`phong`, `fuzzymetal`) and dispersion (no
Mitsuba counterpart), the `regular`, `irregular` and `blackbody` spectrum plugins (Mitsuba's rgb
variants refuse to render them), `aov` (its channels beyond the image need a comparison of their
own: tests/tests/aov.rs), `samples_per_pass` (no change to the image), and ply in big-endian
binary (no such file here).

Files are named by absolute path: tests/data and scenes/meshes of this repository, and the shared
Mitsuba scenes in $CAUSTIC_SHARED (default ../shared), whose files are left out where missing.
Kept clear of too, faults of Mitsuba 3.9.1 (its renderers disagreeing with each other, or
failing): its `path` with hide_emitters dies (segmentation fault) where a camera ray meets an
`instance`; with hide_emitters, what a camera ray meets past an area emitter it skips renders
differently in each of its integrators: `path` completes the surface that a ray spawned past the
emitters found with the camera ray (its distance measured from the last emitter, not the camera),
`volpath` does so with the ray spawned past the first emitter, which is wrong where the camera ray
passed more than one (a cylinder's two walls: a rough conductor disk seen through an emitting null
cylinder renders 0.1844 where its image without hide_emitters less the emitters' directly seen
emission is 0.1734, and caustic's 0.1736), and `ptracer` stops camera connections at the emitter; so under hide_emitters the extended generator makes no shape of the scene emissive (area
lamps above it stay); its `ptracer` never ends where the sampler rounds the sample count (stratified at 512
spp: 529), refuses a checkerboard on an emitter (Texture::sample_spectrum(): not implemented),
lights wrongly from a turned `envmap`, leaves black a band of the image along the edges that a
perspective `principal_point_offset` moves (its importance() tests the unshifted image rectangle,
while its sample_direction() shifts the pixel: seed 28 of the extended generator, offset
-0.104/-0.162, rendered 23% darker than its `path`), and with any filter but the box loses the part of a splat's
filter that falls off the image (its border pixels render darker than its path tracer's; caustic's
renormalises the filter there): so ptracer gets the independent sampler, the box filter, bitmap
emitter textures, unturned environment maps and no principal point offset; and it samples a textured area emitter in uv
space, which takes a one-to-one uv map (a cube's six faces share one, and only one is sampled), and
maps uv to a point of a cylinder or sphere by a ray cast from the world-space point along the
object-space radial direction (eval_parameterization), which meets another point of the shape where
it is turned (a checkerboard of two equal greys on a turned cylinder lit the floor 38% brighter than
the same plain colour; on a sphere turned 150 degrees, 6%), so cubes, meshes without uv, cylinders
(always turned here) and turned spheres emit a plain colour. And its `normalmap` and `bumpmap` do not pass
on eval_null_transmission (the BSDF base class's 0), so its `volpath` stops shadow rays at a
mapped thin dielectric (or mask) while its sampled paths cross it (a bump-mapped pane's shadow
renders 0.004 where the plain pane's is 0.225, as caustic renders both): no thin dielectric under a
map. And its `volpath`, which does not bound the number of null crossings, can cross a null
cylinder in an instance for ever (each crossing meets the cylinder again: seed 88 hung in
Cylinder::ray_intersect_preliminary under VolumetricPathIntegrator::sample, its instance scaled
unequally and, drawn again, uniformly): no null interface on a cylinder in a shapegroup.

Mitsuba 3.9.1 (`scalar_rgb`) renders the reference at `--spp` x `--ref-factor` samples per pixel,
in --ref-batches renders with seeds 1, 2, ... whose spread gives the reference's own variance;
caustic renders the scene on the CPU at `--spp` with `--strict` and `--variance`. `caustic compare`
then z-tests every pixel and z-scores the mean luminance, against the sum of caustic's variance and
the reference's (the larger of the batches' estimate and caustic's scaled by the spp ratio, which
is what compare's --image-spp/--reference-spp assume; the batches' estimate also grows where the
reference met a rare bright path that caustic's samples did not). With --ref-batches 1 Mitsuba
renders once (`mi.render(scene, spp=N, seed=1)`) and compare is given the two spp instead.

A scene passes when at least 99% of its pixels pass and |z| < 4. One line per scene: seed, pass
fraction, luminance z, verdict, seconds, and what the scene holds (camera, film, filter, sampler |
integrator | floor | each shape:BSDF | lights). Verdicts: `ok`; `FAIL`; `noisy`, a failure that
passed when both renderers rendered it again at --recheck times the samples with other seeds
(heavy-tailed noise such as caustics through glass, most likely; a bias does not go away);
`ERROR`, a scene a renderer refused or a render that failed (the message follows). A summary ends
the run. Every scene that did not pass (and every scene with --keep) is left in --out:
seed-NNNN.xml (and seed-NNNN-reference.xml, the copy Mitsuba rendered, where it renders volpath),
Mitsuba's reference and its variance (seed-NNNN-mitsuba.exr, -mitsuba.variance.exr),
caustic's image and variance (-caustic.exr, -caustic.variance.exr), the pair that was compared
(-test.exr, -test.variance.exr: caustic's image with the summed variance) and compare's |z| map
(-error.png); the recheck's files are named seed-NNNN-recheck-*.

Run with a Python that has mitsuba==3.9.1 and numpy, from the repository root after
`cargo build --release`:
    python scripts/random-scenes.py --seeds 0-29
    python scripts/random-scenes.py --seeds 3,7 --spp 1024 --keep --caustic path/to/caustic
    python scripts/random-scenes.py --seeds 0-99 --no-extended       # the original generator
    python scripts/random-scenes.py --seeds 0-59 --without ptracer,envmap
    python scripts/random-scenes.py --seeds 0-59 --without mask,null,thindielectric  # path as is
    python scripts/random-scenes.py --seeds 0-99 --backend gpu      # the SPIR-V kernel (lavapipe here)
To look at a failure again by hand, in --out:
    caustic render seed-0007.xml --backend cpu --spp 256 \\
        --strict --variance -o c.exr
    caustic compare seed-0007-test.exr seed-0007-mitsuba.exr --error-image err.png
Both renderers are limited to --threads threads (default 2) and run one after the other (Mitsuba
3.9.1 deadlocks reading or writing an EXR while its thread pool has one thread: with --threads 1 it
gets two but while it renders).
"""
import argparse
import collections
import functools
import math
import os
import random
import re
import subprocess
import sys
import time

import drjit as dr
import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
# Mitsuba's cylinder warns of shearing at 1e-6, which the rounding of a rotated to_world exceeds.
mi.set_log_level(mi.LogLevel.Error)
# Nor are its progress bars (ptracer draws them on stdout); its errors come as exceptions.
mi.logger().clear_appenders()

# Pass criteria (those of the repository's Mitsuba conformance tests).
MIN_PASS_FRACTION = 0.99
MAX_LUMINANCE_Z = 4.0

NAMED_CONDUCTORS = ["Au", "Cu", "Al", "Ag", "Cr"]
NAMED_IORS = ["bk7", "water", "diamond", "polypropylene", "acrylic glass", "pyrex"]

# The extended generator's kinds of scene element, each on unless --without names it; --no-extended
# leaves out all of them, and the scenes are the original generator's, draw for draw.
EXTENDED = {
    "principled": "principled, each weight left out, a number or a checkerboard; eta or specular",
    "principledthin": "principledthin on rectangles and disks (the floor included)",
    "pplastic": "pplastic (anisotropic only with the kind anisotropic)",
    "blendbsdf": "blendbsdf of two smooth one-sided BSDFs, weight a number, checkerboard or bitmap",
    "nested-blends": "blendbsdfs inside blendbsdfs, two levels deep",
    "sphere-frames": "spheres turned by their to_world (their uv turns with it)",
    "normalmap": "normalmap (normalmap_normals.png) around a BSDF on a shape with uv",
    "bumpmap": "bumpmap (normalmap_height.png, bilinear) around a BSDF on a shape with uv",
    "bitmap": "bitmap reflectances (PNG, BMP): filter_type, wrap_mode, raw, to_uv",
    "uv": "checkerboards' to_uv with unequal scales, a turn and an offset",
    "meshes": "obj and ply meshes, their own or face normals",
    "instances": "instances of a shapegroup (spheres under uniform scales only)",
    "emitter-textures": "area emitters' radiance a checkerboard or an HDR bitmap, a spot's texture",
    "projector": "projector, irradiance a colour, an HDR bitmap or a checkerboard",
    "envmap": "envmap of a small EXR or museum.exr, sometimes mis_compensation",
    "principal-point": "principal_point_offset_x/y on perspective cameras",
    "filters": "mitchell, catmullrom and lanczos filters",
    "samplers": "multijitter, orthogonal and ldsampler samplers",
    "ptracer": "the ptracer integrator (perspective and thinlens cameras)",
    "anisotropic": "alpha_u != alpha_v (numbers, checkerboards): roughconductor, roughdielectric, "
                   "pplastic; principled(thin)'s anisotropic",
    "mask": "mask around an object's BSDF, opacity a number, checkerboard or bitmap (not under ptracer)",
    "null": "null BSDF on objects, emissive objects and area lamps (not under ptracer)",
    "thindielectric": "thindielectric, mostly tinted, more often on rectangles and disks; ptracer: int_ior = "
                      "ext_ior (--without: none at all)",
    "spectra": "colours as <float>, <spectrum> greys and lists, srgb/uniform/d65/rawconstant; conductors' "
               ".spd files",
    "material-params": "textured specular_transmittance and isotropic alpha, dielectrics' specular_reflectance, "
                       "textured conductor eta/k, more named conductors and IORs, plastics' ext_ior, pplastic's eta",
    "twosided-pairs": "twosided around other one-sided BSDFs, and twosided of two (front, back)",
    "shape-options": "flip_normals on objects, to_world as one matrix, OBJ flip_tex_coords",
    "mesh-files": "bunny.ply (binary), matpreview.serialized (shape_index), rectangle.obj, uv_sphere.obj, "
                  "mesh_attribute.ply and its mesh_attribute textures",
    "merge": "objects inside a merge",
    "bitmap-format": "bitmaps' format and accel",
    "directionalarea": "directionalarea lamps (the key light under ptracer; not under ibpt)",
    "projector-focal": "the projector's focal_length",
    "clip-crop": "cameras' near_clip and far_clip, and a crop window",
    "meters": "radiancemeter and irradiancemeter (1x1 film; not under ptracer or ibpt)",
    "direct-samples": "direct's shading_samples or emitter_samples/bsdf_samples",
    "ibpt": "caustic's ibpt, compared with Mitsuba's path (volpath with null interfaces)",
    "prb": "prb, prb_basic and prb_projective, compared with Mitsuba's path",
    "moment": "moment around path or direct",
    "depth": "the depth integrator",
}

# Files the extended generator uses, by absolute path (the saved scenes render from anywhere): the
# repository's test data and, where present, the shared Mitsuba scenes.
REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.environ.get("CAUSTIC_SHARED", os.path.join(os.path.dirname(REPOSITORY), "shared"))


def test_data(name):
    return os.path.join(REPOSITORY, "tests", "data", name)


def shared_scene_file(name):
    return os.path.join(SHARED, "scenes", "mitsuba", "common", name)


REFLECTANCE_IMAGES = [path for path in [  # 8- and 16-bit PNGs, grey and RGB; a BMP
    test_data("normalmap_height.png"), test_data("normalmap_normals.png"), test_data("bitmap_format_8.png"),
    test_data("bitmap_format_16.png"), shared_scene_file("textures/flower.bmp")] if os.path.exists(path)]
EMISSION_IMAGES = [test_data("emitter_area_tex.exr"), test_data("emitter_image.exr")]  # 4x4, 6x4; up to 4
ENVIRONMENT_IMAGES = EMISSION_IMAGES + [path for path in [shared_scene_file("textures/museum.exr")]
                                        if os.path.exists(path)]
NORMAL_MAP = test_data("normalmap_normals.png")  # 16x16 waves of the tangent-space normal
HEIGHT_MAP = test_data("normalmap_height.png")  # 16x16 grey crossed sines
# 8-bit files, which `format` uint8 keeps as they are (Mitsuba dithers what it rounds, caustic does not).
EIGHT_BIT_IMAGES = {test_data("normalmap_height.png"), test_data("normalmap_normals.png"),
                    test_data("bitmap_format_8.png"), shared_scene_file("textures/flower.bmp")}
# A mesh file: plugin, file, the centre and radius of a sphere that holds it, whether it has uv,
# whether it is flat (its interpolated normals are the faces'), its shape_index (serialized files).
MeshFile = collections.namedtuple("MeshFile", "plugin path centre radius uv flat shape_index",
                                  defaults=(False, None))
MESHES = [mesh for mesh in [
    MeshFile("obj", test_data("aov_mesh.obj"), (0, 0, 0), 0.35, True),  # a 64-face sphere with normals and uv
    MeshFile("obj", os.path.join(REPOSITORY, "scenes", "meshes", "prism.obj"), (0, 0, 0), 0.69, False),
    MeshFile("ply", shared_scene_file("meshes/sphere.ply"), (0, 0, 0), 128.0, False),
    MeshFile("ply", shared_scene_file("meshes/teapot.ply"), (0.21, 0, 1.58), 4.1, False),
    MeshFile("obj", shared_scene_file("meshes/cbox/smallbox.obj"), (186, 82.5, 168.5), 169.0, False),
] if os.path.exists(mesh.path)]
# A 4x4 grid of 18 triangles on [-1, 1]² with a vertex colour (r g b) and face attributes wear_x (one
# channel) and tint_r/g/b: face_wear, face_tint_color (mesh_attribute.py).
ATTRIBUTE_MESH = test_data("mesh_attribute.ply")
ATTRIBUTES = [("vertex_color", 3), ("face_tint_color", 3), ("face_wear", 1)]
# Feature "mesh-files": a binary (little-endian) PLY, the three meshes of a serialized file, more OBJs.
MATPREVIEW = shared_scene_file("meshes/matpreview.serialized")
MORE_MESHES = [mesh for mesh in [
    MeshFile("ply", shared_scene_file("meshes/bunny.ply"), (-0.0168, 0.1102, -0.0015), 0.105, False),
    MeshFile("serialized", MATPREVIEW, (0.0645, -0.1886, 0.6482), 1.414, True, shape_index=0),  # the backdrop
    MeshFile("serialized", MATPREVIEW, (0, 0, 0.8279), 1.265, True, shape_index=1),
    MeshFile("serialized", MATPREVIEW, (-0.1085, 0, -0.0817), 1.715, True, shape_index=2),
    MeshFile("obj", shared_scene_file("meshes/rectangle.obj"), (0, 0, 0), 1.415, True, flat=True),
    MeshFile("obj", test_data("uv_sphere.obj"), (0, 0, 0), 1.0, True),
    MeshFile("ply", ATTRIBUTE_MESH, (0, 0, 0), 1.415, False, flat=True),
] if os.path.exists(mesh.path)]
# Feature "material-params": more of Mitsuba's named conductors and IORs (all above 1.3: none is the
# exterior's air).
MORE_CONDUCTORS = ["none", "W", "Cu_palik", "Ni_palik", "TiN", "Hg", "a-C", "Mo", "Rh", "Cu2O"]
MORE_IORS = ["acetone", "ethanol", "carbon tetrachloride", "glycerol", "benzene", "silicone oil", "bromine",
             "water ice", "fused quartz", "sodium chloride", "amber", "pet"]
# Feature "spectra": conductors whose eta and k the shared scenes' ior folder holds as .spd files.
IOR_FOLDER = os.path.join(SHARED, "scenes", "mitsuba", "ior")
SPD_CONDUCTORS = [name for name in ["Au", "Cu", "Al", "Ag", "Cr", "W"]
                  if all(os.path.exists(os.path.join(IOR_FOLDER, f"{name}.{part}.spd")) for part in ["eta", "k"])]


# --- XML helpers ---------------------------------------------------------------------------------

def num(x):
    return f"{x:.4g}"


def vec(v):
    return ", ".join(num(c) for c in v)


def rgb(name, value):
    return f'<rgb name="{name}" value="{vec(value)}"/>'


def flt(name, value):
    return f'<float name="{name}" value="{num(value)}"/>'


def integer(name, value):
    return f'<integer name="{name}" value="{value}"/>'


def string(name, value):
    return f'<string name="{name}" value="{value}"/>'


def boolean(name, value):
    return f'<boolean name="{name}" value="{str(value).lower()}"/>'


def point(name, value):
    return f'<point name="{name}" value="{vec(value)}"/>'


def element(tag, kind, children, name=None):
    named = f' name="{name}"' if name else ""
    body = "".join(children)
    return f'<{tag} type="{kind}"{named}>{body}</{tag}>'


def to_world(*ops):
    return '<transform name="to_world">' + "".join(ops) + "</transform>"


def translate(v):
    return f'<translate value="{vec(v)}"/>'


def scale(v):
    return f'<scale value="{vec(v)}"/>'


def rotate(axis, angle):
    return f'<rotate x="{num(axis[0])}" y="{num(axis[1])}" z="{num(axis[2])}" angle="{num(angle)}"/>'


def lookat(origin, target, up):
    return f'<lookat origin="{vec(origin)}" target="{vec(target)}" up="{vec(up)}"/>'


def transform_matrix(ops):
    """The 4x4 matrix of `ops`, each ("scale", v), ("rotate", axis, degrees) or ("translate", v),
    composed in order as Mitsuba composes a <transform>'s elements (each applied after the ones
    before it); the axis of a rotation is normalised."""
    m = np.eye(4)
    for op in ops:
        step = np.eye(4)
        if op[0] == "scale":
            step[:3, :3] = np.diag(op[1])
        elif op[0] == "translate":
            step[:3, 3] = op[1]
        else:
            a = np.array(op[1], dtype=float) / np.linalg.norm(op[1])
            angle = math.radians(op[2])
            cross = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
            step[:3, :3] = (math.cos(angle) * np.eye(3) + math.sin(angle) * cross
                            + (1 - math.cos(angle)) * np.outer(a, a))
        m = step @ m
    return m


def placement(ops, as_matrix=False):
    """A to_world of `ops` (see `transform_matrix`): their elements, or where `as_matrix` the same
    transform as one <matrix> (rows in order, as Mitsuba reads it)."""
    if as_matrix:
        values = " ".join(f"{x:.9g}" for x in transform_matrix(ops).flatten())
        return f'<transform name="to_world"><matrix value="{values}"/></transform>'
    xml = {"scale": lambda op: scale(op[1]), "rotate": lambda op: rotate(op[1], op[2]),
           "translate": lambda op: translate(op[1])}
    return to_world(*[xml[op[0]](op) for op in ops])


# --- The random scene ----------------------------------------------------------------------------

# What a shape's surface allows: `flat` (principledthin), `uv` (normal and bump maps), `smooth`
# (interpolated normals: no `twosided`, whose side caustic takes from the geometric normal and
# Mitsuba from the shading normal).
Surface = collections.namedtuple("Surface", "flat uv smooth")
# A shape's plugin, what the description calls it, its bounding radius, a function of its centre
# that gives its XML children, its surface, and whether its colours may be mesh attributes.
Shape = collections.namedtuple("Shape", "plugin label bound geometry surface attributes", defaults=(False,))

OBJECT_MATERIALS = ["diffuse", "twosided", "plastic", "roughplastic", "conductor", "roughconductor",
                    "dielectric", "roughdielectric", "thindielectric"]
FLOOR_MATERIALS = ["diffuse", "diffuse", "twosided", "roughplastic", "roughconductor"]
# blendbsdf's children: smooth lobes only (a Dirac lobe beside a smooth one renders differently by
# design), one-sided (a two-sided child beside a one-sided one is refused).
BLEND_MATERIALS = ["diffuse", "roughplastic", "roughconductor", "roughdielectric"]
# What a `twosided` may hold (feature "twosided-pairs"): one-sided models that transmit nothing.
TWOSIDED_MATERIALS = ["diffuse", "plastic", "roughplastic", "conductor", "roughconductor", "pplastic"]


@functools.lru_cache(maxsize=None)
def mean_luminance(path):
    """An image's mean luminance (linear), to scale the emitters textured with it."""
    bitmap = mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False)
    return float((np.array(bitmap) @ [0.2126, 0.7152, 0.0722]).mean())


class SceneMaker:
    """One scene drawn from `random.Random(seed)` with the extended kinds in `features` (none: the
    original generator, draw for draw): `xml()` writes it, `description` says what it holds."""

    def __init__(self, seed, features=frozenset()):
        self.r = random.Random(seed)
        self.features = features
        self.parts = []  # what the description lists, in order
        self.has_environment = False
        self.light_tracing = False  # ptracer (see `sensor` and `light` for what it changes)
        self.path_hides_emitters = False  # Mitsuba 3.9.1's `path` then crashes on an instance
        self.placed = []  # (centre, bounding radius) of the shapes
        self.definitions = []  # elements the shapes refer to (the shapegroup)
        self.group = None  # the shapegroup's (XML, bounding radius, description, holds a sphere)
        self.blend_depth = 0  # blends around the BSDF being made
        self.null_interfaces = False  # a mask, null or thindielectric: Mitsuba's reference by volpath
        self.integrator_kind = None
        self.integrator_children = []  # the integrator's max_depth, rr_depth, hide_emitters
        self.hides_emitters = False
        # Under ptracer, thin dielectrics (feature "thindielectric") in some scenes, which Mitsuba's
        # volpath renders, so none of what its light tracer renders unlike its path tracer (and
        # caustic's light tracer like its): normal and bump maps, principledthin.
        self.clear_panes = False
        self.sphere_turned = False  # whether the last sphere drawn is turned by its to_world
        # ibpt (feature "ibpt"): nothing non-reciprocal (normal and bump maps, principledthin), whose
        # light-traced estimate is another image than the path-traced one; perspective and thinlens.
        self.ibpt = False
        self.moment = False  # the integrator inside a `moment` (feature "moment")
        self.direct_counts = False  # direct's sample counts, drawn once the lights are known
        self.delta_lights = False  # a point, spot, projector or directional light
        self.meter = None  # an irradiancemeter's XML, waiting for its shape (feature "meters")
        self.meter_on_object = False  # whether an object (else the floor) holds it
        self.attributes = False  # whether the BSDF being drawn is on mesh_attribute.ply
        self.last_matrix = False  # whether the shape drawn last writes its to_world as a matrix

    def has(self, feature):
        return feature in self.features

    # Small random helpers.
    def uniform(self, a, b):
        return self.r.uniform(a, b)

    def colour(self, lo=0.1, hi=0.9):
        return [self.uniform(lo, hi) for _ in range(3)]

    def tint(self, power):
        return [power * self.uniform(0.6, 1.0) for _ in range(3)]

    def unit_vector(self):
        z = self.uniform(-1, 1)
        phi = self.uniform(0, 2 * math.pi)
        s = math.sqrt(1 - z * z)
        return [s * math.cos(phi), s * math.sin(phi), z]

    def colour_value(self, name, value, use="reflectance"):
        """The colour `value` as an <rgb>, or (feature "spectra", sometimes) in another form Mitsuba
        reads as a colour: a <float> or <spectrum value> grey of its mean, a `λ:value` list about that
        mean, or the `uniform` (that grey), `d65` (colour x scale), `rawconstant` or (a colour in [0, 1],
        not an IOR) `srgb` plugin. `use`: reflectance, emission or ior (no bound). Its XML and a note
        (None for an <rgb>)."""
        if not (self.has("spectra") and self.r.random() < 0.15):
            return rgb(name, value), None
        forms = ["float", "grey", "list", "uniform", "d65", "rawconstant"]
        if use != "ior" and max(value) <= 1:
            forms.append("srgb")
        form = self.r.choice(forms)
        grey = sum(value) / 3
        if form == "float":
            return flt(name, grey), "float"
        if form == "grey":
            return f'<spectrum name="{name}" value="{num(grey)}"/>', "grey"
        if form == "list":
            # Over the visible range at least (outside the listed range the spectrum is 0).
            wavelengths = ([self.r.randrange(360, 451, 10)] + sorted(self.r.sample(range(460, 650, 10),
                                                                                  self.r.randint(0, 4)))
                           + [self.r.randrange(650, 831, 10)])
            values = [grey * self.uniform(0.5, 1.5) for _ in wavelengths]
            if use == "reflectance":
                values = [min(v, 0.95) for v in values]
            text = ", ".join(f"{w}:{num(v)}" for w, v in zip(wavelengths, values))
            return f'<spectrum name="{name}" value="{text}"/>', "spectrum"
        if form == "uniform":
            return element("spectrum", "uniform", [flt("value", grey)], name=name), "uniform"
        if form == "d65":
            peak = max(value)
            return (element("spectrum", "d65", [rgb("color", [c / peak for c in value]), flt("scale", peak)],
                            name=name), "d65")
        if form == "rawconstant":
            return element("spectrum", "rawconstant", [f'<vector name="value" value="{vec(value)}"/>'],
                           name=name), "raw"
        return element("spectrum", "srgb", [rgb("color", value)], name=name), "srgb"

    # Textures.
    def uv_transform(self):
        """A checkerboard's to_uv: k x k checks, and (feature "uv", sometimes) unequal scales, a turn
        and an offset."""
        k = self.r.choice([2, 3, 4, 6])
        ops = [f'<scale x="{k}" y="{k}"/>']
        if self.has("uv") and self.r.random() < 0.5:
            ops = [f'<scale x="{k}" y="{self.r.choice([1, 2, 3, 4, 6])}"/>']
            if self.r.random() < 0.5:
                ops.append(f'<rotate z="1" angle="{num(self.uniform(0, 90))}"/>')
            if self.r.random() < 0.5:
                ops.append(f'<translate x="{num(self.uniform(-1, 1))}" y="{num(self.uniform(-1, 1))}"/>')
        return '<transform name="to_uv">' + "".join(ops) + "</transform>"

    def bitmap(self, name, path):
        """A `bitmap` of `path` with a random filter, wrap mode and to_uv (scaled and shifted past
        [0, 1]² so that the wrap mode shows); 8-bit files sometimes `raw`."""
        children = [string("filename", path)]
        notes = [os.path.splitext(os.path.basename(path))[0]]
        filter_type = self.r.choice([None, "bilinear", "nearest"])
        wrap_mode = self.r.choice([None, "repeat", "mirror", "clamp"])
        for key, value in [("filter_type", filter_type), ("wrap_mode", wrap_mode)]:
            if value:
                children.append(string(key, value))
                notes.append(value)
        if not path.endswith(".exr") and self.r.random() < 0.2:
            children.append(boolean("raw", True))
            notes.append("raw")
        if self.r.random() < 0.7:
            ops = [f'<scale x="{self.r.choice([1, 2, 3])}" y="{self.r.choice([1, 2, 3])}"/>']
            if self.r.random() < 0.5:
                x, y = self.uniform(-0.5, 0.5), self.uniform(-0.5, 0.5)
                ops.append(f'<translate x="{num(x)}" y="{num(y)}"/>')
            children.append('<transform name="to_uv">' + "".join(ops) + "</transform>")
        if self.has("bitmap-format"):
            # uint8 only where it keeps the texels: Mitsuba dithers what it rounds, caustic rounds.
            formats = ["auto", "variant", "fp16", "float16"] + (["uint8"] if path in EIGHT_BIT_IMAGES else [])
            if self.r.random() < 0.4:
                storage = self.r.choice(formats)
                children.append(string("format", storage))
                notes.append(storage)
            if self.r.random() < 0.2:
                accel = self.r.random() < 0.5
                children.append(boolean("accel", accel))
                notes.append(f"accel={str(accel).lower()}")
        return element("texture", "bitmap", children, name=name), "bitmap(" + "/".join(notes) + ")"

    # Materials.
    def reflectance(self, name, textured_chance=0.3):
        """A colour parameter: an RGB, or (sometimes) a checkerboard of two colours, or (feature
        "bitmap") an image; on mesh_attribute.ply, more often than not one of its attributes."""
        if self.attributes:
            textured_chance = max(textured_chance, 0.7)
        if self.r.random() < textured_chance:
            # On mesh_attribute.ply (feature "mesh-files"), diffuse's and principled(thin)'s colour:
            # not a transmittance (caustic does not read one from a mesh attribute), nor a plastic's
            # diffuse_reflectance (Mitsuba 3.9.1 takes its mean, which a mesh attribute has not).
            if self.attributes and name in ("reflectance", "base_color") and self.r.random() < 0.6:
                return self.mesh_attribute(name)
            if self.has("bitmap") and self.r.random() < 0.4:
                return self.bitmap(name, self.r.choice(REFLECTANCE_IMAGES))
            children = [self.colour_value("color0", self.colour())[0], self.colour_value("color1", self.colour())[0]]
            if self.r.random() < 0.6:
                children.append(self.uv_transform())
            return element("texture", "checkerboard", children, name=name), "checker"
        return self.colour_value(name, self.colour())

    def mesh_attribute(self, name):
        """A `mesh_attribute` texture of mesh_attribute.ply's: a colour, or the one-channel wear (a
        grey), sometimes scaled."""
        attribute, channels = self.r.choice(ATTRIBUTES)
        children, notes = [string("name", attribute)], [attribute]
        if channels == 1 or self.r.random() < 0.3:
            factor = self.uniform(0.3, 1.0)
            children.append(flt("scale", factor))
            notes.append(f"x{num(factor)}")
        return element("texture", "mesh_attribute", children, name=name), f"attribute({'/'.join(notes)})"

    def weight(self, name, lo, hi, textured_chance=0.3):
        """A scalar parameter: a number in [lo, hi], or (sometimes) a checkerboard of two."""
        if self.r.random() < textured_chance:
            children = [flt("color0", self.uniform(lo, hi)), flt("color1", self.uniform(lo, hi)),
                        self.uv_transform()]
            return element("texture", "checkerboard", children, name=name), f"{name}=checker"
        value = self.uniform(lo, hi)
        return flt(name, value), f"{name}={num(value)}"

    def ior(self, name="int_ior"):
        if self.r.random() < 0.4:
            value = self.r.choice(NAMED_IORS + (MORE_IORS if self.has("material-params") else []))
            return string(name, value), value
        value = self.uniform(1.3, 2.0)
        return flt(name, value), num(value)

    def roughness(self, anisotropic=False):
        """A microfacet distribution and its `alpha`, or where `anisotropic` (and feature
        "anisotropic", sometimes) unequal alpha_u and alpha_v, either of them a checkerboard."""
        if anisotropic and self.has("anisotropic") and self.r.random() < 0.5:
            distribution = self.r.choice(["ggx", "beckmann"])
            children, notes = [string("distribution", distribution)], []
            low = self.uniform(0.03, 0.15)
            high = self.uniform(0.3, 0.8)
            pair = [("alpha_u", low), ("alpha_v", high)]
            if self.r.random() < 0.5:
                pair = [("alpha_u", high), ("alpha_v", low)]
            for name, value in pair:
                if self.r.random() < 0.25:
                    child, _ = self.weight(name, 0.03, 0.8, textured_chance=1.0)
                    children.append(child)
                    notes.append(f"{name[-1]}=checker")
                else:
                    children.append(flt(name, value))
                    notes.append(f"{name[-1]}={num(value)}")
            return children, f"{distribution[0]}({'/'.join(notes)})"
        alpha = self.uniform(0.05, 0.6)
        distribution = self.r.choice(["ggx", "beckmann"])
        if anisotropic and self.has("material-params") and self.r.random() < 0.2:
            # A textured isotropic alpha (not roughplastic's, which Mitsuba refuses as a texture).
            texture, _ = self.weight("alpha", 0.05, 0.6, textured_chance=1.0)
            return [string("distribution", distribution), texture], f"{distribution[0]}(alpha=checker)"
        return [string("distribution", distribution), flt("alpha", alpha)], f"{distribution[0]}{num(alpha)}"

    def conductor_ior(self):
        """A named conductor or explicit eta and k (feature "material-params": more names, or eta or
        k a checkerboard of numbers; "spectra": eta and k as .spd files, or in other colour forms)."""
        if self.r.random() < 0.65:
            material = self.r.choice(NAMED_CONDUCTORS + (MORE_CONDUCTORS if self.has("material-params") else []))
            if SPD_CONDUCTORS and self.has("spectra") and self.r.random() < 0.25:
                material = self.r.choice(SPD_CONDUCTORS)
                files = [f'<spectrum name="{part}" filename="{os.path.join(IOR_FOLDER, f"{material}.{part}.spd")}"/>'
                         for part in ["eta", "k"]]
                return files, f"{material}.spd"
            return [string("material", material)], material
        eta = [self.uniform(0.15, 1.8) for _ in range(3)]
        k = [self.uniform(1.5, 5.0) for _ in range(3)]
        if self.has("material-params") and self.r.random() < 0.3:
            if self.r.random() < 0.5:
                texture, _ = self.weight("eta", 0.15, 1.8, textured_chance=1.0)
                return [texture, rgb("k", k)], "eta=checker/k"
            texture, _ = self.weight("k", 1.5, 5.0, textured_chance=1.0)
            return [rgb("eta", eta), texture], "eta/k=checker"
        (eta_xml, eta_note), (k_xml, k_note) = self.colour_value("eta", eta, "ior"), self.colour_value("k", k, "ior")
        notes = [note for note in [eta_note, k_note] if note]
        return [eta_xml, k_xml], "eta/k" + (f"({','.join(notes)})" if notes else "")

    def materials(self, base, surface):
        """`base` and the extended BSDFs that suit `surface`. Objects (not the floor) get more thin
        dielectrics where flat (panes); without feature "thindielectric" the extended generator
        draws no thin dielectric at all."""
        kinds = base + [k for k in ["principled", "pplastic", "blendbsdf"] if self.has(k)]
        if surface.flat and self.has("principledthin") and not (self.clear_panes or self.ibpt):
            kinds.append("principledthin")
        if surface.smooth:
            kinds = [k for k in kinds if k != "twosided"]
        if self.clear_panes:  # light tracing renders no Dirac reflection seen by the camera
            kinds = [k for k in kinds if k not in ("conductor", "dielectric", "plastic")]
        thin = self.has("thindielectric") and (self.clear_panes or not self.light_tracing)
        if self.features and not thin:
            kinds = [k for k in kinds if k != "thindielectric"]
        elif thin and base is OBJECT_MATERIALS and surface.flat:
            kinds.append("thindielectric")
        return kinds

    def object_bsdf(self, surface, nulls=True):
        """An object's BSDF (`surface_bsdf` of `materials`); not under ptracer, sometimes `null`
        (feature "null") or inside a `mask` (feature "mask"); none of the three (nor a thin
        dielectric) where not `nulls`."""
        if nulls and self.has("null") and not self.light_tracing and self.r.random() < 0.07:
            self.null_interfaces = True
            return element("bsdf", "null", []), "null"
        kinds = self.materials(OBJECT_MATERIALS, surface)
        if not nulls:
            kinds = [k for k in kinds if k != "thindielectric"]
        bsdf, text = self.surface_bsdf(kinds, surface)
        # No mask around a twosided of two BSDFs: caustic refuses it.
        if (nulls and self.has("mask") and not self.light_tracing and not text.startswith("twosided-pair")
                and self.r.random() < 0.12):
            return self.mask(bsdf, text)
        return bsdf, text

    def mask(self, inner, text):
        """`inner` in a `mask` whose opacity is a number, a checkerboard of two or a bitmap (its
        luminance)."""
        self.null_interfaces = True
        if self.has("bitmap") and self.r.random() < 0.25:
            opacity, note = self.bitmap("opacity", self.r.choice(REFLECTANCE_IMAGES))
        else:
            opacity, note = self.weight("opacity", 0.1, 0.95, textured_chance=0.4)
        return element("bsdf", "mask", [opacity, inner]), f"mask({note},{text})"

    def thin(self):
        """A `thindielectric` (feature "thindielectric"): an IOR (under ptracer equal inside and out:
        light tracing cannot connect a Dirac reflection to the camera), mostly a tinted
        specular_transmittance (sometimes a texture)."""
        self.null_interfaces = True
        notes = []
        if self.light_tracing:
            value = 1.0 if self.r.random() < 0.5 else self.uniform(1.3, 2.0)
            children = [flt("int_ior", value), flt("ext_ior", value)]
            notes.append(f"clear={num(value)}")
        else:
            ior, ior_text = self.ior()
            children, notes = [ior], [ior_text]
            if self.r.random() < 0.2:
                ext, ext_text = self.ior("ext_ior") if self.r.random() < 0.3 else (flt("ext_ior", 1.0), "1")
                children.append(ext)
                notes.append(f"ext={ext_text}")
        if self.r.random() < 0.8:
            tint, tex = self.reflectance("specular_transmittance", textured_chance=0.25)
            children.append(tint)
            notes.append(f"T={tex}" if tex else "tinted")
        if self.has("material-params") and self.r.random() < 0.2:
            children.append(self.colour_value("specular_reflectance", self.colour(0.5, 1.0))[0])
            notes.append("R")
        return element("bsdf", "thindielectric", children), f"thindielectric({','.join(notes)})"

    def surface_bsdf(self, kinds, surface):
        """`bsdf(kinds)`, on a shape with uv sometimes under a normal or bump map (not a thin
        dielectric: Mitsuba 3.9.1's normalmap and bumpmap do not pass on eval_null_transmission, so
        its volpath's shadow rays stop at them while its sampled paths cross; nor a twosided of two
        BSDFs, which caustic refuses under a map)."""
        bsdf, text = self.bsdf(kinds)
        reciprocal_only = self.clear_panes or self.ibpt
        maps = [kind for kind in ["normalmap", "bumpmap"] if self.has(kind)]
        maps = maps if surface.uv and not reciprocal_only else []
        if maps and not text.startswith(("thindielectric", "twosided-pair")) and self.r.random() < 0.2:
            return self.perturbed(self.r.choice(maps), bsdf, text)
        return bsdf, text

    def perturbed(self, kind, inner, text):
        """`inner` under a `normalmap` (normalmap_normals.png) or `bumpmap` (normalmap_height.png,
        bilinear: caustic's nearest-filtered heights have no gradient)."""
        notes = []
        image = [string("filename", NORMAL_MAP if kind == "normalmap" else HEIGHT_MAP)]
        if self.r.random() < 0.8:
            image.append(boolean("raw", True))
        else:
            notes.append("srgb")
        k = self.r.choice([1, 2, 3])
        image.append(f'<transform name="to_uv"><scale x="{k}" y="{k}"/></transform>')
        children = []
        if kind == "bumpmap":
            children.append(element("texture", "bitmap", image))
            bump = self.uniform(0.05, 0.5)
            children.append(flt("scale", bump))
            notes.append(f"scale={num(bump)}")
        else:
            if self.r.random() < 0.3:
                image.append(string("filter_type", "nearest"))
                notes.append("nearest")
            children.append(element("texture", "bitmap", image, name="normalmap"))
        for flag in ["flip_invalid_normals", "use_shadowing_function"]:
            if self.r.random() < 0.2:
                children.append(boolean(flag, False))
                notes.append(f"no-{flag}")
        return element("bsdf", kind, children + [inner]), f"{kind}({','.join(notes + [text])})"

    def principled(self, kind):
        """`principled` or `principledthin`: each weight left out, a number or a checkerboard."""
        thin = kind == "principledthin"
        refl, tex = self.reflectance("base_color")
        children, notes = [refl], [tex] if tex else []
        weights = [("roughness", 0.05, 0.9), ("spec_trans", 0, 1), ("spec_tint", 0, 1), ("sheen", 0, 1),
                   ("sheen_tint", 0, 1), ("flatness", 0, 1)]
        if thin:
            weights += [("diff_trans", 0, 2), ("eta", 1.2, 1.9)]
        else:
            weights += [("metallic", 0, 1), ("clearcoat", 0, 1), ("clearcoat_gloss", 0, 1)]
        if self.has("anisotropic"):
            weights.append(("anisotropic", 0, 1))
        for name, lo, hi in weights:
            if self.r.random() < 0.5:
                child, note = self.weight(name, lo, hi)
                children.append(child)
                notes.append(note)
        if not thin and self.r.random() < 0.4:  # principled's eta, or its Schlick `specular`: numbers
            if self.r.random() < 0.5:
                name, value = "eta", self.uniform(1.2, 1.9)
            else:
                name, value = "specular", self.uniform(0, 1)
            children.append(flt(name, value))
            notes.append(f"{name}={num(value)}")
        return element("bsdf", kind, children), f"{kind}({','.join(notes)})"

    def pplastic(self):
        refl, tex = self.reflectance("diffuse_reflectance")
        children, notes = [refl], [tex] if tex else []
        if self.r.random() < 0.25:
            children.append(self.colour_value("specular_reflectance", self.colour(0.5, 1.0))[0])
        if self.r.random() < 0.5:
            ior, ior_text = self.ior()
            children.append(ior)
            notes.append(ior_text)
        elif self.has("material-params") and self.r.random() < 0.5:
            # Its relative index as `eta` (not with int_ior/ext_ior, as Mitsuba): a number or a
            # checkerboard (its luminance, Mitsuba's eval_1).
            eta, eta_text = self.weight("eta", 1.3, 2.0, textured_chance=0.4)
            children.append(eta)
            notes.append(eta_text)
        rough, rough_text = self.roughness(anisotropic=True)
        return element("bsdf", "pplastic", children + rough), f"pplastic({','.join(notes + [rough_text])})"

    def blend(self):
        """`blendbsdf` of two smooth one-sided BSDFs, weight a number, a checkerboard or a bitmap."""
        if self.has("bitmap") and self.r.random() < 0.2:
            weight, weight_text = self.bitmap("weight", HEIGHT_MAP)
        else:
            weight, weight_text = self.weight("weight", 0, 1, textured_chance=0.4)
        kinds = BLEND_MATERIALS + [k for k in ["principled", "pplastic"] if self.has(k)]
        # Blends inside, two levels deep at most (caustic mixes up to eight leaves).
        if self.has("nested-blends") and self.blend_depth < 2:
            kinds = kinds + ["blendbsdf"]
        self.blend_depth += 1
        (first, first_text), (second, second_text) = self.bsdf(kinds), self.bsdf(kinds)
        self.blend_depth -= 1
        return (element("bsdf", "blendbsdf", [weight, first, second]),
                f"blendbsdf({weight_text},{first_text},{second_text})")

    def bsdf(self, kinds):
        """A random BSDF among `kinds`: its XML and a short description."""
        kind = self.r.choice(kinds)
        if kind in ("principled", "principledthin"):
            return self.principled(kind)
        if kind == "pplastic":
            return self.pplastic()
        if kind == "blendbsdf":
            return self.blend()
        if kind == "thindielectric":
            if self.has("thindielectric"):
                return self.thin()
            self.null_interfaces = True  # the original generator's (drawn below)
        if kind == "diffuse":
            refl, tex = self.reflectance("reflectance")
            return element("bsdf", "diffuse", [refl]), "diffuse" + (f"({tex})" if tex else "")
        if kind == "twosided":
            if self.has("twosided-pairs") and self.r.random() < 0.5:
                return self.two_sided()
            refl, tex = self.reflectance("reflectance")
            inner = element("bsdf", "diffuse", [refl])
            return element("bsdf", "twosided", [inner]), "twosided(diffuse" + (f",{tex})" if tex else ")")
        if kind in ("plastic", "roughplastic"):
            refl, tex = self.reflectance("diffuse_reflectance")
            ior, ior_text = self.ior()
            children = [refl, ior, boolean("nonlinear", self.r.random() < 0.3)]
            notes = [ior_text] + ([tex] if tex else [])
            if self.r.random() < 0.25:
                children.append(self.colour_value("specular_reflectance", self.colour(0.5, 1.0))[0])
            if self.has("material-params") and self.r.random() < 0.2:
                # Below every interior index drawn (1.31 and up): no index-matched plastic.
                ext = self.uniform(1.0, 1.25)
                children.append(flt("ext_ior", ext))
                notes.append(f"ext={num(ext)}")
            if kind == "roughplastic":
                rough, rough_text = self.roughness()
                children += rough
                notes.append(rough_text)
            return element("bsdf", kind, children), f"{kind}({','.join(notes)})"
        if kind in ("conductor", "roughconductor"):
            children, notes = self.conductor_ior()
            notes = [notes]
            if self.r.random() < 0.25:
                children.append(self.colour_value("specular_reflectance", self.colour(0.5, 1.0))[0])
            if kind == "roughconductor":
                rough, rough_text = self.roughness(anisotropic=True)
                children += rough
                notes.append(rough_text)
            return element("bsdf", kind, children), f"{kind}({','.join(notes)})"
        # The dielectrics.
        ior, ior_text = self.ior()
        children = [ior]
        notes = [ior_text]
        if self.r.random() < 0.2:
            ext, ext_text = self.ior("ext_ior") if self.r.random() < 0.3 else (flt("ext_ior", 1.0), "1")
            children.append(ext)
            notes.append(f"ext={ext_text}")
        if self.r.random() < 0.25:
            if self.has("material-params") and self.r.random() < 0.4:
                tint, tex = self.reflectance("specular_transmittance", textured_chance=1.0)
                children.append(tint)
                notes.append(f"T={tex}")
            else:
                children.append(self.colour_value("specular_transmittance", self.colour(0.4, 1.0))[0])
        if self.has("material-params") and self.r.random() < 0.2:
            children.append(self.colour_value("specular_reflectance", self.colour(0.5, 1.0))[0])
            notes.append("R")
        if kind == "roughdielectric":
            rough, rough_text = self.roughness(anisotropic=True)
            children += rough
            notes.append(rough_text)
        return element("bsdf", kind, children), f"{kind}({','.join(notes)})"

    def two_sided(self):
        """`twosided` (feature "twosided-pairs") around one of TWOSIDED_MATERIALS, or two of them: the
        first on the front, the second on the back."""
        kinds = [k for k in TWOSIDED_MATERIALS if k != "pplastic" or self.has("pplastic")]
        if self.clear_panes:  # as `materials`
            kinds = [k for k in kinds if k not in ("conductor", "plastic")]
        sides = [self.bsdf(kinds) for _ in range(self.r.choice([1, 2]))]
        xml = element("bsdf", "twosided", [bsdf for bsdf, _ in sides])
        if len(sides) == 1:
            return xml, f"twosided({sides[0][1]})"
        return xml, f"twosided-pair({sides[0][1]}|{sides[1][1]})"

    # Geometry. Each maker draws a shape's size and orientation and returns its bounding radius and a
    # function that gives the shape's XML children for a centre, so that a place can be found for it.
    def matrix_form(self):
        """Whether the shape being drawn writes its to_world as one `matrix` (feature
        "shape-options", sometimes)."""
        self.last_matrix = self.has("shape-options") and self.r.random() < 0.2
        return self.last_matrix

    def sphere(self):
        radius = self.uniform(0.25, 0.6)
        self.sphere_turned = False
        if self.r.random() < 0.5:
            return radius, lambda c: [point("center", c), flt("radius", radius)]
        if self.has("sphere-frames") and self.r.random() < 0.7:
            self.sphere_turned = True
            axis, angle = self.unit_vector(), self.uniform(0, 360)
            as_matrix = self.matrix_form()
            return radius, lambda c: [placement([("scale", [radius] * 3), ("rotate", axis, angle), ("translate", c)],
                                                as_matrix)]
        as_matrix = self.matrix_form()
        return radius, lambda c: [placement([("scale", [radius] * 3), ("translate", c)], as_matrix)]

    def flat(self, kind):
        sx, sy = self.uniform(0.3, 0.7), self.uniform(0.3, 0.7)
        if kind == "disk" and self.r.random() < 0.5:
            sy = sx
        axis, angle = self.unit_vector(), self.uniform(0, 360)
        bound = math.hypot(sx, sy) if kind == "rectangle" else max(sx, sy)
        as_matrix = self.matrix_form()
        return bound, lambda c: [placement([("scale", [sx, sy, 1]), ("rotate", axis, angle), ("translate", c)],
                                           as_matrix)]

    def cube(self):
        s = [self.uniform(0.2, 0.45) for _ in range(3)]
        if self.r.random() < 0.4:
            s = [s[0]] * 3
        axis, angle = self.unit_vector(), self.uniform(0, 360)
        as_matrix = self.matrix_form()
        return math.sqrt(sum(x * x for x in s)), lambda c: [
            placement([("scale", s), ("rotate", axis, angle), ("translate", c)], as_matrix)]

    def cylinder(self):
        radius, half = self.uniform(0.15, 0.4), self.uniform(0.2, 0.5)
        bound = math.hypot(half, radius)
        if self.r.random() < 0.5:
            axis = self.unit_vector()
            return bound, lambda c: [point("p0", [c[i] - half * axis[i] for i in range(3)]),
                                     point("p1", [c[i] + half * axis[i] for i in range(3)]),
                                     flt("radius", radius)]
        # The default cylinder runs from z = 0 to 1 with radius 1: centre it, size it, turn it, place it.
        axis, angle = self.unit_vector(), self.uniform(0, 360)
        as_matrix = self.matrix_form()
        return bound, lambda c: [placement([("translate", [0, 0, -0.5]), ("scale", [radius, radius, 2 * half]),
                                            ("rotate", axis, angle), ("translate", c)], as_matrix)]

    def mesh(self):
        """A mesh of MESHES (feature "meshes") or MORE_MESHES ("mesh-files"), centred, sized
        (sometimes unequally), turned; its own or (sometimes) face normals; an OBJ with uv sometimes
        without flip_tex_coords ("shape-options")."""
        pool = (MESHES if self.has("meshes") else []) + (MORE_MESHES if self.has("mesh-files") else [])
        mesh = self.r.choice(pool)
        size = self.uniform(0.3, 0.55)
        factors = [size / mesh.radius] * 3
        if self.r.random() < 0.4:
            factors = [f * self.uniform(0.6, 1.0) for f in factors]
        axis, angle = self.unit_vector(), self.uniform(0, 360)
        children = [string("filename", mesh.path)]
        name = os.path.splitext(os.path.basename(mesh.path))[0]
        notes = []
        if mesh.shape_index is not None:
            children.append(integer("shape_index", mesh.shape_index))
            name += f"#{mesh.shape_index}"
        face_normals = self.r.random() < 0.3
        if face_normals:
            children.append(boolean("face_normals", True))
            notes.append("faces")
        if mesh.plugin == "obj" and mesh.uv and self.has("shape-options") and self.r.random() < 0.3:
            children.append(boolean("flip_tex_coords", False))
            notes.append("unflipped-uv")
        as_matrix = self.matrix_form()
        label = f"{mesh.plugin}({name}{''.join(',' + note for note in notes)})"
        centring = [("translate", [-x for x in mesh.centre])] if any(mesh.centre) else []
        geometry = lambda c: children + [placement(centring + [("scale", factors), ("rotate", axis, angle),
                                                               ("translate", c)], as_matrix)]
        surface = Surface(flat=mesh.flat, uv=mesh.uv, smooth=not face_normals and not mesh.flat)
        return Shape(mesh.plugin, label, size, geometry, surface, attributes=mesh.path == ATTRIBUTE_MESH)

    def shape_geometry(self, kind):
        self.last_matrix = False
        if kind == "mesh":
            shape = self.mesh()
        else:
            if kind == "sphere":
                bound, geometry = self.sphere()
            elif kind in ("rectangle", "disk"):
                bound, geometry = self.flat(kind)
            elif kind == "cube":
                bound, geometry = self.cube()
            else:
                bound, geometry = self.cylinder()
            flat = kind in ("rectangle", "disk")
            shape = Shape(kind, kind, bound, geometry, Surface(flat=flat, uv=True, smooth=False))
        return shape._replace(label=shape.label + "[matrix]") if self.last_matrix else shape

    def shape_kinds(self):
        meshes = self.has("meshes") or self.has("mesh-files")
        return (["sphere", "rectangle", "disk", "cube", "cylinder"] + (["mesh"] if meshes else [])
                + (["instance"] if self.has("instances") and not self.path_hides_emitters else []))

    def shapegroup(self):
        """The scene's `shapegroup`: one or two shapes about its origin, with BSDFs (no emitters:
        Mitsuba refuses them there). Its XML, bounding radius, description, whether it holds a sphere.
        No null interface on a cylinder there: Mitsuba 3.9.1's volpath can cross a null cylinder in
        an instance for ever (each crossing meets the cylinder again, and a crossing is no bounce)."""
        members, texts, bound, has_sphere = [], [], 0.0, False
        kinds = [k for k in self.shape_kinds() if k != "instance"]
        direction = self.unit_vector()
        offset = 0.0
        for _ in range(self.r.choice([1, 2, 2])):
            shape = self.shape_geometry(self.r.choice(kinds))
            if members:  # the second beside the first
                offset += shape.bound + 0.05
            centre = [offset * d for d in direction]
            offset += shape.bound
            bound = max(bound, math.sqrt(sum(x * x for x in centre)) + shape.bound)
            has_sphere |= shape.plugin == "sphere"
            bsdf, text = self.object_bsdf(shape.surface, nulls=shape.plugin != "cylinder")
            members.append(element("shape", shape.plugin, shape.geometry(centre) + [bsdf]))
            texts.append(f"{shape.label}:{text}")
        xml = f'<shape type="shapegroup" id="group">{"".join(members)}</shape>'
        return xml, bound, "+".join(texts), has_sphere

    def instance(self):
        """An `instance` of the shapegroup (made at the first call), turned and sized (unequally or
        mirrored where it holds no sphere): its bounding radius, and a function of its centre that
        gives its XML and description."""
        if self.group is None:
            self.group = self.shapegroup()
        group_xml, group_bound, group_text, has_sphere = self.group
        size = self.uniform(0.35, 0.7)
        factors = [size / group_bound] * 3
        if not has_sphere and self.r.random() < 0.5:
            factors = [f * self.uniform(0.6, 1.0) for f in factors]
            if self.r.random() < 0.4:
                factors[0] = -factors[0]
        axis, angle = self.unit_vector(), self.uniform(0, 360)
        notes = ",mirrored" if factors[0] < 0 else "" if factors[0] == factors[1] == factors[2] else ",unequal"
        as_matrix = self.matrix_form()
        notes += ",matrix" if as_matrix else ""

        def place(c):
            if group_xml not in self.definitions:
                self.definitions.append(group_xml)
            children = ['<ref id="group"/>',
                        placement([("scale", factors), ("rotate", axis, angle), ("translate", c)], as_matrix)]
            return element("shape", "instance", children), f"instance[{group_text}{notes}]"
        return size, place

    def place_objects(self):
        """2-4 shapes floating above the floor around the origin, their bounding spheres apart; some
        (feature "shape-options") with flipped normals, some (feature "merge") inside a `merge`; one
        (feature "meters") may hold the irradiancemeter."""
        placed = self.placed
        shapes = []
        mergeable = []  # whether each of `shapes` may go into a merge: no instance, emitter or sensor
        emissive_left = 1 if self.r.random() < 0.2 else 0
        if self.features and self.hides_emitters:
            # Mitsuba 3.9.1 renders what a camera ray meets past a skipped emitter wrongly (see the
            # docstring): no emissive object among the shapes then (the original generator's kept).
            emissive_left = 0
        for _ in range(self.r.randint(2, 4)):
            kind = self.r.choice(self.shape_kinds())
            if kind == "instance":
                bound, place = self.instance()
            else:
                shape = self.shape_geometry(kind)
                bound = shape.bound
            for _attempt in range(50):
                ring, angle = self.uniform(0, 1.6), self.uniform(0, 2 * math.pi)
                c = [ring * math.cos(angle), ring * math.sin(angle), bound + self.uniform(0.03, 0.6)]
                if all(math.dist(c, pc) > bound + pb + 0.05 for pc, pb in placed):
                    break
            else:
                continue  # no room left: one shape fewer
            placed.append((c, bound))
            if kind == "instance":
                xml, text = place(c)
                shapes.append(xml)
                mergeable.append(False)
                self.parts.append(text)
                continue
            children = shape.geometry(c)
            if emissive_left and kind in ("sphere", "cube", "cylinder", "mesh"):
                emissive_left = 0
                if kind == "sphere" and self.sphere_turned and self.light_tracing:
                    # Mitsuba 3.9.1's sphere samples an emitting point turned by its to_world but
                    # gives it the unturned normal (sphere.cpp, sample_position: `ps.n = local`), so
                    # its ptracer, which starts light paths there, mis-lights a turned emitting sphere
                    # (seed 430's alone under the camera: mean 0.00073 against its path's 0.0394;
                    # caustic's ptracer agrees with the latter). Unturned, the sphere is the same.
                    children = [point("center", c), flt("radius", bound)]
                null = self.has("null") and not self.light_tracing and self.r.random() < 0.3
                if null:
                    self.null_interfaces = True
                    children.append(element("bsdf", "null", []))
                else:
                    children.append(element("bsdf", "diffuse", [self.colour_value("reflectance", self.colour())[0]]))
                power = self.uniform(0.5, 3.0)
                # Mitsuba samples a textured emitter in uv space, which takes a one-to-one uv map:
                # not a cube's (six faces on one square: it samples one) nor a mesh's without uv (nor,
                # unchecked, matpreview.serialized's).
                # Nor a turned cylinder's or sphere's: their eval_parameterization casts a ray from
                # the world-space point along the object-space direction, which misses the point.
                turned = kind == "cylinder" or (kind == "sphere" and self.sphere_turned)
                if shape.surface.uv and kind != "cube" and not turned and shape.plugin != "serialized":
                    radiance, tex = self.radiance("radiance", power, images=True)
                else:
                    radiance, tex = self.colour_value("radiance", self.tint(power), "emission")
                children.append(element("emitter", "area", [radiance]))
                shapes.append(element("shape", shape.plugin, children))
                mergeable.append(False)
                self.parts.append(f"{shape.label}:{'null+' if null else ''}emitter" + (f"({tex})" if tex else ""))
                continue
            self.attributes = shape.attributes
            bsdf, text = self.object_bsdf(shape.surface)
            self.attributes = False
            label, meter = shape.label, False
            if self.has("shape-options") and self.r.random() < 0.12:
                children.append(boolean("flip_normals", True))
                label += "(flipped)"
            elif self.meter and self.meter_on_object and kind in ("sphere", "rectangle", "disk", "cube"):
                children.append(self.meter)
                self.meter, meter = None, True
                label += "(irradiancemeter)"
            shapes.append(element("shape", shape.plugin, children + [bsdf]))
            mergeable.append(not meter)
            self.parts.append(f"{label}:{text}")
        if self.has("merge") and self.r.random() < 0.25:
            candidates = [i for i, ok in enumerate(mergeable) if ok]
            if candidates:
                chosen = sorted(self.r.sample(candidates, self.r.randint(1, len(candidates))))
                merged = element("shape", "merge", [shapes[i] for i in chosen])
                shapes = [merged if i == chosen[0] else xml for i, xml in enumerate(shapes) if i not in chosen[1:]]
                self.parts.append(f"merge of {len(chosen)}")
        return shapes

    def floor(self):
        size = self.uniform(3.0, 6.0)
        surface = Surface(flat=True, uv=True, smooth=False)
        bsdf, text = self.surface_bsdf(self.materials(FLOOR_MATERIALS, surface), surface)
        self.parts.append(f"floor:{text}")
        return element("shape", "rectangle", [to_world(scale([size, size, 1])), bsdf])

    # Lights.
    def emission_checkerboard(self, name, a, b):
        """A checkerboard of the greys `a` and `b`: numbers, which Mitsuba does not bound (its RGB
        colours in a texture are reflectances, at most 1, even in an emitter)."""
        children = [flt("color0", a), flt("color1", b), self.uv_transform()]
        return element("texture", "checkerboard", children, name=name)

    def radiance(self, name, power, images):
        """An emitted colour of about `power`: an RGB or (feature "emitter-textures", sometimes) a
        checkerboard of two greys, or where `images`, an HDR image (values up to 4). Under ptracer
        no checkerboard: Mitsuba's light tracer samples an emitter's spectrum, which its
        checkerboard cannot (Texture::sample_spectrum(): not implemented)."""
        if self.has("emitter-textures") and self.r.random() < 0.4:
            if images and (self.light_tracing or self.r.random() < 0.5):
                return self.bitmap(name, self.r.choice(EMISSION_IMAGES))
            if not self.light_tracing:
                a, b = power * self.uniform(0.6, 1.0), power * self.uniform(0.2, 1.0)
                return self.emission_checkerboard(name, a, b), "checker"
        return self.colour_value(name, self.tint(power), "emission")

    def emitted_image(self, name):
        """A texture for a spot's `texture` or a projector's `irradiance`: an HDR image or (not under
        ptracer: see `radiance`) a checkerboard; and its mean luminance."""
        if self.light_tracing or self.r.random() < 0.7:
            path = self.r.choice(EMISSION_IMAGES)
            texture, text = self.bitmap(name, path)
            return texture, text, mean_luminance(path)
        a, b = self.uniform(0.2, 2.0), self.uniform(0.2, 2.0)
        return self.emission_checkerboard(name, a, b), "checker", (a + b) / 2

    def light(self, kind, key):
        """An emitter of `kind`; the key light is brighter and aimed at the middle of the floor."""
        irradiance = self.uniform(1.0, 3.0) if key else self.uniform(0.2, 1.2)
        spread = 1.0 if key else 2.0
        for _attempt in range(50):  # clear of the shapes (a lamp inside one would light nothing)
            position = [self.uniform(-spread, spread), self.uniform(-spread, spread), self.uniform(2.6, 3.8)]
            if all(math.dist(position, c) > bound + 0.6 for c, bound in self.placed):
                break
        distance2 = sum(x * x for x in position)
        if kind in ("point", "spot", "projector", "directional"):
            self.delta_lights = True
        if kind == "point":
            self.parts.append("point")
            intensity, _ = self.colour_value("intensity", self.tint(irradiance * distance2), "emission")
            return element("emitter", "point", [point("position", position), intensity])
        if kind == "spot":
            target = [self.uniform(-0.7, 0.7), self.uniform(-0.7, 0.7), 0]
            cutoff = self.uniform(20, 60)
            intensity = self.tint(irradiance * distance2)
            children = [to_world(lookat(position, target, [0, 1, 0])), None, flt("cutoff_angle", cutoff)]
            if self.r.random() < 0.7:
                children.append(flt("beam_width", cutoff * self.uniform(0.3, 0.95)))
            notes = [num(cutoff)]
            if self.has("emitter-textures") and self.r.random() < 0.35:
                texture, text, mean = self.emitted_image("texture")
                intensity = [x / mean for x in intensity]
                children.append(texture)
                notes.append(text)
            children[1] = self.colour_value("intensity", intensity, "emission")[0]
            self.parts.append(f"spot({','.join(notes)})")
            return element("emitter", "spot", children)
        if kind == "projector":
            target = [self.uniform(-0.7, 0.7), self.uniform(-0.7, 0.7), 0]
            fov = self.uniform(20, 50)
            if self.has("projector-focal") and self.r.random() < 0.3:
                # A 35 mm-equivalent focal length (fov_axis is then not read, so none is given).
                focal = self.r.randint(35, 120)
                children = [to_world(lookat(position, target, [0, 1, 0])), string("focal_length", f"{focal}mm")]
                notes = [f"{focal}mm"]
            else:
                children = [to_world(lookat(position, target, [0, 1, 0])), flt("fov", fov)]
                notes = [f"fov={num(fov)}"]
                if self.r.random() < 0.3:
                    axis = self.r.choice(["x", "y", "diagonal", "smaller", "larger"])
                    children.append(string("fov_axis", axis))
                    notes.append(axis)
            # Mitsuba's projector gives pi * irradiance * scale / d^2 at distance d.
            power = irradiance * math.dist(position, target) ** 2 / math.pi
            if self.r.random() < 0.5:
                texture, text, mean = self.emitted_image("irradiance")
                children += [texture, flt("scale", power / mean)]
                notes.append(text)
            else:
                children += [self.colour_value("irradiance", self.tint(1.0), "emission")[0], flt("scale", power)]
            self.parts.append(f"projector({','.join(notes)})")
            return element("emitter", "projector", children)
        if kind == "directional":
            theta, phi = math.radians(self.uniform(0, 60)), self.uniform(0, 2 * math.pi)
            direction = [math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), -math.cos(theta)]
            self.parts.append("directional")
            return element("emitter", "directional", [
                f'<vector name="direction" value="{vec(direction)}"/>',
                self.colour_value("irradiance", self.tint(irradiance), "emission")[0]])
        if kind == "constant":
            self.has_environment = True
            self.parts.append("constant")
            return element("emitter", "constant",
                           [self.colour_value("radiance", self.tint(irradiance / math.pi), "emission")[0]])
        if kind == "envmap":
            self.has_environment = True
            path = self.r.choice(ENVIRONMENT_IMAGES)
            children = [string("filename", path), flt("scale", irradiance / (math.pi * mean_luminance(path)))]
            notes = [os.path.splitext(os.path.basename(path))[0]]
            # Under ptracer the map keeps Mitsuba's orientation: Mitsuba 3.9.1's light tracer emits
            # from a turned map wrongly (its ptracer and path images differ up to 15x per pixel). And
            # there caustic leaves compensation off (light tracing samples emission from the map alone).
            if not self.light_tracing:
                children.append(to_world(rotate(self.unit_vector(), self.uniform(0, 360))))
                if self.r.random() < 0.3:
                    children.append(boolean("mis_compensation", True))
                    notes.append("mis_compensation")
            self.parts.append(f"envmap({','.join(notes)})")
            return element("emitter", "envmap", children)
        if kind == "directionalarea":
            # A flat lamp facing down (feature "directionalarea"), a little tilted, that emits along
            # its normal only: its irradiance across the beam is its radiance. Only a light tracer
            # renders its light (the camera and shading points never meet its one direction).
            shape = self.r.choice(["rectangle", "disk"])
            size = self.uniform(0.8, 1.8) if key else self.uniform(0.3, 1.0)
            tilt = rotate(self.unit_vector(), self.uniform(0, 10))
            geometry = [to_world(scale([size, size, 1]), rotate([1, 0, 0], 180), tilt, translate(position))]
            radiance, tex = self.radiance("radiance", irradiance, images=True)
            children = geometry + [element("emitter", "directionalarea", [radiance])]
            if self.r.random() < 0.5:
                children.append(element("bsdf", "diffuse", [self.colour_value("reflectance", self.colour())[0]]))
            self.parts.append(f"directionalarea-{shape}" + (f"({tex})" if tex else ""))
            return element("shape", shape, children)
        # An area lamp above the scene: a sphere, or a rectangle or disk facing down.
        shape = self.r.choice(["sphere", "rectangle", "disk"])
        size = self.uniform(0.15, 0.45)
        if shape == "sphere":
            geometry = [point("center", position), flt("radius", size)]
            area = math.pi * size * size  # the disk it shows the floor below
        else:
            tilt = rotate(self.unit_vector(), self.uniform(0, 25))
            geometry = [to_world(scale([size, size, 1]), rotate([1, 0, 0], 180), tilt, translate(position))]
            area = 4 * size * size if shape == "rectangle" else math.pi * size * size
        radiance, tex = self.radiance("radiance", irradiance * distance2 / area, images=False)
        children = geometry + [element("emitter", "area", [radiance])]
        note = ""
        if self.r.random() < 0.5:
            children.append(element("bsdf", "diffuse", [self.colour_value("reflectance", self.colour())[0]]))
        elif self.has("null") and not self.light_tracing and self.r.random() < 0.4:
            self.null_interfaces = True
            children.append(element("bsdf", "null", []))
            note = "null+"
        self.parts.append(f"area-{note}{shape}" + (f"({tex})" if tex else ""))
        return element("shape", shape, children)

    def lights(self):
        extra = [kind for kind in ["projector", "envmap"] if self.has(kind)]
        # directionalarea: the key light only under ptracer (the only integrator that renders its
        # light); never under ibpt, which caustic refuses it under; nor under ptracer with null
        # interfaces, whose reference is `volpath`, which renders the lamp black (seed 258 compared
        # caustic's lit image with a black one).
        directional_area = (self.has("directionalarea") and not self.ibpt
                            and not (self.light_tracing and self.null_interfaces))
        keys = ["area", "area", "point", "spot", "directional", "constant"] + extra
        if directional_area and self.light_tracing:
            keys += ["directionalarea"] * 2
        # Under ibpt, no delta lights (point, spot, directional, projector): its light tracing finds
        # their caustics through Dirac surfaces (light, mirror, diffuse, camera), which Mitsuba's `path`,
        # the reference, cannot (seeds 200 and 290: ibpt 1.5-4% above it, and as bright as caustic's
        # own ptracer on seed 290).
        delta = {"point", "spot", "directional", "projector"} if self.ibpt else set()
        key = self.r.choice([k for k in keys if k not in delta])
        emitters = [self.light(key, True)]
        for _ in range(self.r.choice([0, 0, 1, 2])):
            kinds = ["area", "point", "spot", "directional"] + ([] if self.has_environment else ["constant"])
            kinds += [kind for kind in extra if kind == "projector" or not self.has_environment]
            kinds += ["directionalarea"] if directional_area else []
            kinds = [k for k in kinds if k not in delta]
            if kinds:
                emitters.append(self.light(self.r.choice(kinds), False))
        return emitters

    # Camera, film, sampler, integrator.
    def sensor(self):
        width, height = self.r.choice([(32, 24), (24, 32)])
        distance = self.uniform(4.0, 6.5)
        azimuth, elevation = self.uniform(0, 2 * math.pi), math.radians(self.uniform(15, 50))
        origin = [distance * math.cos(elevation) * math.cos(azimuth),
                  distance * math.cos(elevation) * math.sin(azimuth),
                  distance * math.sin(elevation)]
        target = [self.uniform(-0.3, 0.3), self.uniform(-0.3, 0.3), self.uniform(0.2, 0.6)]
        view = lookat(origin, target, [0, 0, 1])
        # caustic's light tracing (ptracer, ibpt) has no orthographic camera.
        kinds = ["perspective", "perspective", "thinlens"]
        kinds += [] if self.light_tracing or self.ibpt else ["orthographic"]
        kind = self.r.choice(kinds)
        children = []
        if kind == "orthographic":
            half = self.uniform(2.0, 3.5)
            children.append(to_world(f'<scale x="{num(half)}" y="{num(half)}"/>', view))
            lens = f"half-width={num(half)}"
        else:
            children.append(to_world(view))
            choice = self.r.random()
            if choice < 0.6:
                fov = self.uniform(30, 60)
                axis = self.r.choice([None, "x", "y", "diagonal", "smaller", "larger"])
                children.append(flt("fov", fov))
                if axis:
                    children.append(string("fov_axis", axis))
                lens = f"fov={num(fov)}" + (f"/{axis}" if axis else "")
            elif choice < 0.8:
                focal = self.r.randint(28, 70)
                children.append(string("focal_length", f"{focal}mm"))
                lens = f"{focal}mm"
            else:
                lens = "default-lens"
            if kind == "thinlens":
                aperture = self.uniform(0.01, 0.15)
                focus = math.dist(origin, target) * self.uniform(0.8, 1.2)
                children += [flt("aperture_radius", aperture), flt("focus_distance", focus)]
                lens += f",aperture={num(aperture)}"
            # Not under ptracer: Mitsuba 3.9.1's perspective importance() tests the unshifted image
            # rectangle, so its light tracer loses a band of the shifted image.
            if (kind == "perspective" and self.has("principal-point") and not self.light_tracing
                    and self.r.random() < 0.3):
                x, y = self.uniform(-0.2, 0.2), self.uniform(-0.2, 0.2)
                children += [flt("principal_point_offset_x", x), flt("principal_point_offset_y", y)]
                lens += f",offset={num(x)}/{num(y)}"
        rfilter = self.r.choice(["box", "tent", "gaussian"])
        if self.has("filters") and self.r.random() < 0.3:
            rfilter = self.r.choice(["mitchell", "catmullrom", "lanczos"])
        if self.light_tracing:
            # Mitsuba's light tracer drops the part of a splat's filter that falls off the image (its
            # border pixels render darker than its path tracer's); caustic's renormalises it.
            rfilter = "box"
        filter_children = []
        if rfilter == "gaussian" and self.r.random() < 0.5:
            filter_children.append(flt("stddev", self.uniform(0.3, 0.8)))
        if rfilter == "mitchell" and self.r.random() < 0.5:
            filter_children += [flt("B", self.uniform(0, 1)), flt("C", self.uniform(0, 1))]
        if rfilter == "lanczos" and self.r.random() < 0.5:
            filter_children.append(integer("lobes", self.r.choice([2, 4])))
        sampler_kind = self.r.choice(["independent", "independent", "stratified"])
        if self.has("samplers") and self.r.random() < 0.3:
            sampler_kind = self.r.choice(["multijitter", "orthogonal", "ldsampler"])
        if self.light_tracing:
            # Mitsuba 3.9.1's ptracer never ends where its sampler rounds the sample count (stratified
            # at 512 spp: 529).
            sampler_kind = "independent"
        sampler = element("sampler", sampler_kind, [integer("sample_count", 16)])
        # A radiance or irradiance meter (feature "meters"): one pixel, the box filter (Mitsuba advises
        # a filter no wider). Not under light tracing (caustic refuses them there) nor depth.
        if (self.has("meters") and not (self.light_tracing or self.ibpt) and self.integrator_kind != "depth"
                and self.r.random() < 0.12):
            meter = self.r.choice(["radiancemeter", "irradiancemeter"])
            film = element("film", "hdrfilm", [integer("width", 1), integer("height", 1),
                                               element("rfilter", "box", [])])
            self.parts.insert(0, f"{meter} 1x1 box {sampler_kind}")
            if meter == "irradiancemeter":
                # Nested in an object or (where none takes it) the floor: see place_objects and xml.
                self.meter = element("sensor", meter, [film, sampler])
                self.meter_on_object = self.r.random() < 0.5
                return ""
            aim = [t + self.uniform(-0.5, 0.5) for t in target]
            direction = [a - o for a, o in zip(aim, origin)]
            return element("sensor", meter, [point("origin", origin),
                                              f'<vector name="direction" value="{vec(direction)}"/>', film, sampler])
        film_children = [integer("width", width), integer("height", height)]
        if self.has("clip-crop"):
            if self.r.random() < 0.3:
                # The near plane sometimes cuts into the objects; the far plane sometimes cuts off the
                # floor. No far plane under ptracer: Mitsuba 3.9.1's light tracer connects an
                # environment to the camera from a point the far plane cuts off (a constant sky behind
                # a far_clip of 4 rendered black there, white in its path tracer). Nor a near plane
                # that cuts an object under ptracer: Mitsuba 3.9.1's light tracer tests a connection's
                # whole segment to the lens, so what the plane cuts off still hides what lies behind
                # it, where camera rays (its path tracer's, every caustic integrator's) see past it
                # (seed 404's clipped cylinder under ibpt, against `path`). The camera stands 4 or
                # more from the origin and no object reaches 2.8 from it.
                near = self.uniform(0.01, min(1.0, distance - 1.0) if self.light_tracing else distance - 1.0)
                children.append(flt("near_clip", near))
                lens += f",near={num(near)}"
                if not self.light_tracing and self.r.random() < 0.5:
                    far = self.uniform(max(near + 0.5, distance - 1.0), distance + 4.0)
                    children.append(flt("far_clip", far))
                    lens += f",far={num(far)}"
            if self.r.random() < 0.25:
                crop_width, crop_height = self.r.randint(4, width), self.r.randint(4, height)
                x, y = self.r.randint(0, width - crop_width), self.r.randint(0, height - crop_height)
                film_children += [integer("crop_offset_x", x), integer("crop_offset_y", y),
                                  integer("crop_width", crop_width), integer("crop_height", crop_height)]
                lens += f",crop={crop_width}x{crop_height}+{x}+{y}"
        film = element("film", "hdrfilm", film_children + [element("rfilter", rfilter, filter_children)])
        self.parts.insert(0, f"{kind}({lens}) {width}x{height} {rfilter} {sampler_kind}")
        return element("sensor", kind, children + [film, sampler])

    def depths(self, children, notes):
        depth = self.r.choice([2, 3, 4, 5, 6, 7, 8, -1])
        children.append(integer("max_depth", depth))
        notes.append(f"depth={depth}")
        if self.r.random() < 0.3:
            rr = self.r.randint(1, 6)
            children.append(integer("rr_depth", rr))
            notes.append(f"rr={rr}")

    def integrator(self):
        children = []
        notes = []
        if self.has("depth") and self.r.random() < 0.04:
            # The distance to the first hit (feature "depth"): no other parameter.
            self.parts.insert(0, "depth")
            self.integrator_kind, self.integrator_children, self.integrator_notes = "depth", [], []
            return self.integrator_element()
        if self.has("ptracer") and self.r.random() < 0.15:
            kind = "ptracer"
            self.light_tracing = True
            self.depths(children, notes)
            self.clear_panes = self.has("thindielectric") and self.r.random() < 0.5
        elif self.r.random() < 0.75:
            kind = "path"
            # caustic's ibpt and Mitsuba's prb family, compared with Mitsuba's path (reference_integrator).
            if self.has("ibpt") and self.r.random() < 0.15:
                kind = "ibpt"
                self.ibpt = True
            elif self.has("prb") and self.r.random() < 0.1:
                kind = self.r.choice(["prb", "prb_basic", "prb_projective"])
            self.depths(children, notes)
            if kind.startswith("prb") and self.r.random() < 0.3:
                children.pop(0)  # max_depth: the prb family's default, 6
                notes[0] = "depth=default"
        else:
            # One emitter and one BSDF sample: Mitsuba's `direct` is known to differ from caustic's
            # with more emitter samples and delta emitters (it weighs each sample of a delta light 1,
            # not 1/emitter_samples). Feature "direct-samples": other counts, drawn in `xml` once the
            # lights are known.
            kind = "direct"
            if self.has("direct-samples") and self.r.random() < 0.5:
                self.direct_counts = True
            else:
                children += [integer("emitter_samples", 1), integer("bsdf_samples", 1)]
        if self.r.random() < 0.15:
            children.append(boolean("hide_emitters", True))
            notes.append("hide_emitters")
            # Mitsuba's path renders the reference of ibpt and the prb family.
            self.path_hides_emitters = kind == "path" or kind == "ibpt" or kind.startswith("prb")
            self.hides_emitters = True
        self.moment = self.has("moment") and kind in ("path", "direct") and self.r.random() < 0.1
        self.integrator_kind, self.integrator_children, self.integrator_notes = kind, children, notes
        self.parts.insert(0, self.integrator_text())
        return self.integrator_element()

    def integrator_text(self):
        kind, notes = self.integrator_kind, self.integrator_notes
        text = f"{kind}({','.join(notes)})" if notes else kind
        return f"moment[{text}]" if self.moment else text

    def integrator_element(self, kind=None, children=None):
        """The scene's integrator (or `kind` with `children`), inside a `moment` where the scene's is."""
        xml = element("integrator", kind or self.integrator_kind,
                      self.integrator_children if children is None else children)
        return element("integrator", "moment", [xml]) if self.moment else xml

    def direct_sample_counts(self):
        """Feature "direct-samples": direct's shading_samples, or emitter_samples and bsdf_samples (not
        both 0); more than one emitter sample only where no light is a delta light (Mitsuba 3.9.1
        weighs each sample of one 1, not 1/emitter_samples: the light comes out that many times), and
        none only where none is (with no emitter sample a delta light renders black, while the
        `volpath` reference of a scene with null interfaces lights it: seeds 326 and 374); at least
        one BSDF sample under that reference."""
        most = 1 if self.delta_lights else 4
        if most > 1 and self.r.random() < 0.3:
            n = self.r.randint(1, most)
            return [integer("shading_samples", n)], [f"shading_samples={n}"]
        emitter_samples = self.r.randint(1 if self.delta_lights else 0, most)
        # No BSDF sample only where Mitsuba's `direct` is the reference: with none, light reflected
        # by a Dirac BSDF (a thin pane's or a conductor's) does not reach the camera, which the
        # `volpath` reference of a scene with null interfaces renders (seed 427: 98.1% of pixels
        # passing with none, all with one).
        bsdf_samples = self.r.randint(0 if emitter_samples and not self.null_interfaces else 1, 4)
        return ([integer("emitter_samples", emitter_samples), integer("bsdf_samples", bsdf_samples)],
                [f"emitter_samples={emitter_samples}", f"bsdf_samples={bsdf_samples}"])

    def reference_integrator(self):
        """The integrator of Mitsuba's reference, where it is not the scene's: caustic renders masks,
        `null` and thin dielectrics' transmission as null interfaces under every integrator (a
        crossing is no bounce; shadow rays and camera connections are attenuated through them), as
        Mitsuba's `volpath` renders them and its `path`, `direct` and `ptracer` do not. So with any of
        them in the scene, `path` and `ptracer` are compared with `volpath` at the same max_depth,
        rr_depth and hide_emitters, and `direct` with `volpath` at max_depth 2 (its estimand, as in
        tests/tests/mask.rs and thin_null.rs). caustic's `ibpt` and the `prb` family (which Mitsuba's
        scalar variants do not have) are compared with Mitsuba's `path` (a prb's absent max_depth: 6),
        or `volpath` as above. Inside a `moment` where the scene's is. None where it is the scene's."""
        kind, children = self.integrator_kind, self.integrator_children
        if kind == "depth":
            return None
        if kind.startswith("prb") and not any('name="max_depth"' in child for child in children):
            children = [integer("max_depth", 6)] + children
        if self.null_interfaces:
            if kind == "direct":
                children = [integer("max_depth", 2)] + ([boolean("hide_emitters", True)] if self.hides_emitters else [])
            return self.integrator_element("volpath", children)
        if kind == "ibpt" or kind.startswith("prb"):
            return self.integrator_element("path", children)
        return None

    def xml(self):
        """The scene's XML, and Mitsuba's (None where it is the same: see `reference_integrator`)."""
        integrator = self.integrator()
        sensor = self.sensor()
        floor = self.floor()
        shapes = self.place_objects()
        emitters = self.lights()
        if self.direct_counts:
            counts, notes = self.direct_sample_counts()
            self.integrator_children = counts + self.integrator_children
            self.integrator_notes = notes + self.integrator_notes
            self.parts[1] = self.integrator_text()  # after the sensor's
            integrator = self.integrator_element()
        if self.meter:  # an irradiancemeter that no object took: the floor's
            floor = floor[:-len("</shape>")] + self.meter + "</shape>"
            self.meter = None
            at = next(i for i, part in enumerate(self.parts) if part.startswith("floor:"))
            self.parts[at] = self.parts[at].replace("floor:", "floor(irradiancemeter):", 1)
        rest = [part for part in [sensor, floor] + self.definitions + shapes + emitters if part]

        def scene(integrator):
            body = "\n    ".join([integrator] + rest)
            return f'<scene version="3.0.0">\n    {body}\n</scene>\n'
        reference = self.reference_integrator()
        return scene(integrator), scene(reference) if reference else None

    @property
    def description(self):
        return " | ".join(self.parts)


def make_scene(seed, features=frozenset(EXTENDED)):
    """Seed `seed`'s scene: caustic's XML, Mitsuba's (None where the same), the description."""
    maker = SceneMaker(seed, features)
    xml, reference_xml = maker.xml()
    return xml, reference_xml, maker.description


# --- Rendering and comparing ---------------------------------------------------------------------

def write_exr(path, pixels):
    mi.Bitmap(np.ascontiguousarray(pixels, dtype=np.float32)).write(path)


def read_exr(path):
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


RENDER_THREADS = [2]  # Mitsuba's threads while it renders (--threads)


def render_mitsuba(xml_path, spp, batches, first_seed):
    """Mitsuba's image at `spp` samples per pixel: the mean of `batches` renders with seeds
    first_seed, first_seed + 1, ..., and the variance of that mean from their spread (None for one
    batch)."""
    scene = mi.load_file(xml_path)
    per_batch = max(1, spp // batches)
    # Mitsuba 3.9.1 reads and writes EXRs (scene textures, images) through its thread pool and
    # deadlocks where that has one thread: one only while it renders (see main).
    dr.set_thread_count(RENDER_THREADS[0])
    try:
        images = np.array([np.array(mi.render(scene, spp=per_batch, seed=first_seed + i))[..., :3]
                           for i in range(batches)], dtype=np.float64)
    finally:
        dr.set_thread_count(max(2, RENDER_THREADS[0]))
    variance = images.var(axis=0, ddof=1) / batches if batches > 1 else None
    return images.mean(axis=0), variance


BACKEND = ["cpu"]  # caustic's backend (--backend)
TIMEOUT = [None]  # seconds a caustic render may take (--timeout)


def render_caustic(binary, xml_path, exr_path, spp, seed, env):
    command = [binary, "render", xml_path, "--backend", BACKEND[0], "--spp", str(spp), "--seed", str(seed),
               "--strict", "--variance", "-q", "-o", exr_path]
    try:
        out = subprocess.run(command, capture_output=True, text=True, env=env, timeout=TIMEOUT[0])
    except subprocess.TimeoutExpired:
        raise RuntimeError(f"caustic render ran past --timeout {TIMEOUT[0]} s and was stopped")
    if out.returncode != 0:
        raise RuntimeError(f"caustic render failed (exit {out.returncode}): "
                           + (out.stderr.strip() or out.stdout.strip()))


def caustic_compare(binary, image, reference, error_image, env, spp=None):
    """`caustic compare`'s pass fraction and mean-luminance z; `spp` = (image's, reference's)."""
    command = [binary, "compare", image, reference, "--error-image", error_image]
    if spp:
        command += ["--image-spp", str(spp[0]), "--reference-spp", str(spp[1])]
    out = subprocess.run(command, capture_output=True, text=True, env=env)
    if out.returncode != 0:
        raise RuntimeError(f"caustic compare failed (exit {out.returncode}): "
                           + (out.stderr.strip() or out.stdout.strip()))
    fraction = re.search(r"pass fraction\s+([0-9.]+)", out.stdout)
    z = re.search(r"mean luminance z\s+(\S+)", out.stdout)
    if not fraction or not z:
        raise RuntimeError("unexpected compare output:\n" + out.stdout)
    return float(fraction.group(1)), float(z.group(1))


def render_and_compare(binary, xml_paths, stem, spp, reference_spp, batches, seeds, env):
    """Renders the scene with both renderers and compares them: (pass fraction, luminance z, the
    reference's mean, the files written). `xml_paths` = (caustic's scene, Mitsuba's); `seeds` =
    (caustic's seed, Mitsuba's first seed)."""
    xml_path, reference_xml_path = xml_paths
    files = {name: f"{stem}-{name}" for name in
             ["mitsuba.exr", "mitsuba.variance.exr", "caustic.exr", "caustic.variance.exr",
              "test.exr", "test.variance.exr", "error.png"]}
    reference, reference_variance = render_mitsuba(reference_xml_path, reference_spp, batches, seeds[1])
    write_exr(files["mitsuba.exr"], reference)
    render_caustic(binary, xml_path, files["caustic.exr"], spp, seeds[0], env)
    if reference_variance is None:
        # compare estimates the reference's variance from caustic's and the spp ratio.
        for name in ["mitsuba.variance.exr", "test.exr", "test.variance.exr"]:
            del files[name]
        result = caustic_compare(binary, files["caustic.exr"], files["mitsuba.exr"], files["error.png"], env,
                                 spp=(spp, reference_spp))
        return result + (reference, list(files.values()))
    # The reference's variance from its batches, which (unlike compare's estimate from caustic's
    # variance and the spp ratio) grows where the reference met a rare bright path; the larger of
    # the two is added to caustic's variance beside a copy of its image, which compare then tests.
    write_exr(files["mitsuba.variance.exr"], reference_variance)
    variance = read_exr(files["caustic.variance.exr"])
    combined = variance + np.maximum(reference_variance, variance * spp / reference_spp)
    write_exr(files["test.exr"], read_exr(files["caustic.exr"]))
    write_exr(files["test.variance.exr"], combined)
    result = caustic_compare(binary, files["test.exr"], files["mitsuba.exr"], files["error.png"], env)
    return result + (reference, list(files.values()))


def passes(fraction, z):
    return fraction >= MIN_PASS_FRACTION and abs(z) < MAX_LUMINANCE_Z


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        if "-" in part:
            first, last = part.split("-")
            seeds += range(int(first), int(last) + 1)
        else:
            seeds.append(int(part))
    return seeds


def remove(paths):
    for path in paths:
        if os.path.exists(path):
            os.remove(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="extended kinds (--without):\n" +
                                        "\n".join(f"  {kind:17} {what}" for kind, what in EXTENDED.items()))
    ap.add_argument("--seeds", default="0-29", help="seeds to test: a range 0-29, a list 1,5,9, or both")
    ap.add_argument("--spp", type=int, default=256, help="caustic's samples per pixel")
    ap.add_argument("--ref-factor", type=int, default=16, help="Mitsuba's spp as a multiple of caustic's")
    ap.add_argument("--out", default="/tmp/random-scenes", help="where failing scenes are saved")
    ap.add_argument("--keep", action="store_true", help="save every scene, not only the failing ones")
    ap.add_argument("--caustic", default="target/release/caustic", help="the caustic binary")
    ap.add_argument("--ref-batches", type=int, default=8,
                    help="Mitsuba renders its reference in this many batches, whose spread gives its "
                         "variance (1: one render; compare estimates it from caustic's and the spp ratio)")
    ap.add_argument("--recheck", type=int, default=4,
                    help="render a failing scene again at this multiple of --spp (0: don't)")
    ap.add_argument("--threads", type=int, default=2, help="threads for each renderer")
    ap.add_argument("--variant", default="scalar_rgb",
                    help="Mitsuba's variant for the references (llvm_ad_rgb evaluates the filter exactly, "
                         "as caustic does; the scalar variants read it from a 31-bin table, which a "
                         "sharp highlight under a wide gaussian shows at 1024 spp: seed 296; it needs "
                         "DRJIT_LIBLLVM_PATH where Debian keeps libLLVM)")
    ap.add_argument("--backend", default="cpu", choices=["cpu", "gpu"],
                    help="caustic's backend (gpu: the kernel's SPIR-V, on lavapipe where no GPU is)")
    ap.add_argument("--timeout", type=float, default=None,
                    help="seconds a caustic render may take before it is stopped and the seed reported "
                         "(lavapipe has taken over 12 minutes and 8 GB to compile the largest modules)")
    ap.add_argument("--extended", action=argparse.BooleanOptionalAction, default=True,
                    help="add the extended kinds of scene element (--no-extended: the original generator, "
                         "whose seeds make the scenes they made before)")
    ap.add_argument("--without", default="", metavar="KIND,...",
                    help="extended kinds to leave out (listed below)")
    args = ap.parse_args()
    without = {kind for kind in args.without.split(",") if kind}
    if without - EXTENDED.keys():
        sys.exit(f"--without: unknown kinds {', '.join(sorted(without - EXTENDED.keys()))} "
                 f"(known: {', '.join(EXTENDED)})")
    features = frozenset(EXTENDED.keys() - without) if args.extended else frozenset()

    if not os.access(args.caustic, os.X_OK):
        sys.exit(f"no caustic binary at {args.caustic} (cargo build --release, or --caustic)")
    binary = os.path.abspath(args.caustic)
    os.makedirs(args.out, exist_ok=True)
    RENDER_THREADS[0] = args.threads
    mi.set_variant(args.variant)
    BACKEND[0] = args.backend
    TIMEOUT[0] = args.timeout
    dr.set_thread_count(max(2, args.threads))  # 1 only while rendering: see render_mitsuba
    env = dict(os.environ, RAYON_NUM_THREADS=str(args.threads))
    reference_spp = args.spp * args.ref_factor
    print(f"caustic {args.spp} spp ({args.backend}) against Mitsuba {mi.__version__} {args.variant} {reference_spp} spp; "
          f"pass: fraction >= {MIN_PASS_FRACTION} and |z| < {MAX_LUMINANCE_Z}", flush=True)
    print("generator: " + ("original (--no-extended)" if not features else "extended" +
          (f" without {', '.join(sorted(without))}" if without else "")), flush=True)
    print(f"{'seed':>4} {'pass':>7} {'lum z':>7} verdict {'secs':>5}  scene", flush=True)

    failures = []
    seeds = parse_seeds(args.seeds)
    for seed in seeds:
        xml, reference_xml, description = make_scene(seed, features)
        stem = os.path.join(args.out, f"seed-{seed:04d}")
        xml_path = stem + ".xml"
        with open(xml_path, "w") as f:
            f.write(f"<!-- random-scenes.py seed {seed}: {description} -->\n{xml}")
        scene_files = [xml_path]
        if reference_xml:  # Mitsuba renders with volpath (null interfaces) or path (ibpt, prb)
            description += " | ref=" + ("volpath" if '"volpath"' in reference_xml else "path")
            scene_files.append(stem + "-reference.xml")
            with open(scene_files[1], "w") as f:
                f.write(f"<!-- random-scenes.py seed {seed}, Mitsuba's reference: {description} -->\n"
                        f"{reference_xml}")
        xml_paths = (xml_path, scene_files[-1])
        start = time.time()
        fraction, z, note, files = float("nan"), float("nan"), "", []
        try:
            fraction, z, reference, files = render_and_compare(
                binary, xml_paths, stem, args.spp, reference_spp, args.ref_batches, (seed, 1), env)
            if reference.mean() < 1e-3:
                note = "  (reference nearly black)"
            verdict = "ok" if passes(fraction, z) else "FAIL"
            if verdict == "FAIL" and args.recheck > 1:
                # Heavy-tailed noise (rare bright paths, such as caustics, that neither render
                # samples often enough) fails the z-test at a low spp and passes at a higher one;
                # a bias does not. Both renders again, more samples, other seeds.
                spp = args.spp * args.recheck
                f, zz, _, more = render_and_compare(binary, xml_paths, stem + "-recheck", spp,
                                                    reference_spp * args.recheck, args.ref_batches,
                                                    (seed + 1_000_000, 1_000_000), env)
                files += more
                note += f"  [recheck at {spp} spp: {f:.4f} {zz:+.2f}]"
                if passes(f, zz):
                    verdict = "noisy"
        except Exception as e:  # a refused scene is a failure too: the generator only uses supported plugins
            verdict = "ERROR"
            note = "  " + str(e).strip().splitlines()[0]
        seconds = time.time() - start
        print(f"{seed:>4} {fraction:7.4f} {z:+7.2f} {verdict:<7} {seconds:5.1f}  {description}{note}",
              flush=True)
        if verdict == "ok":
            if not args.keep:
                remove(scene_files + files)
        else:
            failures.append((seed, verdict, description, xml_path))

    passed = len(seeds) - len(failures)
    print(f"\n{passed} of {len(seeds)} scenes passed "
          f"(pass fraction >= {MIN_PASS_FRACTION} and |z| < {MAX_LUMINANCE_Z})")
    noisy = sum(verdict == "noisy" for _, verdict, _, _ in failures)
    if noisy:
        print(f"{noisy} of the {len(failures)} failures passed at {args.recheck}x spp "
              "(noisy: heavy-tailed noise, most likely)")
    for seed, verdict, description, path in failures:
        print(f"  seed {seed} {verdict}: {path}\n      {description}")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
