"""caustic: a physically based renderer whose one kernel runs on the GPU and the CPU.

Mitsuba 3 scenes in, numpy arrays out::

    import caustic
    scene = caustic.load_file("cbox.xml", res=256)   # or caustic.load_dict({"type": "scene", ...})
    image = scene.render(spp=64)          # float32, (height, width, 3), linear RGB

Everything here calls the library functions the `caustic` command line calls: the same loader,
backends, pass loop, image writers, statistics and convergence curves.
"""

import os
import pathlib
from typing import Any, Dict, Literal, Optional, Sequence, Tuple, TypedDict, Union, overload
from typing_extensions import NotRequired

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, "os.PathLike[str]"]
_Backend = Literal["auto", "gpu", "cpu"]
_Integrator = Literal["path", "direct", "ptracer", "ibpt", "bdpt", "vcm"]
_Film = Literal["splat", "fis"]
_Gpus = Union[Literal["all"], int, Sequence[int]]
_Image = npt.NDArray[np.float32]
_Variance = npt.NDArray[np.float64]

class CausticError(RuntimeError):
    """An error of the renderer: a scene that does not load (the message names the file and line),
    a backend that cannot start, an image that cannot be read or written. The message is the
    command line's, causes included."""

class Convergence(TypedDict):
    """Scene.convergence's curve: one entry per point of the arrays, at 1, 2, 4, … samples per
    pixel and at the budget."""

    spp: npt.NDArray[np.int64]
    seconds: npt.NDArray[np.float64]
    rmse: npt.NDArray[np.float64]
    rel_mse: npt.NDArray[np.float64]
    luminance_ratio: npt.NDArray[np.float64]
    # Only where the reference file has its variance beside it.
    net_mse: NotRequired[npt.NDArray[np.float64]]
    net_rel_mse: NotRequired[npt.NDArray[np.float64]]
    backend: str
    log_log_slope: Optional[float]

class Scene:
    """A loaded scene (`load_file`, `load_dict`). It keeps the backend of its last render, so that
    the next render with the same backend, gpus, integrator and film pays no loading, building or
    pipeline compilation."""

    @property
    def path(self) -> Optional[pathlib.Path]:
        """The scene file, as given to load_file; None for a scene of load_dict."""
    @property
    def width(self) -> int:
        """Width of the rendered image in pixels (the crop window's, where the film has one)."""
    @property
    def height(self) -> int:
        """Height of the rendered image in pixels."""
    @property
    def spp(self) -> int:
        """The scene's samples per pixel (its sampler's sample_count): render's default."""
    @property
    def warnings(self) -> list[str]:
        """What loading warned about (also printed on stderr)."""
    @property
    def sum_variance_factor(self) -> float:
        """The variance of a sum of pixels over the sum of their variances, for the film of the
        last render (1.0 before any): pass it to `compare` with that render's variance."""
    @overload
    def render(
        self,
        spp: Optional[int] = None,
        seed: int = 0,
        backend: _Backend = "auto",
        integrator: Optional[_Integrator] = None,
        film: _Film = "splat",
        gpus: Optional[_Gpus] = None,
        progress: bool = True,
        variance: Literal[False] = False,
        aovs: Literal[False] = False,
    ) -> _Image:
        """Renders the scene: a float32 array of shape (height, width, 3), linear RGB.

        spp: samples per pixel (default: the scene's). seed: the same seed gives the same image,
        different seeds statistically independent ones. backend: "auto" (a hardware GPU if there
        is one, else the CPU), "gpu" (software adapters such as lavapipe included) or "cpu".
        integrator: replaces the scene's (its max_depth, rr_depth and hide_emitters kept). film:
        "splat" (Mitsuba's hdrfilm) or "fis" (filter importance sampling). gpus: "all", a count or
        adapter indices. progress: a progress bar on stderr when it is a terminal.

        variance=True also returns each pixel's variance of the mean (float64); aovs=True also
        returns the AOVs of Mitsuba's `aov` integrator, by name. The GIL is released while
        rendering; Ctrl-C stops the render after the pass under way and raises KeyboardInterrupt.
        Raises CausticError."""

    @overload
    def render(
        self,
        spp: Optional[int] = None,
        seed: int = 0,
        backend: _Backend = "auto",
        integrator: Optional[_Integrator] = None,
        film: _Film = "splat",
        gpus: Optional[_Gpus] = None,
        progress: bool = True,
        *,
        variance: Literal[True],
        aovs: Literal[False] = False,
    ) -> Tuple[_Image, _Variance]: ...
    @overload
    def render(
        self,
        spp: Optional[int] = None,
        seed: int = 0,
        backend: _Backend = "auto",
        integrator: Optional[_Integrator] = None,
        film: _Film = "splat",
        gpus: Optional[_Gpus] = None,
        progress: bool = True,
        *,
        variance: Literal[False] = False,
        aovs: Literal[True],
    ) -> Tuple[_Image, Dict[str, npt.NDArray[np.float32]]]: ...
    @overload
    def render(
        self,
        spp: Optional[int] = None,
        seed: int = 0,
        backend: _Backend = "auto",
        integrator: Optional[_Integrator] = None,
        film: _Film = "splat",
        gpus: Optional[_Gpus] = None,
        progress: bool = True,
        *,
        variance: Literal[True],
        aovs: Literal[True],
    ) -> Tuple[_Image, _Variance, Dict[str, npt.NDArray[np.float32]]]: ...
    def convergence(
        self,
        reference: Union[npt.ArrayLike, _Path],
        spp: Optional[int] = None,
        seed: int = 0,
        backend: _Backend = "auto",
        integrator: Optional[_Integrator] = None,
        film: _Film = "splat",
        gpus: Optional[_Gpus] = None,
    ) -> Convergence:
        """The command line's `convergence`: one progressive render up to `spp` (default: the
        scene's), its error against `reference` (an (height, width, 3) array or an EXR file of the
        render's size) measured at 1, 2, 4, … samples per pixel and at `spp`.

        seed, backend, integrator, film, gpus: as render's. The sampler is the independent one; as
        the command line, an untimed one-sample render on a backend of its own comes first, and
        seconds count the passes only. Returns arrays spp (int64), seconds, rmse, rel_mse and
        luminance_ratio (float64), the backend's description and log_log_slope (of rel_mse against
        seconds after the first point; about -1 for an unbiased estimator); where the reference is
        an EXR file with its variance beside it (`render --variance`), also net_mse and net_rel_mse,
        the error against the truth with the reference's noise taken out. The GIL is released;
        Ctrl-C takes effect when it returns. Raises CausticError."""
    def __repr__(self) -> str: ...

