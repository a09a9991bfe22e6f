#!/usr/bin/env python3
"""Writes mitsuba_defaults.json: what Mitsuba 3.9.1 makes of one-element scenes that leave most
parameters at their defaults, against which tests/tests/mitsuba_defaults.rs checks caustic's loader.

    python3 -m venv /tmp/mi-venv && /tmp/mi-venv/bin/pip install mitsuba==3.9.1
    /tmp/mi-venv/bin/python tests/data/mitsuba_defaults.py           # rewrite the file
    /tmp/mi-venv/bin/python tests/data/mitsuba_defaults.py --check   # compare, write nothing

(The `scalar_rgb` variant needs nothing beyond the wheel.)

Each case is a small scene (the XML is written into the JSON, so that the Rust test loads exactly
what Mitsuba loaded) and the values Mitsuba computes from it, under keys the Rust test knows:
  - sensors: `rays`, primary rays for film positions (fractions of the crop window) and aperture
    samples: the ray's first point (Mitsuba starts it on the near clip plane), its direction and its
    last point (on the far clip plane); `film_size`, `crop_size`, `crop_offset`; `filter` and
    `filter_radius` of the film's rfilter and `filter_weights`, its weights at FILTER_POINTS; `sample_count` of the sampler (after the sampler's own
    rounding: stratified and orthogonal to squares, ldsampler to powers of four, multijitter to a
    near-square grid);
  - integrators: `max_depth` (-1 unbounded), `rr_depth`, `emitter_samples`, `bsdf_samples`;
  - emitters: `position`, `intensity`, `cutoff_angle`, `beam_width`, `direction`, `irradiance`,
    `radiance` (RGB, or one number for Mitsuba's uniform spectra);
  - BSDFs (on a sphere): `eta` (relative IOR), `alpha_u`, `alpha_v`, `distribution`, `conductor_eta`,
    `conductor_k`, `reflectance`, `specular_reflectance`, `nonlinear`, `two_sided`;
  - shapes: `bbox_min`, `bbox_max`, `surface_area`, `vertex_normals` (meshes: whether shading normals
    are interpolated), `radiance` of an attached area emitter.
  - errors: `error` is true when Mitsuba refuses the scene.
Values are Mitsuba's float32 results written with 9 significant digits. `--check` reloads every case
and reports any key whose value moved by more than 1e-6 relative.
"""
import argparse
import json
import math
import os
import re
import sys
import tempfile

import mitsuba as mi

mi.set_variant("scalar_rgb")

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "mitsuba_defaults.json")

FILM_POINTS = [[0.5, 0.5], [0.0, 0.0], [1.0, 1.0], [0.2, 0.7]]
LENS_POINTS = [[0.5, 0.5], [0.9, 0.3]]

# A bent quad (two triangles sharing an edge, not coplanar): its vertex normals are not face normals.
BENT_OBJ = """v 0 0 0
v 1 0 0
v 1 1 0.5
v 0 1 0
f 1 2 3
f 1 3 4
"""


def film(w=None, h=None, extra=""):
    body = ""
    if w is not None:
        body += f'<integer name="width" value="{w}"/><integer name="height" value="{h}"/>'
    return f'<film type="hdrfilm">{body}{extra}</film>'


# Spectra in Mitsuba's .spd format (`wavelength value` per line, `#` comments) for the
# `<spectrum filename=...>` cases: made-up but smooth, over and beyond the visible range.
SPD_FILES = {
    "eta.spd": "# eta\n360 0.3\n450 0.45\n550 0.9\n650 1.3\n830 1.8\n",
    "k.spd": "360 1.8\n450 2.4\n550 3.1\n650 3.9\n830 5.0\n",
    "refl.spd": "# a reflectance\n380 0.1\n480 0.25\n530 0.6\n600 0.4\n700 0.8\n780 0.7\n",
}
FILES = {"bent.obj": BENT_OBJ, **SPD_FILES}

LOOKAT = '<transform name="to_world"><lookat origin="1, 2, 3" target="0, 0.5, 0" up="0, 1, 0"/></transform>'


