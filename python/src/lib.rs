//! `import caustic`: Mitsuba 3 scenes in, numpy arrays out, through the same library functions the
//! command line calls (`caustic::load::load_scene_with`, `session::build_scene`, `backend::create_on`,
//! `passes::render_observed`, `session::develop`, `Film::save`, `compare::compare`,
//! `convergence::measure_warmed_up`). Nothing here loads, builds, renders or compares by itself: it
//! converts arguments and arrays (a scene dictionary into the XML the loader reads: `dict`), keeps a
//! scene's backend between renders, releases the GIL while the host works and turns its errors into
//! Python exceptions.
mod dict;

use anyhow::Context;
use caustic::backend::accumulation::{self, Accumulation};
use caustic::backend::{self, Backend, BackendChoice, GpuSelection};
use caustic::load::LoadOptions;
use caustic::output::film::{self, Film};
use caustic::prepare::buffers::SceneBuffers;
use caustic::render::{convergence, passes, session};
use caustic::scene::{FilmMode, IntegratorChoice};
use clap::ValueEnum;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray3, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyString, PyTuple};
use std::ops::ControlFlow::{self, Break, Continue};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

create_exception!(
    caustic,
    CausticError,
    PyRuntimeError,
    "An error of the renderer: a scene that does not load (its message names the file and line), a \
     backend that cannot start, an image that cannot be read or written. The message is the command \
     line's, causes included."
);

/// A host error as a Python exception, with its chain of causes as the command line prints it.
fn host_error(e: anyhow::Error) -> PyErr {
    CausticError::new_err(caustic::error_chain(&e))
}

/// A value of one of the host's `clap::ValueEnum` choices by its command-line name, or a
/// `ValueError` listing the names.
fn choice<T: ValueEnum>(what: &str, name: &str) -> PyResult<T> {
    T::from_str(name, false).map_err(|_| {
        let names: Vec<String> = T::value_variants()
            .iter()
            .filter_map(|v| v.to_possible_value())
            .map(|v| format!("'{}'", v.get_name()))
            .collect();
        PyValueError::new_err(format!("{what} '{name}': expected one of {}", names.join(", ")))
    })
}

/// `gpus`: "all", a count (the first N adapters) or a sequence of adapter indices, parsed by the
/// command line's `--gpus` parser.
fn gpu_selection(gpus: &Bound<'_, PyAny>) -> PyResult<GpuSelection> {
    let text = if let Ok(s) = gpus.cast::<PyString>() {
        s.to_string()
    } else if let Ok(n) = gpus.extract::<usize>() {
        n.to_string()
    } else if let Ok(list) = gpus.extract::<Vec<usize>>() {
        // A trailing comma makes even one index a list (`--gpus 1,`).
        list.iter().map(|i| format!("{i},")).collect()
    } else {
        return Err(PyValueError::new_err("gpus: 'all', a count or a list of adapter indices"));
    };
    text.parse().map_err(|e: String| PyValueError::new_err(format!("gpus: {e}")))
}

/// What the buffers and the backend of a render depend on: a render with another of these builds
/// them anew; `spp` and `seed` change nothing of them.
#[derive(Clone, Debug, PartialEq)]
struct Setup {
    backend: BackendChoice,
    gpus: GpuSelection,
    integrator: Option<IntegratorChoice>,
    film: FilmMode,
}

impl Setup {
    /// The render arguments `render` and `convergence` share, by their command-line names.
    fn parse(
        backend: &str,
        gpus: Option<&Bound<'_, PyAny>>,
        integrator: Option<&str>,
        film: &str,
    ) -> PyResult<Setup> {
        Ok(Setup {
            backend: choice("backend", backend)?,
            gpus: gpus.map(gpu_selection).transpose()?.unwrap_or_default(),
            integrator: integrator.map(|name| choice("integrator", name)).transpose()?,
            film: choice("film", film)?,
        })
    }
}

