//! Sensor plugins (`perspective`, `thinlens`, `orthographic`, `radiancemeter`, and
//! `irradiancemeter` nested in a shape) with their film
//! (`hdrfilm`), reconstruction filter (`box`, `tent`, `gaussian`, `mitchell`, `catmullrom`,
//! `lanczos`) and sampler (`independent`; `stratified`, `multijitter`, `orthogonal` and `ldsampler`
//! all use caustic's stratified sequence with the sample count Mitsuba would take).
use super::loader::Loader;
use super::props::{Entry, Props};
use super::xml::Source;
use crate::scene::{look_at, Crop, FilmMode, Filter, Projection, SamplerKind, Sensor};
use anyhow::{bail, Result};
use glam::{Mat4, Vec3};

/// Mitsuba's `math::RayEpsilon` for f32 (1500 · 2⁻²⁴): how far along its direction a radiance
/// meter's ray starts.
const RAY_EPSILON: f32 = 1500.0 / 16_777_216.0;

/// Mitsuba rejects scaled camera transforms; normalising the axes gives the same rays.
fn without_scale(m: Mat4) -> Mat4 {
    Mat4::from_cols(
        m.x_axis.truncate().normalize().extend(0.0),
        m.y_axis.truncate().normalize().extend(0.0),
        m.z_axis.truncate().normalize().extend(0.0),
        m.w_axis,
    )
}

/// Mitsuba's default perspective sensor: 768×576 film, a 50 mm focal length (38.18° horizontal),
/// Gaussian filter, independent sampler at 4 spp.
pub fn default_sensor() -> Sensor {
    Sensor {
        projection: Projection::Perspective,
        to_world: Mat4::IDENTITY,
        fov_x: focal_length_fov(50.0, 768.0 / 576.0) as f32,
        near_clip: 0.01,
        far_clip: 10_000.0,
        principal_point_offset: [0.0; 2],
        width: 768,
        height: 576,
        crop: None,
        filter: Filter::Gaussian { stddev: 0.5, radius: 2.0 },
        sampler: SamplerKind::Independent,
        spp: 4,
        film: FilmMode::Splat,
    }
}

/// The horizontal field of view (degrees) that Mitsuba 3.9.1 gives a projective camera on a film of
/// `aspect` = width / height: from `fov` along `fov_axis` (x, y, diagonal, smaller, larger; default x,
/// case-insensitive), or, without `fov`, from `focal_length` (default "50mm", a 35 mm-equivalent focal
/// length on the 36×24 mm frame's diagonal; `fov_axis` is then not read). Mitsuba refuses both at once.
pub(crate) fn horizontal_fov(props: &Props, aspect: f64) -> Result<f32> {
    let has_fov = props.has("fov");
    let has_focal = props.has("focal_length");
    if has_fov && has_focal {
        bail!("{}: give either 'fov' or 'focal_length', not both (as Mitsuba)", props.loc);
    }
    let (fov, axis) = if has_fov {
        let fov = props.float("fov", 0.0)? as f64;
        let axis = props.string("fov_axis")?.unwrap_or_else(|| "x".to_string()).to_lowercase();
        let axis = match axis.as_str() {
            "smaller" if aspect > 1.0 => "y".to_string(),
            "smaller" => "x".to_string(),
            "larger" if aspect > 1.0 => "x".to_string(),
            "larger" => "y".to_string(),
            _ => axis,
        };
        (fov, axis)
    } else {
        let text = props.string("focal_length")?.unwrap_or_else(|| "50mm".to_string());
        let number = text.trim().strip_suffix("mm").unwrap_or(text.trim());
        let focal: f64 = match number.trim().parse() {
            Ok(f) if f > 0.0 && f64::is_finite(f) => f,
            _ => bail!(
                "{}: focal_length must be a positive length in mm like \"35mm\", not '{text}'",
                props.loc
            ),
        };
        let diagonal_fov = 2.0 * (FRAME_DIAGONAL_MM / (2.0 * focal)).atan().to_degrees();
        (diagonal_fov, "diagonal".to_string())
    };
    let Some(fov_x) = fov_along_x(fov, &axis, aspect) else {
        bail!("{}: fov_axis must be x, y, diagonal, smaller or larger, not '{axis}'", props.loc)
    };
    if !(fov > 0.0 && fov < 180.0 && fov_x > 0.0 && fov_x < 180.0) {
        bail!("{}: the field of view must be in (0, 180) degrees, got {fov} ({fov_x} horizontal)", props.loc);
    }
    Ok(fov_x as f32)
}

