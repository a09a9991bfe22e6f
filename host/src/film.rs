//! The developed image: per-pixel mean and the variance of that mean, and image files. (The kernel's
//! `film` module is the other end: where each camera sample lands on the sensor.)
use anyhow::{bail, Context, Result};
use caustic_kernel::layout::PixelAccum;
use std::path::Path;

/// A linear-RGB image with a per-pixel, per-channel variance estimate of each value.
#[derive(Clone, Debug)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// Row-major RGB means.
    pub rgb: Vec<[f32; 3]>,
    /// Variance of each mean (sample variance / n), when known.
    pub variance: Option<Vec<[f32; 3]>>,
    /// Samples dropped because they were not finite.
    pub invalid_samples: u64,
    /// A note written into EXR files' `comments` attribute (a partial render says so there).
    pub comment: Option<String>,
}

/// A backend's accumulated sums: one `PixelAccum` per pixel, and how their squares were summed.
#[derive(Clone, Debug, PartialEq)]
pub struct Accumulation {
    pub pixels: Vec<PixelAccum>,
    /// `None`: `sum_sq` sums each sample's square (camera paths). `Some(b)`: the sums came in `b`
    /// batches (passes) whose pixel sums `S` were resolved from splats, `sum_sq` summing `S²/k` for a
    /// pass of `k` samples, and the film estimates the variance from batch means: a light path adds
    /// to arbitrary pixels, so no per-sample square exists for a pixel.
    pub batches: Option<u32>,
}

impl Accumulation {
    pub fn new(pixels: usize, splatted: bool) -> Self {
        Accumulation { pixels: vec![PixelAccum::default(); pixels], batches: splatted.then_some(0) }
    }

    /// Adds one pass of `sample_count` samples per pixel from the splat words (`caustic_kernel::splat`
    /// layout), with the kernel's own `resolved` (the GPU runs the same in its `resolve` entry point).
    pub fn add_splats(&mut self, words: &[u32], sample_count: u32) {
        use caustic_kernel::splat::{resolved, SPLAT_STRIDE};
        for (px, w) in self.pixels.iter_mut().zip(words.chunks_exact(SPLAT_STRIDE as usize)) {
            *px = resolved(*px, w.try_into().expect("a pixel's words"), sample_count);
        }
        self.batches = Some(self.batches.unwrap_or(0) + 1);
    }

    /// Adds another device's sums over disjoint samples (several devices, MPI ranks): the sums, counts
    /// and squares add, and so do the batches (each pass of each device is one batch mean). Both
    /// must have the same size and kind.
    pub fn add(&mut self, other: &Accumulation) {
        assert_eq!(self.pixels.len(), other.pixels.len(), "accumulations of different sizes");
        assert_eq!(self.batches.is_some(), other.batches.is_some(), "splatted and per-sample sums");
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            for c in 0..3 {
                a.sum[c] += b.sum[c];
                a.sum_sq[c] += b.sum_sq[c];
            }
            a.count += b.count;
            a.invalid += b.invalid;
        }
        if let (Some(a), Some(b)) = (&mut self.batches, other.batches) {
            *a += b;
        }
    }

    /// An empty accumulation of the same size and kind.
    pub fn empty_like(&self) -> Accumulation {
        Accumulation::new(self.pixels.len(), self.batches.is_some())
    }
}

impl Film {
    pub fn from_accum(width: u32, height: u32, accum: &Accumulation) -> Film {
        let mut rgb = Vec::with_capacity((width * height) as usize);
        let mut variance = Vec::with_capacity(rgb.capacity());
        let mut invalid = 0u64;
        for px in &accum.pixels {
            let n = px.count.max(1.0) as f64;
            let mean: [f64; 3] = std::array::from_fn(|c| px.sum[c] as f64 / n);
            // Variance of the mean: per sample, (Σx² − n·x̄²) / (n(n−1)); from b batch means weighted
            // by their sizes, (Σ S²/k − n·x̄²) / (n(b−1)).
            let dof = match accum.batches {
                None => (n - 1.0).max(1.0),
                Some(b) => (b as f64 - 1.0).max(1.0),
            };
            let var: [f32; 3] = std::array::from_fn(|c| {
                ((px.sum_sq[c] as f64 - n * mean[c] * mean[c]).max(0.0) / (n * dof)) as f32
            });
            rgb.push(mean.map(|m| m as f32));
            variance.push(var);
            invalid += px.invalid as u64;
        }
        Film { width, height, rgb, variance: Some(variance), invalid_samples: invalid, comment: None }
    }