/// A scene's buffers and the backend made for them, kept for the next render of the same setup: a
/// GPU backend holds the compiled pipelines and the scene's device buffers, so a second render
/// pays for neither.
struct Kept {
    setup: Setup,
    buffers: SceneBuffers,
    backend: Box<dyn Backend + Send>,
}

/// A loaded scene (`load_file`, `load_dict`). It keeps the backend of its last render, so that the
/// next render with the same backend, integrator and film starts at once.
#[pyclass(frozen, module = "caustic")]
struct Scene {
    /// The scene file, or what stands for it in messages (`dict::NAME`).
    path: PathBuf,
    /// Whether `path` is a file (not a dictionary's stand-in).
    from_file: bool,
    scene: caustic::scene::Scene,
    /// Locked for a whole render: a second thread's render of this scene waits for the first.
    kept: Mutex<Option<Kept>>,
}

/// What the pass loop reports to Python: progress, and Ctrl-C. Python's signal handlers run on the
/// main thread when the interpreter gets to them; the render holds no GIL, so between passes it takes
/// it back for an instant to let them run (`check_signals`). A handler that raises
/// (KeyboardInterrupt) stops the render at that rest.
struct Observer<'a, P> {
    progress: P,
    variance: bool,
    raised: &'a mut Option<PyErr>,
}

impl<P: FnMut(u32)> Observer<'_, P> {
    fn interrupted(&mut self) -> bool {
        if self.raised.is_none() {
            // An interpreter shutting down (a daemon thread still rendering at exit) cannot be
            // attached to: the render stops there.
            let checked = Python::try_attach(|py| py.check_signals())
                .unwrap_or_else(|| Err(CausticError::new_err("the Python interpreter is shutting down")));
            if let Err(e) = checked {
                *self.raised = Some(e);
            }
        }
        self.raised.is_some()
    }
}

impl<P: FnMut(u32)> passes::PassObserver for Observer<'_, P> {
    fn progress(&mut self, finished: u32) {
        (self.progress)(finished)
    }

    fn needs_variance(&self) -> bool {
        self.variance
    }

    fn wants_rest(&mut self, _seconds: f64) -> bool {
        self.interrupted()
    }

    fn at_rest(&mut self, _: u32, _: f64, _: &mut dyn Backend) -> anyhow::Result<ControlFlow<()>> {
        Ok(if self.interrupted() { Break(()) } else { Continue(()) })
    }
}

impl Scene {
    /// Renders with the GIL released: the kept backend when `setup` is its own (its accumulation
    /// cleared), else new buffers and a new backend (the old ones freed first).
    fn render_detached(
        &self,
        setup: Setup,
        spp: Option<u32>,
        seed: u32,
        progress: bool,
        variance: bool,
    ) -> PyResult<Film> {
        let mut kept = self.kept.lock().unwrap_or_else(|e| e.into_inner());
        let spp = session::samples_per_pixel(&self.scene, spp).map_err(host_error)?;
        let mut k = match kept.take() {
            Some(k) if k.setup == setup => k,
            old => {
                drop(old);
                self.prepare(setup).map_err(host_error)?
            }
        };
        let pixels = (k.buffers.params.width * k.buffers.params.height) as usize;
        let empty = Accumulation::new(pixels, accumulation::batch_means(&k.buffers.params));
        k.backend.write_accum(&empty).map_err(host_error)?;
        let bar = session::progress_bar(progress, spp, 0);
        let mut raised = None;
        let observer =
            Observer { progress: |n: u32| bar.set_position(n as u64), variance, raised: &mut raised };
        let stats = passes::render_observed(k.backend.as_mut(), &k.buffers, 0, spp, seed, &[], observer);
        bar.finish_and_clear();
        // A backend that failed is not kept: the next render starts a new one.
        stats.map_err(host_error)?;
        if let Some(e) = raised {
            // Interrupted at rest: the backend is whole, and the next render clears it.
            *kept = Some(k);
            return Err(e);
        }
        let accum = k.backend.read_accum().map_err(host_error)?;
        let mut film = session::develop(&k.buffers, &accum, spp, seed);
        session::sanitize(&mut film);
        *kept = Some(k);
        Ok(film)
    }