/// The diagonal of the 36×24 mm frame that `focal_length` refers to.
const FRAME_DIAGONAL_MM: f64 = 43.266_615_305_567_87;

/// The horizontal fov (degrees) of a 35 mm-equivalent `focal_mm` lens on a film of `aspect`.
fn focal_length_fov(focal_mm: f64, aspect: f64) -> f64 {
    let diagonal_fov = 2.0 * (FRAME_DIAGONAL_MM / (2.0 * focal_mm)).atan().to_degrees();
    fov_along_x(diagonal_fov, "diagonal", aspect).unwrap_or(diagonal_fov)
}

/// `fov` degrees along `axis` (x, y or diagonal) as a horizontal fov on a film of `aspect`.
fn fov_along_x(fov: f64, axis: &str, aspect: f64) -> Option<f64> {
    let tan_half = (fov.to_radians() * 0.5).tan();
    let tan_half_x = match axis {
        "x" => return Some(fov),
        "y" => tan_half * aspect,
        "diagonal" => tan_half / (1.0 + 1.0 / (aspect * aspect)).sqrt(),
        _ => return None,
    };
    Some(2.0 * tan_half_x.atan().to_degrees())
}

impl Loader {
    pub(crate) fn load_sensor(&mut self, props: &Props) -> Result<Sensor> {
        let mut sensor = default_sensor();
        if props.kind == "irradiancemeter" {
            bail!(
                "{}: the irradiancemeter measures over a shape: nest it in the <shape> (Mitsuba takes it from there)",
                props.loc
            );
        }
        if !matches!(props.kind.as_str(), "perspective" | "thinlens" | "orthographic" | "radiancemeter") {
            let message = format!(
                "{}: sensor type '{}' is not supported yet; using perspective",
                props.loc, props.kind
            );
            self.substituted(format!("sensor '{}'", props.kind), &props.loc, message);
        }
        self.load_film_and_sampler(props, &mut sensor)?;
        if props.kind == "radiancemeter" {
            sensor.to_world = without_scale(self.radiancemeter(props, &mut sensor)?);
            self.warn_unused(props);
            return Ok(sensor);
        }
        if props.kind != "orthographic" {
            sensor.fov_x = horizontal_fov(props, sensor.width as f64 / sensor.height as f64)?;
        }
        sensor.near_clip = props.float("near_clip", 0.01)?;
        sensor.far_clip = props.float("far_clip", 10_000.0)?;
        if !(sensor.near_clip > 0.0 && sensor.far_clip > sensor.near_clip) {
            bail!("{}: need 0 < near_clip < far_clip", props.loc);
        }
        let to_world = props.transform("to_world")?;
        sensor.projection = match props.kind.as_str() {
            "thinlens" => {
                // As Mitsuba: the aperture has no default, the focal plane defaults to far_clip.
                if !props.has("aperture_radius") {
                    bail!("{}: thinlens needs 'aperture_radius' (Mitsuba gives it no default)", props.loc);
                }
                let aperture_radius = props.float("aperture_radius", 0.0)?;
                let focus_distance = props.float("focus_distance", sensor.far_clip)?;
                if !(aperture_radius >= 0.0 && focus_distance > 0.0) {
                    bail!("{}: thinlens needs aperture_radius ≥ 0 and focus_distance > 0", props.loc);
                }
                Projection::ThinLens { aperture_radius, focus_distance }
            }
            "orthographic" => {
                // The view volume spans [-1, 1] along local x (and the image's aspect along y) before
                // to_world's scale.
                let aspect = sensor.width as f32 / sensor.height as f32;
                let half_width = to_world.x_axis.truncate().length();
                let half_height = to_world.y_axis.truncate().length() / aspect;
                // A zero scale sees nothing: every ray starts on one line and the image is black.
                if !(half_width > 0.0
                    && half_height > 0.0
                    && half_width.is_finite()
                    && half_height.is_finite())
                {
                    bail!("{}: the orthographic camera's to_world scales x or y to {half_width} × {}: it sees nothing", props.loc, half_height * aspect);
                }
                Projection::Orthographic { half_width, half_height }
            }
            _ => {
                // Mitsuba reads the principal point for `perspective` only (and `focus_distance`
                // is meaningful only for thin-lens cameras).
                props.float("focus_distance", 0.0)?;
                let offset = [
                    props.float("principal_point_offset_x", 0.0)?,
                    props.float("principal_point_offset_y", 0.0)?,
                ];
                if !offset.iter().all(|o| o.is_finite()) {
                    bail!(
                        "{}: principal_point_offset_x/y must be finite numbers (got {offset:?})",
                        props.loc
                    );
                }
                sensor.principal_point_offset = offset;
                Projection::Perspective
            }
        };
        sensor.to_world = without_scale(to_world);
        self.warn_unused(props);
        Ok(sensor)
    }

