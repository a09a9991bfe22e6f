//! The developed image: per-pixel mean and the variance of that mean, and image files. (The kernel's
//! `film` module is the other end: where each camera sample lands on the sensor.)
use crate::backend::accumulation::Accumulation;
use crate::load::image_io::linear_to_srgb;
use anyhow::{bail, Context, Result};
use std::path::Path;

/// A linear-RGB image with a per-pixel, per-channel variance estimate of each value.
#[derive(Clone, Debug)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// Row-major RGB means.
    pub rgb: Vec<[f32; 3]>,
    /// Variance of each mean (sample variance / n), when known. f64: a lamp of radiance 1e30 gives
    /// variances near 1e55, past f32's range (3.4e38), and the estimate is computed in f64 anyway.
    pub variance: Option<Vec<[f64; 3]>>,
    /// Samples dropped because they were not finite, or because the GPU driver cut them short.
    pub invalid_samples: u64,
    /// A note written into EXR files' `comments` attribute (a partial render says so there).
    pub comment: Option<String>,
    /// How many times the summed variances of the pixels the variance of their sum is: 1 where each
    /// camera sample reaches one pixel, more under the splatting film, whose neighbouring pixels
    /// share samples (`splat_sum_variance_factor`). `compare` scales the mean luminance's standard
    /// error by its root; the variance file carries it (`SUM_VARIANCE_NOTE`).
    pub sum_variance_factor: f64,
    /// Extra EXR channels after R, G, B: the AOVs of Mitsuba's `aov` integrator (`crate::output::aov`),
    /// empty otherwise. PNG and PPM files and the tev stream show the image only.
    pub aovs: Vec<AovChannel>,
}

/// One extra channel of the film: its EXR name, per-pixel values (row-major) and, where known, the
/// variance of each value (the mean of its samples).
#[derive(Clone, Debug, PartialEq)]
pub struct AovChannel {
    pub name: String,
    pub values: Vec<f32>,
    pub variance: Option<Vec<f64>>,
}

impl Film {
    /// An image of `rgb` (row-major, `width` × `height`) and nothing else: no variance, no AOVs.
    pub fn from_rgb(width: u32, height: u32, rgb: Vec<[f32; 3]>) -> Film {
        Film {
            width,
            height,
            rgb,
            variance: None,
            invalid_samples: 0,
            comment: None,
            sum_variance_factor: 1.0,
            aovs: Vec::new(),
        }
    }

    pub fn from_accum(width: u32, height: u32, accum: &Accumulation) -> Film {
        let mut rgb = Vec::with_capacity((width * height) as usize);
        let mut variance = Vec::with_capacity(rgb.capacity());
        let mut invalid = 0u64;
        for px in &accum.pixels {
            // Samples, or the splatting film's summed filter weights, which may be below one (a
            // corner pixel at one sample) or, under a negative lobe at a handful of samples, below
            // zero: Mitsuba's `hdrfilm` divides by them all the same. A pixel nothing reached is black.
            let n = if px.count != 0.0 { px.count } else { 1.0 };
            let mean: [f64; 3] = std::array::from_fn(|c| px.sum[c] / n);
            // Variance of the mean: per sample, (Σx² − n·x̄²) / (n(n−1)); from b batch means weighted
            // by their sizes (samples, or summed weights), (Σ S²/k − n·x̄²) / (n(b−1)).
            let dof = match accum.batches {
                None => (n - 1.0).max(1.0),
                Some(b) => (b as f64 - 1.0).max(1.0),
            };
            let var: [f64; 3] =
                std::array::from_fn(|c| (px.sum_sq[c] - n * mean[c] * mean[c]).max(0.0) / (n.abs() * dof));
            rgb.push(mean.map(|m| m as f32));
            variance.push(var);
            invalid += px.invalid as u64;
        }
        Film {
            width,
            height,
            rgb,
            variance: Some(variance),
            invalid_samples: invalid,
            comment: None,
            sum_variance_factor: 1.0,
            aovs: Vec::new(),
        }
    }

    /// `from_accum` for a render of `buffers`, with its film's `sum_variance_factor`.
    pub fn develop(buffers: &crate::prepare::buffers::SceneBuffers, accum: &Accumulation) -> Film {
        let mut film = Film::from_accum(buffers.params.width, buffers.params.height, accum);
        film.sum_variance_factor = splat_sum_variance_factor(&buffers.params, &buffers.tables);
        film
    }

    /// The window of `width` × `height` pixels starting at (`x`, `y`) (clamped to the image).
    pub fn crop(&self, x: u32, y: u32, width: u32, height: u32) -> Film {
        let (x, y) = (x.min(self.width), y.min(self.height));
        let (w, h) = (width.min(self.width - x), height.min(self.height - y));
        let rows = (y..y + h).flat_map(|row| (x..x + w).map(move |col| (row * self.width + col) as usize));
        Film {
            width: w,
            height: h,
            rgb: rows.clone().map(|i| self.rgb[i]).collect(),
            variance: self.variance.as_ref().map(|v| rows.clone().map(|i| v[i]).collect()),
            invalid_samples: self.invalid_samples,
            comment: self.comment.clone(),
            sum_variance_factor: self.sum_variance_factor,
            aovs: self
                .aovs
                .iter()
                .map(|c| AovChannel {
                    name: c.name.clone(),
                    values: rows.clone().map(|i| c.values[i]).collect(),
                    variance: c.variance.as_ref().map(|v| rows.clone().map(|i| v[i]).collect()),
                })
                .collect(),
        }
    }

