#!/usr/bin/env python3
"""Writes spectrum_plugins.json: the colour Mitsuba 3.9.1 renders for each spectrum plugin written
out as an object (`<spectrum type="...">`), against which tests/tests/spectrum_plugins.rs checks
caustic's loader (host/src/load/mitsuba/spectrum_plugin.rs).

    python3 -m venv /tmp/mi-venv && /tmp/mi-venv/bin/pip install mitsuba==3.9.1 numpy
    /tmp/mi-venv/bin/python tests/data/spectrum_plugins.py

Each case is rendered as Mitsuba renders it: the constant plugins (srgb, uniform, d65, rawconstant)
by `scalar_rgb`, exactly; the spectra (regular, irregular, blackbody), which `scalar_rgb` loads but
refuses to render ("Not implemented for non-spectral modes"), by `scalar_spectral`, whose film
integrates the sampled wavelengths against the CIE 1931 curves (Monte Carlo: `tolerance` is
relative). An emission case is the radiance of an area-lit rectangle seen head-on (box filter, every
pixel on it); a reflectance case a diffuse rectangle under a unit `d65` constant emitter, rendered
with BSDF samples alone (`direct`), whose radiance is the reflectance. Cases with `error` are ones Mitsuba refuses while loading.
"""
import json
import os

import mitsuba as mi
import numpy as np

SPP_SPECTRAL = 65536


def scene(case):
    inner = case["spectrum"]
    if case["usage"] == "emission":
        shape = f'<shape type="rectangle"><emitter type="area">{inner}</emitter></shape>'
        extra = ""
    else:
        shape = f'<shape type="rectangle"><bsdf type="diffuse">{inner}</bsdf></shape>'
        extra = '<emitter type="constant"><spectrum type="d65" name="radiance"/></emitter>'
    return shape, extra


def integrator(case):
    if case["usage"] == "emission":
        return '<integrator type="path"/>'
    # BSDF samples alone: each is the reflectance times the sky's unit radiance, no spatial noise.
    return ('<integrator type="direct"><integer name="emitter_samples" value="0"/>'
            '<integer name="bsdf_samples" value="1"/></integrator>')


def render(case, variant, spp):
    mi.set_variant(variant)
    shape, extra = scene(case)
    xml = f"""<scene version="3.0.0">{integrator(case)}
<sensor type="perspective"><float name="fov" value="10"/>
<transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
<film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/><rfilter type="box"/></film>
<sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler></sensor>
{shape}{extra}</scene>"""
    image = np.array(mi.render(mi.load_string(xml)))
    return [float(f"{c:.7g}") for c in image[:, :, :3].reshape(-1, 3).mean(axis=0)]


def refused(case):
    mi.set_variant("scalar_rgb")
    shape, extra = scene(case)
    try:
        mi.load_string(f'<scene version="3.0.0">{shape}{extra}</scene>')
        return False
    except RuntimeError:
        return True


def radiance(name, value):
    return f'<spectrum type="{name}" name="radiance">{value}</spectrum>'


def reflectance(name, value):
    return f'<spectrum type="{name}" name="reflectance">{value}</spectrum>'


CONSTANT = [
    ("srgb_emission", "emission", radiance("srgb", '<rgb name="color" value="0.5, 0.2, 0.1"/>')),
    ("srgb_reflectance", "reflectance", reflectance("srgb", '<rgb name="color" value="0.7, 0.3, 0.2"/>')),
    ("uniform_emission", "emission", radiance("uniform", '<float name="value" value="2"/>')),
    ("uniform_reflectance", "reflectance", reflectance("uniform", '<float name="value" value="0.4"/>')),
    ("d65_emission", "emission", radiance("d65", "")),
    ("d65_scale_color", "emission", radiance("d65", '<rgb name="color" value="0.5, 0.2, 0.1"/><float name="scale" value="3"/>')),
    ("rawconstant_float", "emission", radiance("rawconstant", '<float name="value" value="0.5"/>')),
    ("rawconstant_vector", "emission", radiance("rawconstant", '<vector name="value" value="0.5, 0.2, 0.1"/>')),
]

SPECTRAL = [
    ("regular_emission", "emission",
     radiance("regular", '<float name="wavelength_min" value="400"/><float name="wavelength_max" value="700"/>'
                         '<string name="values" value="1, 2, 0.5"/>')),
    ("regular_reflectance", "reflectance",
     reflectance("regular", '<float name="wavelength_min" value="380"/><float name="wavelength_max" value="780"/>'
                            '<string name="values" value="0.1, 0.2, 0.8, 0.6, 0.3"/>')),
    ("irregular_emission", "emission",
     radiance("irregular", '<string name="wavelengths" value="420, 500, 610, 700"/><string name="values" value="3, 0.5, 2, 1"/>')),
    ("blackbody_3000", "emission", radiance("blackbody", '<float name="temperature" value="3000"/>')),
    ("blackbody_6500_range", "emission",
     radiance("blackbody", '<float name="temperature" value="6500"/><float name="wavelength_min" value="450"/>'
                           '<float name="wavelength_max" value="650"/>')),
]

ERRORS = [
    ("srgb_above_one", "emission", radiance("srgb", '<rgb name="color" value="2, 5, 9"/>')),
    ("srgb_float_color", "emission", radiance("srgb", '<float name="color" value="0.5"/>')),
    ("uniform_no_value", "emission", radiance("uniform", "")),
    ("blackbody_no_temperature", "emission", radiance("blackbody", "")),
    ("blackbody_lambda_min", "emission",
     radiance("blackbody", '<float name="temperature" value="3000"/><float name="lambda_min" value="500"/>')),
    ("regular_no_range", "emission", radiance("regular", '<string name="values" value="1, 2"/>')),
]


def main():
    cases = []
    for name, usage, spectrum in CONSTANT:
        case = {"name": name, "usage": usage, "spectrum": spectrum}
        case["mitsuba"] = render(case, "scalar_rgb", 4)
        case["tolerance"] = 1e-5
        cases.append(case)
    for name, usage, spectrum in SPECTRAL:
        case = {"name": name, "usage": usage, "spectrum": spectrum}
        case["mitsuba"] = render(case, "scalar_spectral", SPP_SPECTRAL)
        case["tolerance"] = 0.01
        cases.append(case)
    for name, usage, spectrum in ERRORS:
        case = {"name": name, "usage": usage, "spectrum": spectrum}
        case["error"] = refused(case)
        cases.append(case)
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "spectrum_plugins.json")
    with open(out, "w") as fh:
        json.dump({"mitsuba": mi.__version__, "cases": cases}, fh, indent=1)
        fh.write("\n")
    for case in cases:
        print(case["name"], case.get("mitsuba", case.get("error")))


if __name__ == "__main__":
    main()