    /// A sensor nested in shape `shape` (index into the loader's shapes), which must be Mitsuba's
    /// `irradiancemeter` (`src/sensors/irradiancemeter.cpp`): the irradiance averaged over the
    /// shape's surface. Like Mitsuba it takes its placement from the shape (a `to_world` is refused)
    /// and measures the same value in every pixel of whatever film it has (its documentation asks for
    /// 1×1).
    pub(crate) fn load_shape_sensor(&mut self, props: &Props, shape: usize) -> Result<Sensor> {
        if props.kind != "irradiancemeter" {
            bail!(
                "{}: a sensor inside a shape must be an irradiancemeter, not '{}' (Mitsuba attaches no other sensor to a shape)",
                props.loc,
                props.kind
            );
        }
        if props.has("to_world") {
            bail!(
                "{}: the irradiancemeter takes its placement from its shape: a 'to_world' is not allowed (Mitsuba refuses it too)",
                props.loc
            );
        }
        let mut sensor = default_sensor();
        self.load_film_and_sampler(props, &mut sensor)?;
        if sensor.filter.radius() > 0.5 + RAY_EPSILON {
            self.warn(&format!(
                "{}: Mitsuba advises a reconstruction filter of radius 0.5 or less (e.g. box) for the irradiancemeter",
                props.loc
            ));
        }
        sensor.projection = Projection::IrradianceMeter { shape };
        self.warn_unused(props);
        Ok(sensor)
    }

    /// A sensor's film and sampler, nested or `<ref>`ed.
    fn load_film_and_sampler(&mut self, props: &Props, sensor: &mut Sensor) -> Result<()> {
        for e in props.nested("film") {
            let film = self.props(props.src, e.node)?;
            self.load_film(&film, sensor)?;
        }
        for e in props.nested("sampler") {
            let sampler = self.props(props.src, e.node)?;
            self.load_sampler(&sampler, sensor)?;
        }
        for e in props.nested("ref") {
            self.referenced_part(props, e, &["film", "sampler"], sensor)?;
        }
        Ok(())
    }

    /// The top-level element a `<ref>` inside a sensor or film names (`named_sensor_parts`), loaded
    /// as if it were nested there when its tag is among `tags`; anything else is reported as ignored.
    fn referenced_part(
        &mut self,
        parent: &Props,
        e: &Entry,
        tags: &[&str],
        sensor: &mut Sensor,
    ) -> Result<()> {
        let id = self.attribute(e.node, "id", &e.loc)?.unwrap_or_default();
        let part = self.named_sensor_parts.get(&id).cloned();
        let Some((path, text)) = part else {
            let message = format!(
                "{}: <ref id=\"{id}\"> names no {} defined before it; ignored",
                e.loc,
                tags.join(" or ")
            );
            self.ignored(format!("<ref> inside {} '{}'", parent.tag, parent.kind), &e.loc, message);
            return Ok(());
        };
        let src = Source::parse(&path, &text)?;
        let p = self.props(&src, src.doc.root_element())?;
        match p.tag.as_str() {
            "film" if tags.contains(&"film") => self.load_film(&p, sensor),
            "sampler" if tags.contains(&"sampler") => self.load_sampler(&p, sensor),
            "rfilter" if tags.contains(&"rfilter") => self.load_rfilter(&p, sensor),
            other => bail!("{}: <ref id=\"{id}\"> names a <{other}>, which does not belong here", e.loc),
        }
    }

