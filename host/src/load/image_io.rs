//! Loading texture images as linear RGB floats, the way Mitsuba 3's `bitmap` texture sees them in
//! its rgb variants, and the sRGB transfer curve both ways.
//!
//! - 8- and 16-bit images (PNG, JPEG, BMP, TGA) are sRGB-encoded: each texel is decoded with the
//!   exact sRGB curve, unless `raw` asks for the stored values as they are. Mitsuba assumes sRGB for
//!   every integer image and ignores PNG gamma chunks; so does this loader.
//! - EXR and Radiance HDR images hold linear values and are never decoded; `raw` changes nothing.
//! - Nothing is clamped: Mitsuba only warns about reflectance texels outside [0, 1].
//! - Grey images are replicated to three channels; alpha is dropped without being applied.
use anyhow::{bail, Context, Result};
use std::path::Path;

/// A linear RGB image: `rgb` holds `width × height` texels, 3 floats each, row-major from the top row.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearImage {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<f32>,
    /// What the file stored each sample as (Mitsuba's `bitmap` picks its storage by it).
    pub depth: SampleDepth,
}

/// The samples of an image file: 8- or 16-bit integers (sRGB-encoded unless `raw`), or floats
/// (half or single: EXR, Radiance HDR).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleDepth {
    Int8,
    Int16,
    Float,
}

impl LinearImage {
    /// The texel at column `x`, row `y` (row 0 at the top).
    pub fn texel(&self, x: u32, y: u32) -> [f32; 3] {
        let i = 3 * (y as usize * self.width as usize + x as usize);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
}

/// Loads an image as linear RGB; `raw` disables the sRGB decoding of 8/16-bit images (normal
/// maps, roughness maps and other non-colour data), as Mitsuba's `raw` property does.
pub fn load_linear_rgb(path: &Path, raw: bool) -> Result<LinearImage> {
    let is_exr = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    let image = if is_exr { load_exr(path) } else { load_with_image_crate(path, raw) };
    let image = image.with_context(|| format!("cannot load image {}", path.display()))?;
    if image.width == 0 || image.height == 0 {
        bail!("{}: the image has no texels ({}×{})", path.display(), image.width, image.height);
    }
    check_texels(&image, path)?;
    Ok(image)
}

/// Every texel that enters a scene passes here: an infinite, NaN or negative one is refused, naming
/// file and texel (one Inf texel in an envmap made its sampling tables infinite and 60% of the
/// samples NaN, counted as black; Mitsuba takes no negative radiance or reflectance either).
fn check_texels(image: &LinearImage, path: &Path) -> Result<()> {
    if let Some(i) = image.rgb.iter().position(|v| !v.is_finite() || *v < 0.0) {
        let texel = i / 3;
        let (x, y) = (texel % image.width as usize, texel / image.width as usize);
        let rgb = image.texel(x as u32, y as u32);
        bail!(
            "{}: texel ({x}, {y}) (column, row from the top) is {rgb:?}: texels must be finite and \
             non-negative",
            path.display()
        );
    }
    Ok(())
}

/// The bytes of EXR file `path`, refused (naming it) when its header claims more texels than this
/// machine's available memory holds decoded: a data window of 65535×32767 in a file of a few
/// hundred bytes made the decoder abort the process allocating it.
pub fn read_exr(path: &Path) -> Result<Vec<u8>> {
    let bytes = crate::system::files::read(path, "EXR image")?;
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(&bytes), false)
        .with_context(|| format!("cannot read EXR image {}", path.display()))?;
    // f32 samples as decoded, and a copy as the caller converts them.
    let need = |h: &exr::meta::header::Header| h.layer_size.area() as u64 * h.channels.list.len() as u64 * 8;
    if let (Some(h), Some(have)) =
        (meta.headers.iter().max_by_key(|h| need(h)), crate::system::memory::available())
    {
        if need(h) > have {
            bail!(
                "{}: its header claims a {}×{} image of {} channels, {:.1} GiB decoded, more than the {:.1} GiB \
                 this machine has available",
                path.display(),
                h.layer_size.width(),
                h.layer_size.height(),
                h.channels.list.len(),
                need(h) as f64 / (1u64 << 30) as f64,
                have as f64 / (1u64 << 30) as f64
            );
        }
    }
    Ok(bytes)
}