    /// Writes `.exr` (linear float), `.png` (sRGB, clamped) or `.ppm` (sRGB, clamped, binary).
    pub fn save(&self, path: &Path) -> Result<()> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        }
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        match ext.as_str() {
            "exr" if !self.aovs.is_empty() => self.write_exr_with_aovs(path),
            "exr" => write_exr(path, self.width, self.height, &self.rgb, self.comment.as_deref()),
            "png" => {
                let img =
                    image::RgbImage::from_fn(self.width, self.height, |x, y| image::Rgb(self.srgb8(x, y)));
                crate::system::files::write(path, &png_bytes(&img)?)
            }
            "ppm" => {
                let mut bytes = format!("P6\n{} {}\n255\n", self.width, self.height).into_bytes();
                for y in 0..self.height {
                    for x in 0..self.width {
                        bytes.extend(self.srgb8(x, y));
                    }
                }
                crate::system::files::write(path, &bytes)
            }
            other => bail!("{}: unknown image format '.{other}' (use .exr, .png or .ppm)", path.display()),
        }
    }

    /// Writes the variance estimate (of each pixel's mean) as an EXR. EXR holds f32: a variance past
    /// f32's range (a lamp of radiance above ~1e19) is written as the largest f32, with a warning.
    pub fn save_variance(&self, path: &Path) -> Result<()> {
        let Some(v) = &self.variance else { bail!("this image has no variance estimate") };
        let saturated = v.iter().flatten().filter(|&&x| x > f32::MAX as f64).count();
        if saturated > 0 {
            eprintln!(
                "warning: {}: {saturated} variance value(s) exceed f32's range ({:e}) and are written as it",
                path.display(),
                f32::MAX
            );
        }
        let narrow: Vec<[f32; 3]> = v.iter().map(|p| p.map(|x| x.min(f32::MAX as f64) as f32)).collect();
        let factor = format!("{SUM_VARIANCE_NOTE}{}", self.sum_variance_factor);
        let comment = match &self.comment {
            Some(c) => format!("{c}\n{factor}"),
            None => factor,
        };
        write_exr(path, self.width, self.height, &narrow, Some(&comment))
    }

    /// Writes the image and the AOV channels in one layer, as Mitsuba writes an `aov` render (f32
    /// samples; EXR keeps channels sorted by name; non-finite values written as 0, as
    /// `session::sanitize` does for the image) with the comment.
    fn write_exr_with_aovs(&self, path: &Path) -> Result<()> {
        use exr::prelude::*;
        let finite = |v: f32| if v.is_finite() { v } else { 0.0 };
        let mut list: Vec<AnyChannel<FlatSamples>> = ["R", "G", "B"]
            .iter()
            .enumerate()
            .map(|(c, name)| {
                AnyChannel::new(*name, FlatSamples::F32(self.rgb.iter().map(|p| finite(p[c])).collect()))
            })
            .collect();
        for channel in &self.aovs {
            if list.iter().any(|c| c.name.to_string() == channel.name) {
                bail!("{}: two channels named '{}'", path.display(), channel.name);
            }
            let values = channel.values.iter().map(|&v| finite(v)).collect();
            list.push(AnyChannel::new(channel.name.as_str(), FlatSamples::F32(values)));
        }
        let channels = AnyChannels::sort(list.into());
        let mut layer = Layer::new(
            (self.width as usize, self.height as usize),
            LayerAttributes::default(),
            Encoding::FAST_LOSSLESS,
            channels,
        );
        layer.attributes.comments = self.comment.as_deref().map(Text::from);
        let mut bytes = std::io::Cursor::new(Vec::new());
        Image::from_layer(layer)
            .write()
            .to_buffered(&mut bytes)
            .with_context(|| format!("cannot encode {}", path.display()))?;
        crate::system::files::write(path, bytes.get_ref())
    }

    fn srgb8(&self, x: u32, y: u32) -> [u8; 3] {
        self.rgb[(y * self.width + x) as usize].map(|c| (linear_to_srgb(c) * 255.0 + 0.5) as u8)
    }

    pub fn load_exr(path: &Path) -> Result<Film> {
        use exr::prelude::*;
        let bytes = crate::load::image_io::read_exr(path)?;
        let image = read()
            .no_deep_data()
            .largest_resolution_level()
            .rgba_channels(
                |resolution, _| {
                    (resolution.width(), vec![[0.0f32; 3]; resolution.width() * resolution.height()])
                },
                |(w, data), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
                    data[pos.y() * *w + pos.x()] = [r, g, b]
                },
            )
            .first_valid_layer()
            .all_attributes()
            .from_buffered(std::io::Cursor::new(bytes))
            .with_context(|| format!("cannot read EXR image {}", path.display()))?;
        let size = image.layer_data.size;
        let (_, rgb) = image.layer_data.channel_data.pixels;
        Ok(Film::from_rgb(size.width() as u32, size.height() as u32, rgb))
    }

    /// Loads an image's sibling variance file written by `render --variance`, if present.
    pub fn load_with_variance(path: &Path) -> Result<Film> {
        let mut film = Film::load_exr(path)?;
        let var_path = variance_path(path);
        if var_path.exists() {
            let v = Film::load_exr(&var_path)?;
            if v.width != film.width || v.height != film.height {
                bail!("{}: size differs from {}", var_path.display(), path.display());
            }
            film.variance = Some(v.rgb.iter().map(|p| p.map(f64::from)).collect());
            let comment = exr_comment(&var_path)?.unwrap_or_default();
            let note = comment.lines().find_map(|l| l.strip_prefix(SUM_VARIANCE_NOTE));
            if let Some(note) = note {
                film.sum_variance_factor = match note.trim().parse::<f64>() {
                    Ok(f) if f.is_finite() && f >= 1.0 => f,
                    _ => bail!(
                        "{}: a damaged note in its comments: {SUM_VARIANCE_NOTE}{note}",
                        var_path.display()
                    ),
                };
            }
        }
        Ok(film)
    }
}