    fn prepare(&self, setup: Setup) -> anyhow::Result<Kept> {
        let buffers =
            session::build_scene(self.scene.clone(), &self.path, setup.integrator, setup.film, false)?;
        let backend = backend::create_on(setup.backend, &setup.gpus, &buffers)
            .with_context(|| format!("{}: its sensor's film", self.path.display()))?;
        Ok(Kept { setup, buffers, backend })
    }

    /// The size of the image a render gives (the crop window's, where the sensor has one).
    fn size(&self) -> (u32, u32) {
        let s = &self.scene.sensor;
        s.crop.map_or((s.width, s.height), |c| (c.width, c.height))
    }
}

#[pymethods]
impl Scene {
    /// Renders the scene and returns the image as a float32 array of shape (height, width, 3):
    /// linear RGB, each pixel the mean of its samples.
    ///
    /// spp: samples per pixel (default: the scene's sampler's count). seed: different seeds give
    /// statistically independent images; the same seed the same image. backend: "auto" (a hardware
    /// GPU if there is one, else the CPU), "gpu" (software adapters such as lavapipe included) or
    /// "cpu". integrator: "path", "direct", "ptracer", "ibpt", "bdpt" or "vcm" in place of the scene's (its
    /// max_depth, rr_depth and hide_emitters kept). film: "splat" (Mitsuba's hdrfilm) or "fis"
    /// (filter importance sampling). gpus: "all", a count, or a list of adapter indices.
    /// progress: a progress bar on stderr when it is a terminal.
    ///
    /// variance=True also returns the variance of each pixel's mean (float64, same shape); aovs=True
    /// also returns the AOVs of Mitsuba's `aov` integrator as a dict of name to (height, width)
    /// float32 arrays. With either, the result is a tuple (image, variance?, aovs?) of those asked
    /// for, in that order.
    ///
    /// The GIL is released while rendering. The backend is kept for the next render with the same
    /// backend, gpus, integrator and film, which then pays no loading, building or pipeline
    /// compilation. Ctrl-C stops the render after the pass under way and raises KeyboardInterrupt.
    #[pyo3(signature = (spp=None, seed=0, backend="auto", integrator=None, film="splat", gpus=None, progress=true, variance=false, aovs=false))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        spp: Option<u32>,
        seed: u32,
        backend: &str,
        integrator: Option<&str>,
        film: &str,
        gpus: Option<&Bound<'py, PyAny>>,
        progress: bool,
        variance: bool,
        aovs: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let setup = Setup::parse(backend, gpus, integrator, film)?;
        let film = py.detach(|| self.render_detached(setup, spp, seed, progress, variance))?;
        let image = rgb_array(py, film.width, film.height, &film.rgb)?;
        if !variance && !aovs {
            return Ok(image.into_any());
        }
        let mut parts = vec![image.into_any()];
        if variance {
            let v = film.variance.as_deref().unwrap_or_default();
            let flat: Vec<f64> = v.iter().flatten().copied().collect();
            let shape = (film.height as usize, film.width as usize, 3);
            let array =
                Array3::from_shape_vec(shape, flat).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
            parts.push(array.into_pyarray(py).into_any());
        }
        if aovs {
            let dict = PyDict::new(py);
            for channel in &film.aovs {
                let shape = (film.height as usize, film.width as usize);
                let array = Array2::from_shape_vec(shape, channel.values.clone())
                    .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
                dict.set_item(&channel.name, array.into_pyarray(py))?;
            }
            parts.push(dict.into_any());
        }
        Ok(PyTuple::new(py, parts)?.into_any())
    }

    /// The scene file, as given to load_file; None for a scene of load_dict.
    #[getter]
    fn path(&self) -> Option<PathBuf> {
        self.from_file.then(|| self.path.clone())
    }

    /// Width of the rendered image in pixels (the crop window's, where the film has one).
    #[getter]
    fn width(&self) -> u32 {
        self.size().0
    }

    /// Height of the rendered image in pixels.
    #[getter]
    fn height(&self) -> u32 {
        self.size().1
    }

    /// The scene's samples per pixel (its sampler's sample_count): render's default.
    #[getter]
    fn spp(&self) -> u32 {
        self.scene.sensor.spp
    }

    /// What loading warned about (also printed on stderr): unsupported plugins replaced or left
    /// out, properties not read, values clamped.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scene.warnings.clone()
    }

    /// How many times the summed variances of pixels the variance of their sum is, for the film
    /// of the last render (1 before any): `compare`'s `sum_variance_factor` for that render's
    /// variance. Above 1 under the splatting film, whose filter spreads a sample over neighbouring
    /// pixels.
    #[getter]
    fn sum_variance_factor(&self, py: Python<'_>) -> f64 {
        // Waiting for another thread's render without the GIL: that render takes the GIL between
        // passes (`Observer`), and would wait for this thread forever.
        py.detach(|| {
            let kept = self.kept.lock().unwrap_or_else(|e| e.into_inner());
            kept.as_ref()
                .map_or(1.0, |k| film::splat_sum_variance_factor(&k.buffers.params, &k.buffers.tables))
        })
    }

    /// The command line's `convergence` for this scene: one progressive render up to `spp`, its
    /// error against `reference` measured at 1, 2, 4, … samples per pixel and at `spp`.
    ///
    /// reference: an array of shape (height, width, 3) or the path of an EXR file, of the render's
    /// size. spp: the largest sample count (default: the scene's). seed, backend, integrator, film,
    /// gpus: as render's. The sampler is the independent one, whatever the scene's; as the command
    /// line, a one-sample render on a backend of its own comes first (pipeline compilation, caches),
    /// untimed, and the curve is measured on a new backend; seconds count the passes only, not the
    /// read-backs and comparisons between them.
    ///
    /// Returns a dict of numpy arrays, one entry per point: spp (int64), seconds, rmse, rel_mse
    /// (relative MSE) and luminance_ratio (mean luminance of the image over the reference's), all
    /// float64; and backend (the backend's description) and log_log_slope (the least-squares slope
    /// of log rel_mse against log seconds after the first point, about -1 for an unbiased
    /// estimator at constant throughput; None with fewer than two points). Where the reference is an
    /// EXR file with its variance beside it (`render --variance`), also net_mse and net_rel_mse: the
    /// error against the truth, the reference's noise taken out. The GIL is released meanwhile;
    /// Ctrl-C takes effect when it returns. Raises CausticError.
    #[pyo3(signature = (reference, spp=None, seed=0, backend="auto", integrator=None, film="splat", gpus=None))]
    #[allow(clippy::too_many_arguments)]
    fn convergence<'py>(
        &self,
        py: Python<'py>,
        reference: &Bound<'py, PyAny>,
        spp: Option<u32>,
        seed: u32,
        backend: &str,
        integrator: Option<&str>,
        film: &str,
        gpus: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let setup = Setup::parse(backend, gpus, integrator, film)?;
        let (reference, reference_name) = film_or_file(py, reference, "reference", Film::load_with_variance)?;
        let (backend, points) = py
            .detach(|| {
                caustic::output::compare::check_finite(&reference, &reference_name)?;
                let spp = session::samples_per_pixel(&self.scene, spp)?;
                let buffers = session::build_scene(
                    self.scene.clone(),
                    &self.path,
                    setup.integrator,
                    setup.film,
                    false,
                )?;
                convergence::check_reference_size(&reference, &reference_name, &buffers, &self.path)?;
                convergence::measure_warmed_up(setup.backend, &setup.gpus, &buffers, &reference, spp, seed)
            })
            .map_err(host_error)?;
        let column =
            |f: fn(&convergence::ConvergencePoint) -> f64| points.iter().map(f).collect::<Vec<f64>>();
        let curve = PyDict::new(py);
        let spps: Vec<i64> = points.iter().map(|p| p.spp as i64).collect();
        curve.set_item("spp", spps.into_pyarray(py))?;
        curve.set_item("seconds", column(|p| p.seconds).into_pyarray(py))?;
        curve.set_item("rmse", column(|p| p.rmse).into_pyarray(py))?;
        curve.set_item("rel_mse", column(|p| p.rel_mse).into_pyarray(py))?;
        curve.set_item("luminance_ratio", column(|p| p.luminance_ratio).into_pyarray(py))?;
        if points.iter().all(|p| p.net_mse.is_some()) {
            let net = |f: fn(&convergence::ConvergencePoint) -> Option<f64>| {
                points.iter().map(|p| f(p).unwrap_or(f64::NAN)).collect::<Vec<f64>>()
            };
            curve.set_item("net_mse", net(|p| p.net_mse).into_pyarray(py))?;
            curve.set_item("net_rel_mse", net(|p| p.net_rel_mse).into_pyarray(py))?;
        }
        curve.set_item("backend", backend)?;
        curve.set_item("log_log_slope", convergence::log_log_slope(&points))?;
        Ok(curve)
    }

    fn __repr__(&self) -> String {
        let (w, h) = self.size();
        format!("caustic.Scene('{}', {w}x{h}, {} spp)", self.path.display(), self.scene.sensor.spp)
    }
}