    /// Mitsuba's `radiancemeter` (`src/sensors/radiancemeter.cpp`): the ray from the origin along
    /// local +z of `to_world`, or from `origin` along `direction` (both or neither; `to_world` wins
    /// over them); returns the sensor's transform. Its film must be one pixel wide or high, as
    /// Mitsuba requires; its ray starts Mitsuba's ray epsilon along the direction.
    fn radiancemeter(&mut self, props: &Props, sensor: &mut Sensor) -> Result<Mat4> {
        if sensor.width != 1 && sensor.height != 1 {
            bail!(
                "{}: the radiancemeter measures one ray: its film must be 1 pixel wide or high (Mitsuba refuses {}×{})",
                props.loc,
                sensor.width,
                sensor.height
            );
        }
        if sensor.filter.radius() > 0.5 + RAY_EPSILON {
            self.warn(&format!(
                "{}: Mitsuba advises a reconstruction filter of radius 0.5 or less (e.g. box) for the radiancemeter",
                props.loc
            ));
        }
        sensor.projection = Projection::RadianceMeter;
        sensor.near_clip = RAY_EPSILON;
        sensor.far_clip = f32::MAX;
        if props.has("to_world") {
            props.mark_used("origin");
            props.mark_used("direction");
            return props.transform("to_world");
        }
        if props.has("origin") != props.has("direction") {
            bail!("{}: the radiancemeter needs both 'origin' and 'direction', or neither", props.loc);
        }
        if !props.has("direction") {
            return Ok(Mat4::IDENTITY);
        }
        let origin = props.point("origin", Vec3::ZERO)?;
        let direction = props.point("direction", Vec3::Z)?;
        let up = direction.normalize_or_zero().any_orthonormal_vector();
        look_at(origin, origin + direction, up)
            .ok_or_else(|| anyhow::anyhow!("{}: the radiancemeter's 'direction' must not be zero", props.loc))
    }

    fn load_film(&mut self, props: &Props, sensor: &mut Sensor) -> Result<()> {
        if props.kind != "hdrfilm" {
            let message = format!("{}: film type '{}' is treated as hdrfilm", props.loc, props.kind);
            self.substituted(format!("film '{}'", props.kind), &props.loc, message);
        }
        let width = props.integer("width", 768)?;
        let height = props.integer("height", 576)?;
        if !(1..=32768).contains(&width) || !(1..=32768).contains(&height) {
            bail!("{}: film size must be between 1 and 32768 pixels, got {width}×{height}", props.loc);
        }
        sensor.width = width as u32;
        sensor.height = height as u32;
        sensor.crop = self.load_crop(props, sensor.width, sensor.height)?;
        for e in props.nested("rfilter") {
            let f = self.props(props.src, e.node)?;
            self.load_rfilter(&f, sensor)?;
        }
        for e in props.nested("ref") {
            self.referenced_part(props, e, &["rfilter"], sensor)?;
        }
        for name in ["pixel_format", "component_format", "file_format"] {
            props.string(name)?; // output format choices: caustic writes what -o names
        }
        self.warn_unused(props);
        Ok(())
    }

    /// A film's reconstruction filter.
    fn load_rfilter(&mut self, f: &Props, sensor: &mut Sensor) -> Result<()> {
        sensor.filter = match f.kind.as_str() {
            // Mitsuba's box filter has no parameter: its radius is half a pixel.
            "box" => Filter::Box { radius: 0.5 },
            "tent" => Filter::Tent { radius: f.float("radius", 1.0)? },
            "gaussian" => {
                let stddev = f.float("stddev", 0.5)?;
                Filter::Gaussian { stddev, radius: 4.0 * stddev }
            }
            "mitchell" => Filter::Mitchell { b: f.float("B", 1.0 / 3.0)?, c: f.float("C", 1.0 / 3.0)? },
            "catmullrom" => Filter::Mitchell { b: 0.0, c: 0.5 },
            "lanczos" => {
                let lobes = f.integer("lobes", 3)?;
                if !(1..=16).contains(&lobes) {
                    bail!("{}: lanczos 'lobes' must be between 1 and 16, got {lobes}", f.loc);
                }
                Filter::Lanczos { lobes: lobes as u32 }
            }
            other => {
                let message = format!("{}: rfilter '{other}' is not supported; using gaussian", f.loc);
                self.substituted(format!("rfilter '{other}'"), &f.loc, message);
                f.mark_all_used();
                Filter::Gaussian { stddev: 0.5, radius: 2.0 }
            }
        };
        if !(sensor.filter.radius() > 0.0 && sensor.filter.radius() <= 16.0) {
            bail!("{}: filter radius must be in (0, 16] pixels", f.loc);
        }
        self.warn_unused(f);
        Ok(())
    }