def sensor_cases():
    cases = [
        ("sensor_default", '<sensor type="perspective"/>'),
        ("sensor_focal_square", f'<sensor type="perspective">{LOOKAT}{film(256, 256)}</sensor>'),
        ("sensor_focal_tall", f'<sensor type="perspective">{film(200, 400)}</sensor>'),
        ("sensor_focal_35mm",
         f'<sensor type="perspective"><string name="focal_length" value="35mm"/>{film(300, 200)}</sensor>'),
        ("sensor_focal_plain_number",
         f'<sensor type="perspective"><string name="focal_length" value="24"/>{film(300, 200)}</sensor>'),
        ("sensor_fov_default_axis", f'<sensor type="perspective"><float name="fov" value="40"/>{film(300, 200)}</sensor>'),
    ]
    for axis in ["x", "y", "diagonal", "smaller", "larger", "Y"]:
        for w, h in [(300, 200), (200, 300)]:
            cases.append((f"sensor_fov_axis_{axis}_{w}x{h}",
                          f'<sensor type="perspective"><float name="fov" value="40"/>'
                          f'<string name="fov_axis" value="{axis}"/>{LOOKAT}{film(w, h)}</sensor>'))
    cases += [
        ("sensor_clip",
         f'<sensor type="perspective"><float name="near_clip" value="0.5"/><float name="far_clip" value="20"/>{film(64, 48)}</sensor>'),
        ("sensor_crop",
         f'<sensor type="perspective"><float name="fov" value="30"/>'
         + film(64, 48, '<integer name="crop_offset_x" value="10"/><integer name="crop_offset_y" value="4"/>'
                '<integer name="crop_width" value="20"/><integer name="crop_height" value="30"/>')
         + '</sensor>'),
        ("sensor_principal_point",
         '<sensor type="perspective"><float name="principal_point_offset_x" value="0.1"/>'
         f'<float name="principal_point_offset_y" value="-0.2"/>{LOOKAT}{film(64, 48)}</sensor>'),
        ("sensor_principal_point_crop",
         '<sensor type="perspective"><float name="fov" value="30"/><float name="principal_point_offset_x" value="-0.15"/>'
         '<float name="principal_point_offset_y" value="0.05"/>'
         + film(64, 48, '<integer name="crop_offset_x" value="10"/><integer name="crop_offset_y" value="4"/>'
                '<integer name="crop_width" value="20"/><integer name="crop_height" value="30"/>')
         + '</sensor>'),
        ("sensor_crop_offset_only",
         '<sensor type="perspective">' + film(64, 48, '<integer name="crop_offset_x" value="0"/>') + '</sensor>'),
        ("sensor_thinlens_default_focus",
         f'<sensor type="thinlens"><float name="aperture_radius" value="0.1"/>{LOOKAT}{film(80, 60)}</sensor>'),
        ("sensor_thinlens_focus",
         '<sensor type="thinlens"><float name="aperture_radius" value="0.25"/><float name="focus_distance" value="3"/>'
         f'<float name="fov" value="50"/><string name="fov_axis" value="smaller"/>{film(60, 80)}</sensor>'),
        ("sensor_orthographic_default", '<sensor type="orthographic"/>'),
        ("sensor_orthographic_scaled",
         '<sensor type="orthographic"><transform name="to_world"><scale x="2" y="3"/>'
         '<lookat origin="0, 0, -5" target="0, 0, 0" up="0, 1, 0"/></transform>' + film(40, 20) + '</sensor>'),
    ]
    for f in ["box", "tent", "gaussian", "mitchell", "catmullrom", "lanczos"]:
        cases.append((f"filter_{f}_default", f'<sensor type="perspective"><film type="hdrfilm"><rfilter type="{f}"/></film></sensor>'))
    cases += [
        ("filter_tent_radius",
         '<sensor type="perspective"><film type="hdrfilm"><rfilter type="tent"><float name="radius" value="1.5"/></rfilter></film></sensor>'),
        ("filter_gaussian_stddev",
         '<sensor type="perspective"><film type="hdrfilm"><rfilter type="gaussian"><float name="stddev" value="0.3"/></rfilter></film></sensor>'),
        ("filter_mitchell_b_c",
         '<sensor type="perspective"><film type="hdrfilm"><rfilter type="mitchell"><float name="B" value="0.2"/>'
         '<float name="C" value="0.6"/></rfilter></film></sensor>'),
        ("filter_lanczos_lobes",
         '<sensor type="perspective"><film type="hdrfilm"><rfilter type="lanczos"><integer name="lobes" value="2"/></rfilter></film></sensor>'),
    ]
    for s in ["independent", "stratified", "multijitter", "orthogonal", "ldsampler"]:
        cases.append((f"sampler_{s}_default", f'<sensor type="perspective"><sampler type="{s}"/></sensor>'))
        for n in [5, 17, 64]:
            cases.append((f"sampler_{s}_{n}",
                          f'<sensor type="perspective"><sampler type="{s}"><integer name="sample_count" value="{n}"/></sampler></sensor>'))
    return cases