/// Loads a scene: Mitsuba 3 XML, or OBJ with its MTL. Keyword arguments set the scene's
/// `$name` parameters (the command line's `-D name=value`): `load_file("cbox.xml", res=64)`.
/// strict=True refuses a scene that would not render as written (an unsupported plugin, a property
/// not read) instead of warning. Raises CausticError naming the file and line of what is wrong.
#[pyfunction]
#[pyo3(signature = (path, strict=false, **params))]
fn load_file(
    py: Python<'_>,
    path: PathBuf,
    strict: bool,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let mut defines = Vec::new();
    for (name, value) in params.into_iter().flatten() {
        let name: String = name.extract()?;
        // Mitsuba's XML spells booleans in lower case; Python's str() would give "True".
        let value = match value.cast::<PyBool>() {
            Ok(b) => if b.is_true() { "true" } else { "false" }.to_string(),
            Err(_) => value.str()?.to_string(),
        };
        defines.push((name, value));
    }
    let scene = py
        .detach(|| caustic::load::load_scene_with(&path, &defines, LoadOptions { strict }))
        .map_err(host_error)?;
    Ok(Scene { path, from_file: true, scene, kept: Mutex::new(None) })
}

/// Loads a scene given in Mitsuba 3's dictionary form, as `mitsuba.load_dict`:
/// `{"type": "scene", "sensor": {"type": "perspective", …}, "box": {"type": "ply", …}, …}`. The
/// dictionary is written out as the Mitsuba XML it stands for (`dict_to_xml`), which the loader of
/// `load_file` reads: the scene is the one that XML gives.
///
/// A nested dict is a child object (its key the property name; at the scene level, its id), or
/// `{"type": "rgb", "value": [r, g, b]}`, `{"type": "spectrum", "value": v or [(λ, v), …]}` or
/// `{"type": "ref", "id": key_or_id}`. bool, int, float and str values are `<boolean>`,
/// `<integer>`, `<float>` and `<string>`; three numbers a `<vector>`; a 4×4 matrix (nested lists, a
/// numpy array, or a `mitsuba.ScalarTransform4f`) a `<transform>` such as `to_world`. Relative
/// file names resolve against the current directory. strict: as load_file's.
///
/// Raises ValueError naming the key path (`scene.box.bsdf.reflectance: …`) for what cannot be
/// written as XML, and CausticError for what the loader refuses: its message names `<dict>:LINE`,
/// a line of dict_to_xml's text, followed by the key path written there.
#[pyfunction]
#[pyo3(signature = (d, strict=false))]
fn load_dict(py: Python<'_>, d: &Bound<'_, PyDict>, strict: bool) -> PyResult<Scene> {
    let xml = dict::to_xml(d)?;
    let path = PathBuf::from(dict::NAME);
    let scene = py
        .detach(|| {
            let dir =
                std::env::current_dir().context("the current directory, which file names are relative to")?;
            caustic::load::load_scene_from_text(&path, &xml.text, &dir, &[], LoadOptions { strict })
        })
        .map_err(|e| CausticError::new_err(xml.annotate(&caustic::error_chain(&e))))?;
    Ok(Scene { path, from_file: false, scene, kept: Mutex::new(None) })
}

