"""caustic.load_dict: Mitsuba 3's dictionary form of a scene, written as the XML it stands for and read
by the loader of load_file. A dictionary renders the image of its XML file bit for bit (same seed, CPU):
the Cornell box, and a scene of nested BSDFs, references, transforms, colours, spectra and meshes; what
cannot be written raises ValueError naming its key path, what the loader refuses CausticError."""

import pathlib
import textwrap

import numpy as np
import pytest

import caustic

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORNELL = ROOT / "scenes" / "cornell-box.xml"
DATA = ROOT / "tests" / "data"


def render(scene, spp=4, seed=3):
    return scene.render(spp=spp, seed=seed, backend="cpu", progress=False)


def rotate(axis, degrees):
    """Mitsuba's <rotate>: a right-handed rotation about a coordinate axis."""
    a = np.radians(degrees)
    c, s = np.cos(a), np.sin(a)
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    m = np.eye(4)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def translate(x=0.0, y=0.0, z=0.0):
    m = np.eye(4)
    m[:3, 3] = x, y, z
    return m


def scale(x, y=None, z=None):
    return np.diag([x, x if y is None else y, x if z is None else z, 1.0])


def look_at(origin, target, up):
    """Mitsuba's <lookat>: columns left, up, forward, origin."""
    origin, target, up = (np.asarray(v, dtype=float) for v in (origin, target, up))
    forward = (target - origin) / np.linalg.norm(target - origin)
    left = np.cross(up, forward)
    left /= np.linalg.norm(left)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = left, np.cross(forward, left), forward, origin
    return m


def matrix_xml(m):
    """A <transform>'s <matrix> as a person writes one: the numbers as Python prints them."""
    return '<matrix value="' + " ".join(repr(float(v)) for v in np.asarray(m).ravel()) + '"/>'


# scenes/cornell-box.xml's transforms, composed as Mitsuba composes a <transform>'s operations (each
# one after those before it).
CBOX_CAMERA = look_at([0, 0, 3.9], [0, 0, 0], [0, 1, 0])
CBOX_WALLS = {
    "floor": (translate(y=-1) @ rotate("x", -90), "white"),
    "ceiling": (translate(y=1) @ rotate("x", 90), "white"),
    "back": (translate(z=-1), "white"),
    "left": (translate(x=-1) @ rotate("y", 90), "red"),
    "right": (translate(x=1) @ rotate("y", -90), "green"),
}
CBOX_LIGHT = translate(y=0.99) @ rotate("x", 90) @ scale(0.25)
CBOX_TALL = translate(-0.35, -0.4, -0.3) @ rotate("y", 20) @ scale(0.3, 0.6, 0.3)
CBOX_SHORT = translate(0.35, -0.7, 0.3) @ rotate("y", -18) @ scale(0.3)


def cornell_dict(res=32, spp=64):
    """scenes/cornell-box.xml as Mitsuba's load_dict takes it."""
    rgb = lambda *v: {"type": "rgb", "value": list(v)}  # noqa: E731
    d = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": -1},
        "sensor": {
            "type": "perspective",
            "fov": 40.0,
            "to_world": CBOX_CAMERA,
            "sampler": {"type": "stratified", "sample_count": spp},
            "film": {"type": "hdrfilm", "width": res, "height": res, "rfilter": {"type": "gaussian"}},
        },
        "white": {"type": "diffuse", "reflectance": rgb(0.73, 0.73, 0.73)},
        "red": {"type": "diffuse", "reflectance": rgb(0.63, 0.065, 0.05)},
        "green": {"type": "diffuse", "reflectance": rgb(0.14, 0.45, 0.091)},
        "glossy": {
            "type": "phong",
            "diffuse_reflectance": rgb(0.35, 0.35, 0.5),
            "specular_reflectance": rgb(0.5, 0.5, 0.45),
            "exponent": 60.0,
        },
    }
    for name, (to_world, bsdf) in CBOX_WALLS.items():
        d[name] = {"type": "rectangle", "to_world": to_world, "bsdf": {"type": "ref", "id": bsdf}}
    d["light"] = {
        "type": "rectangle",
        "to_world": CBOX_LIGHT,
        "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.0}},
        "emitter": {"type": "area", "radiance": rgb(17.0, 12.0, 4.0)},
    }
    d["tall_box"] = {"type": "cube", "to_world": CBOX_TALL, "bsdf": {"type": "ref", "id": "white"}}
    d["short_box"] = {"type": "cube", "to_world": CBOX_SHORT, "bsdf": {"type": "ref", "id": "glossy"}}
    return d