def integrator_cases():
    return [
        ("integrator_path_default", '<integrator type="path"/>'),
        ("integrator_path_depths",
         '<integrator type="path"><integer name="max_depth" value="7"/><integer name="rr_depth" value="3"/></integrator>'),
        ("integrator_direct_default", '<integrator type="direct"/>'),
        ("integrator_direct_shading", '<integrator type="direct"><integer name="shading_samples" value="3"/></integrator>'),
        ("integrator_direct_split",
         '<integrator type="direct"><integer name="emitter_samples" value="2"/><integer name="bsdf_samples" value="0"/></integrator>'),
        ("integrator_ptracer_default", '<integrator type="ptracer"/>'),
    ]


def emitter_cases():
    return [
        ("emitter_point_default", '<emitter type="point"/>'),
        ("emitter_point_position", '<emitter type="point"><point name="position" value="1, 2, 3"/><rgb name="intensity" value="2, 3, 4"/></emitter>'),
        ("emitter_point_to_world", '<emitter type="point"><transform name="to_world"><translate value="4, 5, 6"/></transform></emitter>'),
        ("emitter_spot_default", '<emitter type="spot"/>'),
        ("emitter_spot_cutoff", '<emitter type="spot"><float name="cutoff_angle" value="30"/></emitter>'),
        ("emitter_spot_both",
         '<emitter type="spot"><float name="cutoff_angle" value="30"/><float name="beam_width" value="10"/>'
         '<transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0" up="0, 0, 1"/></transform></emitter>'),
        ("emitter_directional_default", '<emitter type="directional"/>'),
        ("emitter_directional_direction",
         '<emitter type="directional"><vector name="direction" value="1, -2, 0.5"/><rgb name="irradiance" value="3, 2, 1"/></emitter>'),
        ("emitter_directional_to_world",
         '<emitter type="directional"><transform name="to_world"><rotate x="1" angle="30"/></transform></emitter>'),
        ("emitter_constant_default", '<emitter type="constant"/>'),
        ("emitter_area_default", '<shape type="sphere"><emitter type="area"/></shape>'),
    ]


def bsdf_cases():
    bsdfs = [
        ("diffuse_default", '<bsdf type="diffuse"/>'),
        ("dielectric_default", '<bsdf type="dielectric"/>'),
        ("dielectric_named", '<bsdf type="dielectric"><string name="int_ior" value="diamond"/><string name="ext_ior" value="water"/></bsdf>'),
        ("dielectric_numbers", '<bsdf type="dielectric"><float name="int_ior" value="1.33"/><float name="ext_ior" value="1.1"/></bsdf>'),
        ("thindielectric_default", '<bsdf type="thindielectric"/>'),
        ("roughdielectric_default", '<bsdf type="roughdielectric"/>'),
        ("roughdielectric_ggx_aniso",
         '<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.3"/></bsdf>'),
        ("conductor_default", '<bsdf type="conductor"/>'),
        ("conductor_eta_only", '<bsdf type="conductor"><rgb name="eta" value="0.2, 0.9, 1.1"/></bsdf>'),
        ("conductor_spectrum_files",
         '<bsdf type="conductor"><spectrum name="eta" filename="eta.spd"/><spectrum name="k" filename="k.spd"/></bsdf>'),
        ("diffuse_spectrum_file", '<bsdf type="diffuse"><spectrum name="reflectance" filename="refl.spd"/></bsdf>'),
        ("roughconductor_default", '<bsdf type="roughconductor"/>'),
        ("roughconductor_ggx", '<bsdf type="roughconductor"><string name="distribution" value="GGX"/><float name="alpha" value="0.3"/></bsdf>'),
        ("plastic_default", '<bsdf type="plastic"/>'),
        ("plastic_nonlinear", '<bsdf type="plastic"><boolean name="nonlinear" value="true"/><float name="int_ior" value="1.9"/></bsdf>'),
        ("roughplastic_default", '<bsdf type="roughplastic"/>'),
        ("roughplastic_ggx", '<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf>'),
        ("twosided_default", '<bsdf type="twosided"><bsdf type="diffuse"/></bsdf>'),
        ("twosided_conductor", '<bsdf type="twosided"><bsdf type="roughconductor"/></bsdf>'),
    ]
    return [(f"bsdf_{n}", f'<shape type="sphere">{b}</shape>') for n, b in bsdfs]