/// The sRGB transfer curve, decoded (encoded value in [0, 1] → linear).
pub fn srgb_to_linear(encoded: f32) -> f32 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
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

/// A Radiance file whose first line names another program than `RADIANCE` (`#?RGBE`, which
/// Mitsuba's own writer puts there: the format only asks for `#?`): the same bytes with that line
/// read as `#?RADIANCE`, which the `image` crate insists on; `None` for every other file.
fn radiance_with_standard_signature(bytes: &[u8]) -> Option<Vec<u8>> {
    if !bytes.starts_with(b"#?") || bytes.starts_with(b"#?RADIANCE") {
        return None;
    }
    let line_end = bytes.iter().position(|&b| b == b'\n')?;
    Some([b"#?RADIANCE".as_slice(), &bytes[line_end..]].concat())
}

fn load_with_image_crate(path: &Path, raw: bool) -> Result<LinearImage> {
    let bytes = crate::system::files::read(path, "image")?;
    let reader = match radiance_with_standard_signature(&bytes) {
        Some(fixed) => image::ImageReader::with_format(std::io::Cursor::new(fixed), image::ImageFormat::Hdr),
        None => {
            // As `ImageReader::open`: the extension's format unless the content says otherwise (TGA
            // has no signature).
            let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes));
            if let Ok(format) = image::ImageFormat::from_path(path) {
                reader.set_format(format);
            }
            reader.with_guessed_format()?
        }
    };
    let decoded = reader.decode()?;
    let (width, height) = (decoded.width(), decoded.height());
    use image::DynamicImage as D;
    use SampleDepth::{Float, Int16, Int8};
    let depth = match &decoded {
        D::ImageLuma8(_) | D::ImageLumaA8(_) | D::ImageRgb8(_) | D::ImageRgba8(_) => Int8,
        D::ImageLuma16(_) | D::ImageLumaA16(_) | D::ImageRgb16(_) | D::ImageRgba16(_) => Int16,
        _ => Float,
    };
    let rgb = match decoded {
        // Floating-point formats (Radiance HDR) are linear already.
        D::ImageRgb32F(img) => img.into_raw(),
        D::ImageRgba32F(img) => drop_alpha(&img.into_raw(), 4),
        // Integer formats: keep only the colour channels, normalise, then decode.
        D::ImageLuma8(img) => integer_to_linear(&img.into_raw(), 1, u8::MAX as f32, raw),
        D::ImageLumaA8(img) => integer_to_linear(&img.into_raw(), 2, u8::MAX as f32, raw),
        D::ImageRgb8(img) => integer_to_linear(&img.into_raw(), 3, u8::MAX as f32, raw),
        D::ImageRgba8(img) => integer_to_linear(&img.into_raw(), 4, u8::MAX as f32, raw),
        D::ImageLuma16(img) => integer_to_linear(&img.into_raw(), 1, u16::MAX as f32, raw),
        D::ImageLumaA16(img) => integer_to_linear(&img.into_raw(), 2, u16::MAX as f32, raw),
        D::ImageRgb16(img) => integer_to_linear(&img.into_raw(), 3, u16::MAX as f32, raw),
        D::ImageRgba16(img) => integer_to_linear(&img.into_raw(), 4, u16::MAX as f32, raw),
        other => bail!("unsupported pixel layout {:?}", other.color()),
    };
    Ok(LinearImage { width, height, rgb, depth })
}