/// How a variance file's `comments` attribute carries `Film::sum_variance_factor` (a line of its
/// own, the number after this).
pub const SUM_VARIANCE_NOTE: &str = "caustic: variance of a sum of pixels / sum of their variances = ";

/// `Film::sum_variance_factor` of the splatting film (1 without it), from the filter as the kernel
/// tabulates it. Each sample adds w·L to the pixels it reaches, so in an image of locally even noise
/// the variance of a sum of pixels is E[(Σw)²] / E[Σw²] times their summed variances, over samples
/// uniform in a pixel; the filter is separable, so that is the square of the same ratio along one
/// axis. Measured by midpoints over a pixel.
pub fn splat_sum_variance_factor(params: &caustic_kernel::layout::FrameParams, tables: &[f32]) -> f64 {
    if params.film_reach == 0 {
        return 1.0;
    }
    const STEPS: u32 = 1024;
    let r = params.film_reach as i32;
    let (mut squared_sum, mut sum_of_squares) = (0.0f64, 0.0f64);
    for k in 0..STEPS {
        let u = (k as f32 + 0.5) / STEPS as f32;
        let w: Vec<f64> = (-r..=r)
            .map(|i| caustic_kernel::film::filter_weight(tables, params, i as f32 + 0.5 - u) as f64)
            .collect();
        squared_sum += w.iter().sum::<f64>().powi(2);
        sum_of_squares += w.iter().map(|x| x * x).sum::<f64>();
    }
    if sum_of_squares > 0.0 {
        (squared_sum / sum_of_squares).powi(2).max(1.0)
    } else {
        1.0
    }
}

/// Fails early (before any rendering) on an output name whose format caustic cannot write.
pub fn check_output_path(path: &Path) -> Result<()> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("exr" | "png" | "ppm") => Ok(()),
        _ => bail!("{}: unknown image format (use .exr, .png or .ppm)", path.display()),
    }
}

/// Fails early (before any rendering) if `path` cannot be written, naming it: creates its folder
/// and opens the file for writing (without truncating one that exists; one created here is
/// removed again).
pub fn check_writable(path: &Path) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let existed = path.exists();
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    if !existed {
        std::fs::remove_file(path).ok();
    }
    Ok(())
}

/// `image.exr` → `image.variance.exr`.
pub fn variance_path(path: &Path) -> std::path::PathBuf {
    path.with_extension("variance.exr")
}

fn write_exr(path: &Path, width: u32, height: u32, data: &[[f32; 3]], comment: Option<&str>) -> Result<()> {
    use exr::prelude::*;
    let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
        let p = data[y * width as usize + x];
        (p[0], p[1], p[2])
    });
    let mut image = Image::from_channels((width as usize, height as usize), channels);
    image.layer_data.attributes.comments = comment.map(Text::from);
    let mut bytes = std::io::Cursor::new(Vec::new());
    image.write().to_buffered(&mut bytes).with_context(|| format!("cannot encode {}", path.display()))?;
    crate::system::files::write(path, bytes.get_ref())
}

/// A PNG file's bytes (encoded in memory: `files::write` writes them whole or not at all).
pub fn png_bytes(img: &image::RgbImage) -> Result<Vec<u8>> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png).context("cannot encode a PNG image")?;
    Ok(bytes.into_inner())
}

/// The `comments` attribute of an EXR file's first layer, if it has one.
pub fn exr_comment(path: &Path) -> Result<Option<String>> {
    let bytes = crate::system::files::read(path, "EXR image")?;
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false)
        .with_context(|| format!("cannot read EXR header {}", path.display()))?;
    Ok(meta.headers.first().and_then(|h| h.own_attributes.comments.as_ref()).map(|t| t.to_string()))
}