def shape_cases():
    return [
        ("shape_sphere_default", '<shape type="sphere"/>'),
        ("shape_sphere_center_to_world",
         '<shape type="sphere"><point name="center" value="1, 0, 0"/><float name="radius" value="0.5"/>'
         '<transform name="to_world"><scale value="2"/><translate value="0, 1, 0"/></transform></shape>'),
        ("shape_rectangle_default", '<shape type="rectangle"/>'),
        ("shape_rectangle_to_world",
         '<shape type="rectangle"><transform name="to_world"><scale x="2" y="3"/><rotate x="1" angle="90"/></transform></shape>'),
        ("shape_disk_default", '<shape type="disk"/>'),
        ("shape_cube_default", '<shape type="cube"/>'),
        ("shape_cylinder_default", '<shape type="cylinder"/>'),
        ("shape_cylinder_points",
         '<shape type="cylinder"><point name="p0" value="1, 0, 0"/><point name="p1" value="1, 0, 3"/><float name="radius" value="0.5"/></shape>'),
        ("shape_obj_default", '<shape type="obj"><string name="filename" value="bent.obj"/></shape>'),
        ("shape_obj_face_normals",
         '<shape type="obj"><string name="filename" value="bent.obj"/><boolean name="face_normals" value="true"/></shape>'),
    ]


def error_cases():
    """Scenes Mitsuba refuses: caustic must refuse them too (with a message naming file and line)."""
    return [
        # Mitsuba refuses a property that its plugin does not read; caustic warns and ignores it (and
        # refuses it under --strict): the box filter has no radius parameter.
        ("error_unreferenced_box_radius",
         '<sensor type="perspective"><film type="hdrfilm"><rfilter type="box"><float name="radius" value="2"/></rfilter></film></sensor>'),
        ("error_spectrum_file_missing",
         '<shape type="sphere"><bsdf type="diffuse"><spectrum name="reflectance" filename="missing.spd"/></bsdf></shape>'),
        ("error_fov_and_focal_length",
         '<sensor type="perspective"><float name="fov" value="40"/><string name="focal_length" value="35mm"/></sensor>'),
        ("error_bad_fov_axis", '<sensor type="perspective"><float name="fov" value="40"/><string name="fov_axis" value="z"/></sensor>'),
        ("error_bad_focal_length", '<sensor type="perspective"><string name="focal_length" value="wide"/></sensor>'),
        ("error_thinlens_no_aperture", '<sensor type="thinlens"/>'),
        ("error_near_clip_beyond_far", '<sensor type="perspective"><float name="near_clip" value="5"/><float name="far_clip" value="2"/></sensor>'),
        ("error_point_position_and_to_world",
         '<emitter type="point"><point name="position" value="1, 2, 3"/><transform name="to_world"><translate value="1, 0, 0"/></transform></emitter>'),
        ("error_directional_direction_and_to_world",
         '<emitter type="directional"><vector name="direction" value="0, 0, 1"/><transform name="to_world"><translate value="1, 0, 0"/></transform></emitter>'),
        ("error_alpha_u_without_alpha_v",
         '<shape type="sphere"><bsdf type="roughconductor"><float name="alpha_u" value="0.2"/></bsdf></shape>'),
        ("error_alpha_and_alpha_u",
         '<shape type="sphere"><bsdf type="roughdielectric"><float name="alpha" value="0.2"/><float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.2"/></bsdf></shape>'),
        ("error_bad_distribution", '<shape type="sphere"><bsdf type="roughplastic"><string name="distribution" value="phong"/></bsdf></shape>'),
        ("error_crop_outside_film",
         '<sensor type="perspective">' + film(64, 48, '<integer name="crop_offset_x" value="60"/><integer name="crop_width" value="10"/>') + '</sensor>'),
    ]