def load_file(path: _Path, strict: bool = False, **params: Union[str, int, float, bool]) -> Scene:
    """Loads a scene: Mitsuba 3 XML, or OBJ with its MTL. Keyword arguments set the scene's `$name`
    parameters, as the command line's `-D name=value` (`load_file("cbox.xml", res=64)`).
    strict=True refuses a scene that would not render as written instead of warning. Raises
    CausticError naming the file and line of what is wrong."""

def load_dict(d: Dict[str, Any], strict: bool = False) -> Scene:
    """Loads a scene in Mitsuba 3's dictionary form, as `mitsuba.load_dict`:
    `{"type": "scene", "sensor": {"type": "perspective", ...}, "box": {"type": "ply", ...}}`. The
    dictionary is written as the Mitsuba XML it stands for (`dict_to_xml`), which load_file's loader
    reads: the scene is the one that XML gives.

    A nested dict is a child object (its key the property's name; at the scene level, the object's
    id, unless it has an "id"), or {"type": "rgb", "value": [r, g, b]}, {"type": "spectrum",
    "value": v or [(wavelength, v), ...]} or {"type": "ref", "id": key_or_id}. bool, int, float and
    str values are <boolean>, <integer>, <float> and <string>; three numbers a <vector>; a 4x4
    matrix (nested lists, a numpy array or a mitsuba.ScalarTransform4f) a <transform> such as
    to_world. Relative file names resolve against the current directory. strict: as load_file's.

    Raises ValueError naming the key path (`scene.box.bsdf.reflectance: ...`) of what cannot be
    written as XML, and CausticError for what the loader refuses: `<dict>:LINE (key path): ...`,
    LINE a line of dict_to_xml's text."""

def dict_to_xml(d: Dict[str, Any]) -> str:
    """The Mitsuba 3 XML that load_dict reads for a scene dictionary: to read, or to save and
    render with the command line. Raises ValueError as load_dict does."""

def write(path: _Path, image: npt.ArrayLike) -> None:
    """Writes an (height, width, 3) image: .exr (linear float), .png or .ppm (sRGB, 8 bits). The
    file is replaced whole or not at all; a file this process has read (a scene, a mesh, a
    texture) is refused."""

def read(path: _Path) -> _Image:
    """Reads an EXR image's R, G and B channels: float32, (height, width, 3)."""

class Comparison(TypedDict):
    rmse: float
    rel_mse: float
    luminance_ratio: float
    pass_fraction: Optional[float]
    z_critical: float
    luminance_z: Optional[float]
    error_map: npt.NDArray[np.float32]

def compare(
    image: Union[npt.ArrayLike, _Path],
    reference: Union[npt.ArrayLike, _Path],
    variance: Optional[npt.ArrayLike] = None,
    image_spp: int = 0,
    reference_spp: int = 0,
    sum_variance_factor: Optional[float] = None,
) -> Comparison:
    """The command line's `compare`: an image against a reference of the same size.

    Arrays of shape (height, width, 3), or paths of EXR files (an image file's variance is read
    from IMAGE.variance.exr beside it). variance: the image's per-pixel variance of the mean
    (render(variance=True)), which enables the per-pixel z-test and luminance_z. image_spp and
    reference_spp: samples per pixel of both, to count the reference's noise.
    sum_variance_factor: Scene.sum_variance_factor of the render that gave the variance.

    pass_fraction: pixels passing the z-test at 1% (Šidák-corrected); luminance_z: the mean
    luminances' difference in standard errors; error_map: each pixel's largest |z| (or relative
    error without a variance)."""