def cornell_xml(res=32, spp=64):
    """The same scene as a person writes its XML (anonymous nested objects, <ref>s without names),
    with the dictionary's transforms as matrices."""
    walls = "\n".join(
        f'<shape type="rectangle"><transform name="to_world">{matrix_xml(m)}</transform><ref id="{bsdf}"/></shape>'
        for m, bsdf in CBOX_WALLS.values()
    )
    return f"""\
<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="-1"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world">{matrix_xml(CBOX_CAMERA)}</transform>
        <sampler type="stratified"><integer name="sample_count" value="{spp}"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="{res}"/><integer name="height" value="{res}"/>
            <rfilter type="gaussian"/>
        </film>
    </sensor>
    <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.73, 0.73, 0.73"/></bsdf>
    <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.63, 0.065, 0.05"/></bsdf>
    <bsdf type="diffuse" id="green"><rgb name="reflectance" value="0.14, 0.45, 0.091"/></bsdf>
    <bsdf type="phong" id="glossy">
        <rgb name="diffuse_reflectance" value="0.35, 0.35, 0.5"/>
        <rgb name="specular_reflectance" value="0.5, 0.5, 0.45"/>
        <float name="exponent" value="60"/>
    </bsdf>
    {walls}
    <shape type="rectangle">
        <transform name="to_world">{matrix_xml(CBOX_LIGHT)}</transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="17, 12, 4"/></emitter>
    </shape>
    <shape type="cube"><transform name="to_world">{matrix_xml(CBOX_TALL)}</transform><ref id="white"/></shape>
    <shape type="cube"><transform name="to_world">{matrix_xml(CBOX_SHORT)}</transform><ref id="glossy"/></shape>
</scene>
"""


def test_a_dict_renders_the_image_of_its_xml(tmp_path):
    """The Cornell box as a dictionary and as XML: the same image, bit for bit."""
    xml = tmp_path / "cbox.xml"
    xml.write_text(cornell_xml())
    from_file = caustic.load_file(xml)
    from_dict = caustic.load_dict(cornell_dict())
    assert (from_dict.width, from_dict.height, from_dict.spp) == (32, 32, 64)
    assert from_dict.warnings == from_file.warnings == []
    image = render(from_dict)
    assert image.shape == (32, 32, 3) and image.dtype == np.float32 and image.mean() > 0
    np.testing.assert_array_equal(image, render(from_file))


def test_the_cornell_box_dict_is_the_scene_file():
    """Against scenes/cornell-box.xml itself, whose transforms are <lookat>, <rotate>, <translate> and
    <scale> (composed in single precision, so the matrices differ in their last bits): the same image
    within noise (independent seeds, the z-test of tests/tests/reference.rs); with the same seed, whose
    noise the two images share but for paths the last bits turn aside, the mean luminance within 0.5%
    (measured: 0.05%)."""
    scene_file = caustic.load_file(CORNELL, res=32)
    from_dict = caustic.load_dict(cornell_dict(res=32))
    reference = render(scene_file, spp=64, seed=1)
    image, variance = from_dict.render(spp=64, seed=2, backend="cpu", variance=True, progress=False)
    c = caustic.compare(
        image, reference, variance=variance, image_spp=64, reference_spp=64,
        sum_variance_factor=from_dict.sum_variance_factor,
    )
    print({k: v for k, v in c.items() if k != "error_map"})
    assert c["pass_fraction"] >= 0.99 and abs(c["luminance_z"]) < 4.0
    same_seed = render(from_dict, spp=64, seed=1)
    assert abs(same_seed.mean() / reference.mean() - 1.0) < 5e-3


class Transform4f:
    """What load_dict reads of a mitsuba.ScalarTransform4f: its 4×4 `matrix`."""

    def __init__(self, matrix):
        self.matrix = np.asarray(matrix).tolist()