def scene_xml(body):
    return f'<scene version="3.0.0">{body}</scene>'


def rgb_or_float(value):
    if isinstance(value, (float, int)):
        return float(value)
    return [float(v) for v in value]


def vec(v):
    return [float(v[0]), float(v[1]), float(v[2])]


# Offsets (pixels) at which the filter's weight is compared (clear of the box's and tent's edges).
FILTER_POINTS = [0.0, 0.3, 0.7, 1.2, 1.7, 2.3, 2.9, 3.5]


def sensor_values(scene):
    sensor = scene.sensors()[0]
    f = sensor.film()
    size, crop, offset = f.size(), f.crop_size(), f.crop_offset()
    rays = []
    lens_points = LENS_POINTS if "ThinLens" in str(sensor) else LENS_POINTS[:1]
    for p in FILM_POINTS:
        for u in lens_points:
            ray, _ = sensor.sample_ray(0.0, 0.5, p, u)
            rays.append({"film": p, "lens": u, "start": vec(ray.o), "dir": vec(ray.d),
                         "end": vec(ray.o + ray.d * ray.maxt)})
    rfilter = f.rfilter()
    # catmullrom is the Mitchell-Netravali filter with B = 0, C = 1/2: caustic loads it as that.
    name = {"BoxFilter": "box", "TentFilter": "tent", "GaussianFilter": "gaussian",
            "MitchellNetravaliFilter": "mitchell", "CatmullRomFilter": "mitchell",
            "LanczosSincFilter": "lanczos"}[rfilter.class_name()]
    return {
        "rays": rays,
        "film_size": [int(size[0]), int(size[1])],
        "crop_size": [int(crop[0]), int(crop[1])],
        "crop_offset": [int(offset[0]), int(offset[1])],
        "filter": name,
        "filter_radius": float(rfilter.radius()),
        "filter_weights": [float(rfilter.eval(x)) for x in FILTER_POINTS],
        "sample_count": int(sensor.sampler().sample_count()),
    }


def integrator_values(scene):
    text = str(scene.integrator())
    out = {}
    for key in ["max_depth", "rr_depth", "emitter_samples", "bsdf_samples"]:
        m = re.search(rf"{key} = (-?\d+)", text)
        if m:
            v = int(m.group(1))
            out[key] = -1 if v == 2**32 - 1 else v
    return out


def emitter_values(emitter):
    params = mi.traverse(emitter)
    out = {}
    for key in ["intensity", "irradiance", "radiance"]:
        if f"{key}.value" in params:
            out[key] = rgb_or_float(params[f"{key}.value"])
    for key in ["cutoff_angle", "beam_width"]:
        if key in params:
            out[key] = float(params[key])
    if "position" in params:
        out["position"] = vec(params["position"])
    name = emitter.class_name()
    if name == "DirectionalEmitter":
        out["direction"] = vec(params["to_world"] @ mi.ScalarVector3f(0, 0, 1))
    if name == "SpotLight":
        out["to_world"] = [[float(x) for x in row] for row in params["to_world"].matrix]
    return out