/// The Mitsuba 3 XML that load_dict reads for a scene dictionary: to read, or to save and render
/// with the command line. Raises ValueError as load_dict does.
#[pyfunction]
fn dict_to_xml(d: &Bound<'_, PyDict>) -> PyResult<String> {
    Ok(dict::to_xml(d)?.text)
}

/// An (height, width, 3) float32 array of `rgb`.
fn rgb_array<'py>(
    py: Python<'py>,
    width: u32,
    height: u32,
    rgb: &[[f32; 3]],
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let flat: Vec<f32> = rgb.iter().flatten().copied().collect();
    let array = Array3::from_shape_vec((height as usize, width as usize, 3), flat)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}

/// `value` (an array, or anything numpy makes one of) as C-contiguous `T` values of shape
/// (height, width, 3), or a ValueError naming `what`.
fn pixels<'py, T: numpy::Element + Copy>(
    value: &Bound<'py, PyAny>,
    what: &str,
    dtype: &str,
) -> PyResult<(u32, u32, Vec<[T; 3]>)> {
    let np = value.py().import("numpy")?;
    let kwargs = PyDict::new(value.py());
    kwargs.set_item("dtype", dtype)?;
    let array = np.call_method("ascontiguousarray", (value,), Some(&kwargs))?;
    let array = array.cast_into::<numpy::PyArrayDyn<T>>().map_err(PyErr::from)?;
    let shape = array.shape().to_vec();
    let [h, w, 3] = shape[..] else {
        return Err(PyValueError::new_err(format!("{what}: shape {shape:?}, expected (height, width, 3)")));
    };
    let values = array.readonly();
    let slice = values.as_slice()?;
    let rgb = slice.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    Ok((w as u32, h as u32, rgb))
}