def nested_dict():
    """Nested BSDFs (twosided of a blend whose weight is a texture and whose second BSDF is a
    reference), references by key and by id, a mesh by a relative file name, three-number vectors,
    spectra, a transform object, numpy scalars, booleans."""
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": np.int64(6), "hide_emitters": False},
        "camera": {
            "type": "perspective",
            "fov": np.float32(45.0),
            "to_world": Transform4f(look_at([0.3, -4.0, 2.0], [0, 0, 0.3], [0, 0, 1])),
            "film": {"type": "hdrfilm", "width": 24, "height": 16, "rfilter": {"type": "box"}},
        },
        "gold": {"type": "roughconductor", "id": "au", "material": "Au", "alpha": 0.25},
        "checks": {"type": "checkerboard", "color0": {"type": "rgb", "value": [0.1, 0.1, 0.1]},
                   "color1": {"type": "rgb", "value": [0.9, 0.9, 0.9]},
                   "to_uv": scale(4.0)},
        "mesh": {
            "type": "ply",
            "filename": "mesh_attribute.ply",
            "face_normals": True,
            "to_world": translate(z=0.01) @ scale(2.0),
            "bsdf": {
                "type": "twosided",
                "blend": {
                    "type": "blendbsdf",
                    "weight": {"type": "ref", "id": "checks"},
                    "bsdf_0": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.2, 0.5, 0.8]}},
                    "bsdf_1": {"type": "ref", "id": "gold"},
                },
            },
        },
        "ball": {
            "type": "sphere",
            "center": [0.4, 0.2, 0.5],
            "radius": 0.4,
            "bsdf": {"type": "ref", "id": "au"},
        },
        "glass": {
            "type": "sphere",
            "center": np.array([-0.6, 0.0, 0.35]),
            "radius": 0.3,
            "bsdf": {"type": "dielectric", "int_ior": "bk7", "ext_ior": 1.0},
        },
        "lamp": {
            "type": "point",
            "position": (0.0, -1.0, 3.0),
            "intensity": {"type": "spectrum", "value": 8.0},
        },
        "sky": {"type": "constant", "radiance": {"type": "spectrum", "value": [(400.0, 0.2), (550.0, 0.3), (700.0, 0.25)]}},
        "sun": {
            "type": "directional",
            "direction": [0.2, 0.3, -1.0],
            "irradiance": {"type": "blackbody", "temperature": 5000.0},
        },
    }


NESTED_XML = """\
<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="6"/><boolean name="hide_emitters" value="false"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world">{camera}</transform>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/><rfilter type="box"/></film>
    </sensor>
    <bsdf type="roughconductor" id="au"><string name="material" value="Au"/><float name="alpha" value="0.25"/></bsdf>
    <texture type="checkerboard" id="checks">
        <rgb name="color0" value="0.1, 0.1, 0.1"/><rgb name="color1" value="0.9, 0.9, 0.9"/>
        <transform name="to_uv"><scale value="4"/></transform>
    </texture>
    <shape type="ply">
        <string name="filename" value="{data}/mesh_attribute.ply"/>
        <boolean name="face_normals" value="true"/>
        <transform name="to_world"><scale value="2"/><translate z="0.01"/></transform>
        <bsdf type="twosided">
            <bsdf type="blendbsdf">
                <ref name="weight" id="checks"/>
                <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf>
                <ref id="au"/>
            </bsdf>
        </bsdf>
    </shape>
    <shape type="sphere"><point name="center" x="0.4" y="0.2" z="0.5"/><float name="radius" value="0.4"/><ref id="au"/></shape>
    <shape type="sphere">
        <point name="center" value="-0.6, 0, 0.35"/><float name="radius" value="0.3"/>
        <bsdf type="dielectric"><string name="int_ior" value="bk7"/><float name="ext_ior" value="1"/></bsdf>
    </shape>
    <emitter type="point"><point name="position" value="0, -1, 3"/><spectrum name="intensity" value="8"/></emitter>
    <emitter type="constant"><spectrum name="radiance" value="400:0.2, 550:0.3, 700:0.25"/></emitter>
    <emitter type="directional">
        <vector name="direction" value="0.2, 0.3, -1"/>
        <spectrum type="blackbody" name="irradiance"><float name="temperature" value="5000"/></spectrum>
    </emitter>
</scene>
"""


def test_nested_objects_references_and_values_render_as_their_xml(tmp_path, monkeypatch):
    monkeypatch.chdir(DATA)  # the mesh's file name is relative: to the current directory
    camera = look_at([0.3, -4.0, 2.0], [0, 0, 0.3], [0, 0, 1])
    xml = tmp_path / "nested.xml"
    xml.write_text(NESTED_XML.format(camera=matrix_xml(camera), data=DATA))
    from_file = caustic.load_file(xml)
    from_dict = caustic.load_dict(nested_dict())
    # Everything given was read: nothing ignored or substituted.
    assert from_dict.warnings == from_file.warnings == []
    assert from_dict.path is None and "<dict>" in repr(from_dict)
    image = render(from_dict, spp=8)
    assert image.shape == (16, 24, 3) and np.isfinite(image).all() and image.mean() > 0
    np.testing.assert_array_equal(image, render(from_file, spp=8))