/// `channels` = 1 (grey), 2 (grey + alpha), 3 (RGB) or 4 (RGBA) integer samples per texel.
fn integer_to_linear<T: Copy + Into<f32>>(samples: &[T], channels: usize, max: f32, raw: bool) -> Vec<f32> {
    // Decoding through a table would be faster for 8 bits, but loading is not a hot path.
    let to_linear = |s: T| {
        let v = s.into() / max;
        if raw {
            v
        } else {
            srgb_to_linear(v)
        }
    };
    let mut rgb = Vec::with_capacity(samples.len() / channels * 3);
    for texel in samples.chunks_exact(channels) {
        match channels {
            1 | 2 => rgb.extend([to_linear(texel[0]); 3]),
            _ => rgb.extend(texel[..3].iter().map(|&s| to_linear(s))),
        }
    }
    rgb
}

fn drop_alpha(samples: &[f32], channels: usize) -> Vec<f32> {
    samples.chunks_exact(channels).flat_map(|t| [t[0], t[1], t[2]]).collect()
}

/// Which colour role an EXR channel plays; like Mitsuba, only the part after the last '.' counts
/// and case is ignored (`diffuse.R` and `r` are both red).
fn exr_channel_role(name: &str) -> String {
    name.rsplit('.').next().unwrap_or(name).to_ascii_lowercase()
}