def bsdf_values(bsdf):
    out = {}
    text = str(bsdf)
    name = bsdf.class_name()
    params = {k: v for k, v in mi.traverse(bsdf).items()}
    if name.startswith("TwoSided"):
        # One BSDF on both sides: its parameters are listed as brdf_0.* (and brdf_1.* for the same).
        out["two_sided"] = True
        params = {k[len("brdf_0."):]: v for k, v in params.items() if k.startswith("brdf_0.")}
    m = re.search(r"distribution = (\w+)", text)
    if m:
        out["distribution"] = m.group(1)
    m = re.search(r"nonlinear = (\d)", text)
    if m:
        out["nonlinear"] = m.group(1) == "1"
    for key, value in params.items():
        if key == "eta":
            out["eta"] = float(value)
        elif key in ("alpha", "alpha.value"):
            out["alpha_u"] = out["alpha_v"] = float(value)
        elif key in ("alpha_u.value", "alpha_v.value"):
            out[key.split(".")[0]] = float(value)
        elif key == "eta.value":
            out["conductor_eta"] = rgb_or_float(value)
        elif key == "k.value":
            out["conductor_k"] = rgb_or_float(value)
        elif key in ("reflectance.value", "diffuse_reflectance.value"):
            out["reflectance"] = rgb_or_float(value)
        elif key == "specular_reflectance.value":
            out["specular_reflectance"] = rgb_or_float(value)
    return out


def shape_values(shape):
    bbox = shape.bbox()
    out = {"bbox_min": vec(bbox.min), "bbox_max": vec(bbox.max), "surface_area": float(shape.surface_area())}
    if shape.class_name() == "OBJMesh":
        out["vertex_normals"] = bool(shape.has_vertex_normals())
    return out


def compute(name, xml, files):
    with tempfile.TemporaryDirectory() as tmp:
        for fname, text in files.items():
            with open(os.path.join(tmp, fname), "w") as fh:
                fh.write(text)
        path = os.path.join(tmp, "scene.xml")
        with open(path, "w") as fh:
            fh.write(xml)
        try:
            scene = mi.load_file(path)
        except RuntimeError:
            return {"error": True}
    if name.startswith("error_"):
        return {"error": False}
    if name.startswith(("sensor_", "filter_", "sampler_")):
        return sensor_values(scene)
    if name.startswith("integrator_"):
        return integrator_values(scene)
    if name.startswith("emitter_area"):
        return emitter_values(scene.shapes()[0].emitter())
    if name.startswith("emitter_"):
        return emitter_values(scene.emitters()[0])
    if name.startswith("bsdf_"):
        return bsdf_values(scene.shapes()[0].bsdf())
    return shape_values(scene.shapes()[0])


def all_cases():
    cases = []
    for name, body in sensor_cases() + integrator_cases() + emitter_cases() + bsdf_cases() + shape_cases() + error_cases():
        files = {f: text for f, text in FILES.items() if f in body}
        cases.append({"name": name, "xml": scene_xml(body), "files": files})
    return cases


def round9(value):
    if isinstance(value, float):
        return float(f"{value:.9g}")
    if isinstance(value, list):
        return [round9(v) for v in value]
    if isinstance(value, dict):
        return {k: round9(v) for k, v in value.items()}
    return value


def differences(path, a, b):
    if isinstance(a, dict) and isinstance(b, dict):
        out = [f"{path}.{k}: only in one" for k in set(a) ^ set(b)]
        for k in set(a) & set(b):
            out += differences(f"{path}.{k}", a[k], b[k])
        return out
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(f"{path}[{i}]", x, y)]
    if isinstance(a, float) and isinstance(b, (float, int)):
        return [] if abs(a - b) <= 1e-6 * max(1.0, abs(a)) else [f"{path}: {a} vs {b}"]
    return [] if a == b else [f"{path}: {a!r} vs {b!r}"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="compare with the committed file, write nothing")
    args = parser.parse_args()
    cases = all_cases()
    for case in cases:
        case["mitsuba"] = round9(compute(case["name"], case["xml"], case["files"]))
    doc = {"mitsuba": mi.__version__, "variant": "scalar_rgb", "cases": cases}
    if args.check:
        with open(OUT) as fh:
            committed = json.load(fh)
        diffs = differences("", committed, doc)
        for d in diffs:
            print(d)
        print(f"{len(cases)} cases, {len(diffs)} differences")
        sys.exit(1 if diffs else 0)
    with open(OUT, "w") as fh:
        json.dump(doc, fh, indent=1)
        fh.write("\n")
    print(f"wrote {len(cases)} cases to {OUT}")


if __name__ == "__main__":
    main()