/// A film of an RGB array, without variance.
fn film_of(value: &Bound<'_, PyAny>, what: &str) -> PyResult<Film> {
    let (width, height, rgb) = pixels::<f32>(value, what, "float32")?;
    Ok(Film::from_rgb(width, height, rgb))
}

/// An array, or a path to read: the film and a name for messages (the path, or `what`).
fn film_or_file(
    py: Python<'_>,
    value: &Bound<'_, PyAny>,
    what: &str,
    load: fn(&Path) -> anyhow::Result<Film>,
) -> PyResult<(Film, PathBuf)> {
    if let Ok(path) = value.extract::<PathBuf>() {
        let film = py.detach(|| load(&path)).map_err(host_error)?;
        return Ok((film, path));
    }
    Ok((film_of(value, what)?, PathBuf::from(what)))
}

/// Writes an (height, width, 3) array: .exr (linear float), .png or .ppm (sRGB, 8 bits), through
/// the command line's writers: the file is replaced whole or not at all, and a file this process
/// has read (a scene, a mesh, a texture) is refused.
#[pyfunction]
fn write(py: Python<'_>, path: PathBuf, image: &Bound<'_, PyAny>) -> PyResult<()> {
    film::check_output_path(&path).map_err(host_error)?;
    let film = film_of(image, "image")?;
    py.detach(|| film.save(&path)).map_err(host_error)
}

/// Reads an EXR image as a float32 array of shape (height, width, 3): its R, G and B channels.
#[pyfunction]
fn read<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let film = py.detach(|| Film::load_exr(&path)).map_err(host_error)?;
    rgb_array(py, film.width, film.height, &film.rgb)
}