    /// Mitsuba's `crop_offset_x/y`, `crop_width/height`: render only that window of the image.
    fn load_crop(&mut self, props: &Props, width: u32, height: u32) -> Result<Option<Crop>> {
        let x = props.integer("crop_offset_x", 0)?;
        let y = props.integer("crop_offset_y", 0)?;
        let w = props.integer("crop_width", width as i64)?;
        let h = props.integer("crop_height", height as i64)?;
        // Checked sums: an offset near i64::MAX wrapped past the test and gave a window outside the film.
        let outside =
            |offset: i64, size: i64, film: u32| offset.checked_add(size).is_none_or(|end| end > film as i64);
        if x < 0 || y < 0 || w < 1 || h < 1 || outside(x, w, width) || outside(y, h, height) {
            bail!(
                "{}: the crop window ({x}, {y}) + {w}×{h} must lie inside the {width}×{height} film",
                props.loc
            );
        }
        let crop = Crop { x: x as u32, y: y as u32, width: w as u32, height: h as u32 };
        Ok((crop != Crop { x: 0, y: 0, width, height }).then_some(crop))
    }

    fn load_sampler(&mut self, props: &Props, sensor: &mut Sensor) -> Result<()> {
        let kind = props.kind.as_str();
        sensor.sampler = match kind {
            "independent" => SamplerKind::Independent,
            // Mitsuba's stratified, multi-jittered, orthogonal-array and low-discrepancy samplers
            // all stratify the pixel; caustic's stratified sequence stands in for each (the image
            // converges to the same; the noise differs).
            "stratified" | "multijitter" | "orthogonal" | "ldsampler" => SamplerKind::Stratified,
            other => {
                let message = format!("{}: sampler '{other}' is not supported; using stratified", props.loc);
                self.substituted(format!("sampler '{other}'"), &props.loc, message);
                SamplerKind::Stratified
            }
        };
        let requested = props.integer("sample_count", 4)?;
        if !(1..=1 << 24).contains(&requested) {
            bail!("{}: sample_count must be in [1, 16777216], got {requested}", props.loc);
        }
        sensor.spp = mitsuba_sample_count(kind, requested as u32);
        props.integer("seed", 0)?;
        if matches!(kind, "stratified" | "multijitter" | "orthogonal") {
            props.boolean("jitter", true)?;
        }
        if kind == "orthogonal" {
            props.integer("strength", 2)?;
        }
        self.warn_unused(props);
        Ok(())
    }
}

/// The sample count Mitsuba 3.9.1's sampler `kind` takes for a requested `n`: stratified rounds up to
/// a square, orthogonal to the square of a prime, ldsampler to a power of four (at least 4),
/// multijitter to a near-square grid (⌊√n⌋ rows).
fn mitsuba_sample_count(kind: &str, n: u32) -> u32 {
    let is_prime = |x: u32| (2..=x / 2).all(|i| !x.is_multiple_of(i));
    match kind {
        "stratified" => {
            let r = (1u32..).find(|r| r * r >= n).unwrap_or(1);
            r * r
        }
        "orthogonal" => {
            let r = (2u32..).find(|&r| r * r >= n && is_prime(r)).unwrap_or(2);
            r * r
        }
        "ldsampler" => {
            let mut r = 2u32;
            while r * r < n {
                r = (r + 1).next_power_of_two();
            }
            r * r
        }
        "multijitter" => {
            let rows = ((n as f32).sqrt() as u32).max(1);
            n.div_ceil(rows) * rows
        }
        _ => n,
    }
}