def test_relative_file_names_resolve_against_the_current_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(caustic.CausticError, match=r"\(scene\.mesh\): file not found: mesh_attribute\.ply"):
        caustic.load_dict(nested_dict())
    # Mitsuba's search path for a scene dictionary, as XML's <path>.
    with_resources = {"type": "scene", "resources": {"type": "resources", "path": str(DATA)}, **nested_dict()}
    assert '<path value="' in caustic.dict_to_xml(with_resources)
    assert caustic.load_dict(with_resources).warnings == []
    (tmp_path / "mesh_attribute.ply").write_bytes((DATA / "mesh_attribute.ply").read_bytes())
    assert caustic.load_dict(nested_dict()).warnings == []


def test_dict_to_xml_writes_mitsubas_xml():
    xml = caustic.dict_to_xml(
        {
            "type": "scene",
            "white": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.5, 0.25, 1.0]}},
            "box": {
                "type": "cube",
                "id": "my box",
                "to_world": translate(1.0, 2.0, 3.0),
                "flip_normals": True,
                "bsdf": {"type": "ref", "id": "white"},
                "emitter": {"type": "area", "radiance": {"type": "spectrum", "value": 2}},
            },
        }
    )
    assert xml.startswith('<scene version="3.0.0">\n') and xml.endswith("</scene>\n")
    lines = [line.strip() for line in xml.splitlines()]
    assert '<bsdf type="diffuse" id="white">' in lines  # the scene's objects: their keys are their ids
    assert '<rgb name="reflectance" value="0.5, 0.25, 1.0"/>' in lines
    assert '<shape type="cube" id="my box">' in lines  # ... unless they have an id
    assert '<matrix value="1.0 0.0 0.0 1.0 0.0 1.0 0.0 2.0 0.0 0.0 1.0 3.0 0.0 0.0 0.0 1.0"/>' in lines
    assert '<boolean name="flip_normals" value="true"/>' in lines
    assert '<ref name="bsdf" id="white"/>' in lines  # inside an object, keys are names
    assert '<emitter type="area" name="emitter">' in lines
    assert '<spectrum name="radiance" value="2.0"/>' in lines


def test_references_name_a_key_or_an_id():
    """Mitsuba resolves a reference by the key of a scene object or by its id; the XML knows ids."""
    d = {
        "type": "scene",
        "paint": {"type": "diffuse", "id": "red paint"},
        "a": {"type": "sphere", "bsdf": {"type": "ref", "id": "paint"}},
        "b": {"type": "sphere", "bsdf": {"type": "ref", "id": "red paint"}},
    }
    assert caustic.dict_to_xml(d).count('<ref name="bsdf" id="red paint"/>') == 2
    caustic.load_dict(d)
    # An id comes before a key, as Mitsuba looks ids up first.
    d = {
        "type": "scene",
        "paint": {"type": "diffuse", "id": "other"},
        "matte": {"type": "diffuse", "id": "paint"},
        "a": {"type": "sphere", "bsdf": {"type": "ref", "id": "paint"}},
    }
    assert '<ref name="bsdf" id="paint"/>' in caustic.dict_to_xml(d)


def test_values_are_escaped():
    """Text reaches the loader as given: XML's special characters, quotes, tabs and newlines."""
    name = "a&b<c>\"d'\te\nf.ply"
    with pytest.raises(caustic.CausticError) as error:
        caustic.load_dict({"type": "scene", "mesh": {"type": "ply", "filename": name}})
    assert f"file not found: {name}" in str(error.value)