    /// The window of `width` × `height` pixels starting at (`x`, `y`) (clamped to the image).
    pub fn crop(&self, x: u32, y: u32, width: u32, height: u32) -> Film {
        let (x, y) = (x.min(self.width), y.min(self.height));
        let (w, h) = (width.min(self.width - x), height.min(self.height - y));
        let window = |v: &Vec<[f32; 3]>| -> Vec<[f32; 3]> {
            (y..y + h)
                .flat_map(|row| (x..x + w).map(move |col| (row * self.width + col) as usize))
                .map(|i| v[i])
                .collect()
        };
        Film {
            width: w,
            height: h,
            rgb: window(&self.rgb),
            variance: self.variance.as_ref().map(window),
            invalid_samples: self.invalid_samples,
            comment: self.comment.clone(),
        }
    }

    /// Writes `.exr` (linear float), `.png` (sRGB, clamped) or `.ppm` (sRGB, clamped, binary).
    pub fn save(&self, path: &Path) -> Result<()> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        }
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        match ext.as_str() {
            "exr" => write_exr(path, self.width, self.height, &self.rgb, self.comment.as_deref()),
            "png" => {
                let img =
                    image::RgbImage::from_fn(self.width, self.height, |x, y| image::Rgb(self.srgb8(x, y)));
                img.save(path).with_context(|| format!("cannot write {}", path.display()))
            }
            "ppm" => {
                let mut bytes = format!("P6\n{} {}\n255\n", self.width, self.height).into_bytes();
                for y in 0..self.height {
                    for x in 0..self.width {
                        bytes.extend(self.srgb8(x, y));
                    }
                }
                std::fs::write(path, bytes).with_context(|| format!("cannot write {}", path.display()))
            }
            other => bail!("{}: unknown image format '.{other}' (use .exr, .png or .ppm)", path.display()),
        }
    }

    /// Writes the variance estimate (of each pixel's mean) as an EXR.
    pub fn save_variance(&self, path: &Path) -> Result<()> {
        match &self.variance {
            Some(v) => write_exr(path, self.width, self.height, v, self.comment.as_deref()),
            None => bail!("this image has no variance estimate"),
        }
    }

    fn srgb8(&self, x: u32, y: u32) -> [u8; 3] {
        self.rgb[(y * self.width + x) as usize].map(|c| (linear_to_srgb(c) * 255.0 + 0.5) as u8)
    }

    pub fn load_exr(path: &Path) -> Result<Film> {
        use exr::prelude::*;
        let image = read_first_rgba_layer_from_file(
            path,
            |resolution, _| (resolution.width(), vec![[0.0f32; 3]; resolution.width() * resolution.height()]),
            |(w, data), pos, (r, g, b, _a): (f32, f32, f32, f32)| data[pos.y() * *w + pos.x()] = [r, g, b],
        )
        .with_context(|| format!("cannot read EXR image {}", path.display()))?;
        let size = image.layer_data.size;
        let (_, rgb) = image.layer_data.channel_data.pixels;
        Ok(Film {
            width: size.width() as u32,
            height: size.height() as u32,
            rgb,
            variance: None,
            invalid_samples: 0,
            comment: None,
        })
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
            film.variance = Some(v.rgb);
        }
        Ok(film)
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
    image.write().to_file(path).with_context(|| format!("cannot write {}", path.display()))
}

/// The `comments` attribute of an EXR file's first layer, if it has one.
pub fn exr_comment(path: &Path) -> Result<Option<String>> {
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .with_context(|| format!("cannot read EXR header {}", path.display()))?;
    Ok(meta.headers.first().and_then(|h| h.own_attributes.comments.as_ref()).map(|t| t.to_string()))
}

/// The sRGB transfer function, clamped to [0, 1].
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = if c.is_finite() { c.clamp(0.0, 1.0) } else { 0.0 };
    if c <= 0.0031308 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}