/// The first layer of an EXR: R, G, B (+ A) or Y (+ A) channels of half, float or uint samples.
fn load_exr(path: &Path) -> Result<LinearImage> {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(read_exr(path)?))?;
    let layer = image.layer_data;
    let (width, height) = (layer.size.width(), layer.size.height());
    let channels = &layer.channel_data.list;
    let names: Vec<String> = channels.iter().map(|c| c.name.to_string()).collect();
    if let Some(c) = channels.iter().find(|c| c.sampling != Vec2(1, 1)) {
        bail!("channel {} is subsampled (luminance/chroma EXRs are not supported)", c.name);
    }
    let find = |role: &str| channels.iter().find(|c| exr_channel_role(&c.name.to_string()) == role);
    let has_alpha = find("a").is_some();
    let colour_count = channels.len() - has_alpha as usize;
    let planes: Vec<Vec<f32>> = match (find("r"), find("g"), find("b"), find("y")) {
        (Some(r), Some(g), Some(b), _) if colour_count == 3 => {
            [r, g, b].iter().map(|c| c.sample_data.values_as_f32().collect()).collect()
        }
        (_, _, _, Some(y)) if colour_count == 1 => vec![y.sample_data.values_as_f32().collect(); 3],
        _ => bail!("channels [{}] are neither R, G, B[, A] nor Y[, A]", names.join(", ")),
    };
    let texels = width * height;
    if planes.iter().any(|p| p.len() != texels) {
        bail!("channel sizes do not match the {width}×{height} data window");
    }
    let rgb = (0..texels).flat_map(|i| [planes[0][i], planes[1][i], planes[2][i]]).collect();
    Ok(LinearImage { width: width as u32, height: height as u32, rgb, depth: SampleDepth::Float })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn scratch_file(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("caustic-image-io-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    fn textures_dir() -> Option<PathBuf> {
        let dir = match std::env::var_os("CAUSTIC_SHARED") {
            Some(p) => PathBuf::from(p),
            None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared"),
        }
        .join("scenes/mitsuba/common/textures");
        if dir.is_dir() {
            Some(dir)
        } else {
            eprintln!("notice: {} is absent; skipping the checks on real textures", dir.display());
            None
        }
    }

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() <= 1e-6 + 1e-5 * b.abs()
    }

    #[test]
    fn srgb_curve_is_exact_not_gamma_2_2() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!(close(srgb_to_linear(1.0), 1.0));
        assert!(close(srgb_to_linear(0.04045), 0.04045 / 12.92));
        // 0.5 encodes 0.21404114 (gamma 2.2 would give 0.2176).
        assert!(close(srgb_to_linear(0.5), 0.214_041_14));
        assert!(close(srgb_to_linear(128.0 / 255.0), 0.215_860_53));
    }

    #[test]
    fn png_8bit_is_srgb_decoded_unless_raw() {
        let path = scratch_file("rgb8.png");
        let img = image::RgbImage::from_raw(2, 1, vec![0, 128, 255, 10, 188, 64]).unwrap();
        img.save(&path).unwrap();
        let linear = load_linear_rgb(&path, false).unwrap();
        assert_eq!((linear.width, linear.height), (2, 1));
        let want = [0u8, 128, 255, 10, 188, 64].map(|v| srgb_to_linear(v as f32 / 255.0));
        assert!(linear.rgb.iter().zip(want).all(|(g, w)| close(*g, w)), "{:?}", linear.rgb);
        assert!(close(linear.texel(0, 0)[1], 0.215_860_53));
        let raw = load_linear_rgb(&path, true).unwrap();
        assert!(close(raw.texel(0, 0)[1], 128.0 / 255.0) && close(raw.texel(1, 0)[2], 64.0 / 255.0));
    }

    #[test]
    fn grey_alpha_png_is_replicated_and_alpha_dropped() {
        let path = scratch_file("grey-alpha.png");
        image::GrayAlphaImage::from_raw(1, 2, vec![255, 0, 51, 255]).unwrap().save(&path).unwrap();
        let linear = load_linear_rgb(&path, false).unwrap();
        assert_eq!(linear.texel(0, 0), [1.0; 3]);
        let grey = srgb_to_linear(51.0 / 255.0);
        assert!(linear.texel(0, 1).iter().all(|c| close(*c, grey)), "{:?}", linear.rgb);
    }

    #[test]
    fn tga_and_bmp_are_srgb_decoded() {
        for name in ["rgb8.tga", "rgb8.bmp"] {
            let path = scratch_file(name);
            image::RgbImage::from_raw(1, 1, vec![255, 128, 0]).unwrap().save(&path).unwrap();
            let linear = load_linear_rgb(&path, false).unwrap();
            assert!(
                close(linear.texel(0, 0)[1], 0.215_860_53) && linear.texel(0, 0)[0] == 1.0,
                "{name}: {:?}",
                linear.rgb
            );
        }
    }

    #[test]
    fn png_16bit_keeps_its_precision() {
        let path = scratch_file("rgba16.png");
        let samples: Vec<u16> = vec![0, 1000, 32768, 65535];
        image::ImageBuffer::<image::Rgba<u16>, _>::from_raw(1, 1, samples).unwrap().save(&path).unwrap();
        let raw = load_linear_rgb(&path, true).unwrap();
        assert!(close(raw.texel(0, 0)[1], 1000.0 / 65535.0) && close(raw.texel(0, 0)[2], 32768.0 / 65535.0));
        let linear = load_linear_rgb(&path, false).unwrap();
        assert!(close(linear.texel(0, 0)[2], srgb_to_linear(32768.0 / 65535.0)));
    }

    #[test]
    fn exr_float_round_trips_without_gamma() {
        let path = scratch_file("float.exr");
        let texel = |x: usize, y: usize| (x as f32 * 0.25, y as f32 * 3.5, 0.125 + x as f32 + y as f32);
        exr::prelude::write_rgb_file(&path, 3, 2, texel).unwrap();
        let linear = load_linear_rgb(&path, false).unwrap();
        assert_eq!((linear.width, linear.height), (3, 2));
        for (x, y) in [(0, 0), (2, 0), (1, 1), (2, 1)] {
            let (r, g, b) = texel(x, y);
            assert_eq!(linear.texel(x as u32, y as u32), [r, g, b]);
        }
    }

    #[test]
    fn exr_half_luminance_is_replicated() {
        use exr::prelude::*;
        let path = scratch_file("luminance.exr");
        let values: Vec<f16> = [0.5f32, 2.0, 0.0, 8.0].iter().map(|&v| f16::from_f32(v)).collect();
        let channels =
            AnyChannels::sort(SmallVec::from_vec(vec![AnyChannel::new("Y", FlatSamples::F16(values))]));
        Image::from_channels((2, 2), channels).write().to_file(&path).unwrap();
        let linear = load_linear_rgb(&path, false).unwrap();
        assert_eq!(linear.texel(1, 0), [2.0; 3]);
        assert_eq!(linear.texel(1, 1), [8.0; 3]);
    }

    #[test]
    fn radiance_files_with_any_program_name_load() {
        // One texel in the flat (uncompressed) RGBE encoding: (1, 0.5, 0.25) as mantissas 128, 64,
        // 32 with exponent 129 (2^1).
        let body = b"FORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n\x80\x40\x20\x81";
        for signature in ["#?RADIANCE", "#?RGBE"] {
            let path = scratch_file(&format!("signature-{}.hdr", &signature[2..]));
            std::fs::write(&path, [signature.as_bytes(), b"\n", body].concat()).unwrap();
            let image = load_linear_rgb(&path, false).unwrap();
            assert_eq!(image.texel(0, 0), [1.0, 0.5, 0.25], "{signature}");
        }
    }

    #[test]
    fn errors_name_the_file() {
        let path = scratch_file("not-an-image.png");
        std::fs::write(&path, b"hello").unwrap();
        let message = format!("{:#}", load_linear_rgb(&path, false).unwrap_err());
        assert!(message.contains(&path.display().to_string()), "{message}");
        let missing = scratch_file("missing.exr");
        let message = format!("{:#}", load_linear_rgb(&missing, false).unwrap_err());
        assert!(message.contains("missing.exr"), "{message}");
    }

    #[test]
    fn real_textures_load() {
        let Some(dir) = textures_dir() else { return };
        for name in ["wood.jpg", "flower.bmp", "museum.exr"] {
            let path = dir.join(name);
            if !path.exists() {
                eprintln!("notice: {} is absent; skipped", path.display());
                continue;
            }
            let img = load_linear_rgb(&path, false).unwrap();
            assert!(
                img.width >= 2 && img.height >= 2 && img.width <= 16384 && img.height <= 16384,
                "{name}: {}×{}",
                img.width,
                img.height
            );
            assert_eq!(img.rgb.len(), 3 * img.width as usize * img.height as usize, "{name}");
            assert!(
                img.rgb.iter().all(|c| c.is_finite() && *c >= 0.0),
                "{name} has negative or non-finite texels"
            );
            assert!(img.rgb.iter().any(|c| *c > 0.0), "{name} is all black");
        }
    }

    /// A header claiming 65535×32767 texels in a file of a few hundred bytes is refused before any
    /// decoding, naming the file; the same file with its true size loads.
    #[test]
    fn an_exr_header_claiming_more_than_memory_is_refused() {
        let path = scratch_file("claims.exr");
        exr::prelude::write_rgb_file(&path, 1, 1, |_, _| (0.5f32, 0.5f32, 0.5f32)).unwrap();
        assert!(load_linear_rgb(&path, false).is_ok());
        let mut bytes = std::fs::read(&path).unwrap();
        // `dataWindow` (box2i: xMin, yMin, xMax, yMax) made 65535×32767.
        let at = bytes.windows(11).position(|w| w == b"dataWindow\0").unwrap() + 11 + 6 + 4;
        bytes[at + 8..at + 12].copy_from_slice(&65534i32.to_le_bytes());
        bytes[at + 12..at + 16].copy_from_slice(&32766i32.to_le_bytes());
        std::fs::write(&path, &bytes).unwrap();
        if crate::system::memory::available().is_some_and(|m| m < 65535 * 32767 * 3 * 8) {
            let e = format!("{:#}", load_linear_rgb(&path, false).unwrap_err());
            assert!(e.contains("claims.exr") && e.contains("65535×32767"), "{e}");
        }
        assert!(load_linear_rgb(&path, false).is_err());
    }

    /// A Radiance file of no texels (`-Y 0 +X 0`), which the decoder accepts, is refused by name.
    #[test]
    fn an_image_of_no_texels_is_refused() {
        let path = scratch_file("empty.hdr");
        std::fs::write(&path, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n").unwrap();
        let e = format!("{:#}", load_linear_rgb(&path, false).unwrap_err());
        assert!(e.contains("empty.hdr"), "{e}");
    }
}