/// The command line's `compare`: statistics of an image against a reference of the same size.
///
/// image and reference: arrays of shape (height, width, 3), or paths of EXR files (an image's
/// variance is then read from IMAGE.variance.exr beside it, as `caustic render --variance` writes
/// it). variance: the image's per-pixel variance of the mean (render(variance=True)), enabling the
/// z-test. image_spp and reference_spp: their samples per pixel, to count the reference's own
/// noise. sum_variance_factor: the image's film's (Scene.sum_variance_factor) for an array image;
/// a file's is read from its variance file.
///
/// Returns a dict: rmse, rel_mse, luminance_ratio (mean luminance of the image over the
/// reference's), pass_fraction (pixels passing the per-pixel z-test at 1%, Šidák-corrected; None
/// without a variance), z_critical, luminance_z (the mean luminances' difference in standard errors;
/// None without a variance) and error_map (float32 (height, width): each pixel's largest |z|, or
/// relative error without a variance).
#[pyfunction]
#[pyo3(signature = (image, reference, variance=None, image_spp=0, reference_spp=0, sum_variance_factor=None))]
fn compare<'py>(
    py: Python<'py>,
    image: &Bound<'py, PyAny>,
    reference: &Bound<'py, PyAny>,
    variance: Option<&Bound<'py, PyAny>>,
    image_spp: u32,
    reference_spp: u32,
    sum_variance_factor: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let (mut a, a_name) = film_or_file(py, image, "image", Film::load_with_variance)?;
    let (b, b_name) = film_or_file(py, reference, "reference", Film::load_exr)?;
    if let Some(v) = variance {
        let (w, h, values) = pixels::<f64>(v, "variance", "float64")?;
        if (w, h) != (a.width, a.height) {
            return Err(PyValueError::new_err(format!(
                "variance is {w}x{h} but the image is {}x{}",
                a.width, a.height
            )));
        }
        a.variance = Some(values);
    }
    if let Some(f) = sum_variance_factor {
        a.sum_variance_factor = f;
    }
    let c = py
        .detach(|| {
            caustic::output::compare::check_finite(&a, &a_name)?;
            caustic::output::compare::check_finite(&b, &b_name)?;
            let ratio = caustic::output::compare::samples_ratio(image_spp, reference_spp);
            caustic::output::compare::compare(&a, &b, ratio)
                .with_context(|| format!("{} against {}", a_name.display(), b_name.display()))
        })
        .map_err(host_error)?;
    let stats = PyDict::new(py);
    stats.set_item("rmse", c.rmse)?;
    stats.set_item("rel_mse", c.rel_mse)?;
    stats.set_item("luminance_ratio", c.luminance_ratio)?;
    stats.set_item("pass_fraction", c.pass_fraction)?;
    stats.set_item("z_critical", c.z_critical)?;
    stats.set_item("luminance_z", c.luminance_z)?;
    let shape = (a.height as usize, a.width as usize);
    let error_map =
        Array2::from_shape_vec(shape, c.error_map).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    stats.set_item("error_map", error_map.into_pyarray(py))?;
    Ok(stats)
}

/// caustic: a physically based renderer whose one kernel runs on the GPU and the CPU. Mitsuba 3
/// scenes in (`load_file`, `load_dict`), numpy arrays out (`Scene.render`); `write`, `read`,
/// `compare` and `Scene.convergence` as the command line's. See docs/python.md.
#[pymodule]
#[pyo3(name = "caustic")]
fn caustic_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // The Vulkan loader's window-system code complains on stderr without XDG_RUNTIME_DIR (ssh, CI,
    // containers); the command line sets a private one at start. Here at import: the host's own
    // threads (rayon's, wgpu's) do not exist yet.
    backend::runtime_dir::ensure_xdg_runtime_dir();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("CausticError", m.py().get_type::<CausticError>())?;
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(load_file, m)?)?;
    m.add_function(wrap_pyfunction!(load_dict, m)?)?;
    m.add_function(wrap_pyfunction!(dict_to_xml, m)?)?;
    m.add_function(wrap_pyfunction!(write, m)?)?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    Ok(())
}