@pytest.mark.parametrize(
    "d, message",
    [
        ({"type": "diffuse"}, "scene: load_dict takes a scene"),
        ({"type": "scene", "s": {"radius": 1.0}}, "scene.s: a dictionary needs a 'type'"),
        ({"type": "scene", "s": {"type": "teapot"}}, "scene.s: unknown plugin type 'teapot'"),
        (
            {"type": "scene", "shape_1": {"type": "sphere", "bsdf": {"type": "diffuse", "reflectance": None}}},
            "scene.shape_1.bsdf.reflectance: unsupported value of type NoneType",
        ),
        (
            {"type": "scene", "s": {"type": "sphere", "to_world": np.eye(3)}},
            r"scene.s.to_world: unsupported value of type ndarray of shape \(3, 3\)",
        ),
        ({"type": "scene", "s": {"type": "sphere", "center": [1.0, 2.0]}}, r"scene.s.center: .* of shape \(2,\)"),
        ({"type": "scene", "s": {"type": "sphere", "data": {1, 2, 3}}}, "scene.s.data: unsupported value of type set"),
        (
            {"type": "scene", "s": {"type": "sphere", "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [1, 2]}}}},
            "scene.s.bsdf.reflectance: 'value' takes 1 or 3 numbers, not 2",
        ),
        (
            {"type": "scene", "s": {"type": "sphere", "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": 1, "x": 2}}}},
            "scene.s.bsdf.reflectance.x: an 'rgb' takes 'type' and 'value' only",
        ),
        ({"type": "scene", "s": {"type": "sphere", "bsdf": {"type": "ref"}}}, "scene.s.bsdf: a 'ref' needs 'id'"),
        ({"type": "scene", "white": {"type": "ref", "id": "x"}}, "scene.white: a 'ref' belongs inside an object"),
        ({"type": "scene", "c": {"type": "rgb", "value": 1}}, "scene.c: an 'rgb' belongs inside an object"),
        ({"type": "scene", "s.1": {"type": "sphere"}}, r"scene: the key 's.1' contains '\.'"),
        ({"type": "scene", "s": {"type": "sphere", 3: 1.0}}, "scene.s: the key 3 is not a str"),
        ({"type": "scene", "s": {"type": "ply", "filename": "$mesh.ply"}}, r"scene.s.filename: .*a '\$' cannot be given"),
        ({"type": "scene", "s": {"type": "ply", "filename": "a\x01b"}}, "scene.s.filename: the character U\\+0001"),
        ({"type": "scene", "s": {"type": "sphere", "id": 7}}, "scene.s.id: an id must be a str"),
        ({"type": "scene", "s": {"type": "scene"}}, "scene.s: a scene inside a scene"),
        ({"type": "scene", "id": "x"}, "scene.id: the scene takes no id"),
    ],
)
def test_what_cannot_be_written_raises_a_value_error_naming_the_key_path(d, message):
    with pytest.raises(ValueError, match=message):
        caustic.load_dict(d)
    with pytest.raises(ValueError, match=message):
        caustic.dict_to_xml(d)


def test_what_the_loader_refuses_raises_caustic_error_with_the_key_path():
    camera = {"type": "perspective", "fov": "wide"}
    with pytest.raises(caustic.CausticError, match=r"<dict>:\d+ \(scene\.camera\.fov\): 'fov' must be a number"):
        caustic.load_dict({"type": "scene", "camera": camera})
    unknown = {"type": "scene", "s": {"type": "sphere", "bsdf": {"type": "ref", "id": "nowhere"}}}
    with pytest.raises(caustic.CausticError, match=r"\(scene\.s\.bsdf\).*nowhere"):
        caustic.load_dict(unknown)
    # The line is one of dict_to_xml's text.
    with pytest.raises(caustic.CausticError) as error:
        caustic.load_dict({"type": "scene", "camera": camera})
    line = int(str(error.value).split("<dict>:")[1].split(" ")[0])
    assert 'name="fov"' in caustic.dict_to_xml({"type": "scene", "camera": camera}).splitlines()[line - 1]


def test_strict_refuses_what_would_not_render_as_written():
    d = {"type": "scene", "s": {"type": "sphere", "shininess": 3.0}}
    assert any("shininess" in w for w in caustic.load_dict(d).warnings)
    with pytest.raises(caustic.CausticError, match="shininess"):
        caustic.load_dict(d, strict=True)


def test_vcm_from_a_dict_and_by_name():
    """`vcm` (caustic's own) in a dictionary, its merging radius and alpha as properties, renders as
    its XML does; and `integrator="vcm"` renders any scene so."""
    d = cornell_dict(res=16, spp=4)
    d["integrator"] = {"type": "vcm", "max_depth": 6, "radius_factor": 0.01, "alpha": 0.5}
    scene = caustic.load_dict(d)
    assert scene.warnings == []
    image = render(scene)
    assert image.shape == (16, 16, 3) and np.isfinite(image).all() and image.mean() > 0
    by_name = caustic.load_dict(cornell_dict(res=16, spp=4)).render(
        spp=4, seed=3, backend="cpu", integrator="vcm", progress=False
    )
    assert np.isfinite(by_name).all() and by_name.mean() > 0
    d["integrator"]["alpha"] = 1.5
    with pytest.raises(caustic.CausticError, match="alpha"):
        caustic.load_dict(d)
