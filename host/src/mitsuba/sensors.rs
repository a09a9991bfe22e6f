//! Sensor plugins (`perspective`) with their film (`hdrfilm`), reconstruction filter (`box`, `tent`,
//! `gaussian`) and sampler (`independent`, `stratified`; others map to the nearest with a warning).
use super::props::Props;
use super::Loader;
use crate::scene::{Crop, Filter, Projection, SamplerKind, Sensor};
use anyhow::{bail, Result};
use glam::Mat4;

/// Mitsuba's defaults: 768×576, 39.3077° horizontal fov, Gaussian filter, 4 spp.
pub fn default_sensor() -> Sensor {
    Sensor {
        projection: Projection::Perspective,
        to_world: Mat4::IDENTITY,
        fov_x: 39.3077,
        near_clip: 0.01,
        far_clip: 10_000.0,
        width: 768,
        height: 576,
        crop: None,
        filter: Filter::Gaussian { stddev: 0.5, radius: 2.0 },
        sampler: SamplerKind::Independent,
        spp: 4,
    }
}

/// Converts Mitsuba's `fov` along `fov_axis` to the horizontal field of view (degrees).
fn horizontal_fov(fov: f32, axis: &str, width: u32, height: u32, props: &Props) -> Result<f32> {
    let aspect = width as f32 / height as f32;
    let axis = match axis {
        "smaller" => {
            if aspect > 1.0 {
                "y"
            } else {
                "x"
            }
        }
        "larger" => {
            if aspect > 1.0 {
                "x"
            } else {
                "y"
            }
        }
        other => other,
    };
    let half = (fov.to_radians() * 0.5).tan();
    let fov_x = match axis {
        "x" => fov,
        "y" => 2.0 * (half * aspect).atan().to_degrees(),
        "diagonal" => {
            let w = 2.0 * half / (1.0 + 1.0 / (aspect * aspect)).sqrt();
            2.0 * (w * 0.5).atan().to_degrees()
        }
        other => bail!("{}: fov_axis must be x, y, diagonal, smaller or larger, not '{other}'", props.loc),
    };
    Ok(fov_x)
}

impl Loader {
    pub(crate) fn load_sensor(&mut self, props: &Props) -> Result<Sensor> {
        let mut sensor = default_sensor();
        if !matches!(props.kind.as_str(), "perspective" | "thinlens" | "orthographic") {
            self.warn(&format!(
                "{}: sensor type '{}' is not supported yet; using perspective",
                props.loc, props.kind
            ));
        }
        for e in props.nested("film") {
            let film = self.props(props.src, e.node)?;
            self.load_film(&film, &mut sensor)?;
        }
        for e in props.nested("sampler") {
            let sampler = self.props(props.src, e.node)?;
            self.load_sampler(&sampler, &mut sensor)?;
        }
        if props.kind != "orthographic" {
            let fov = props.float("fov", 39.3077)?;
            if !(fov > 0.0 && fov < 180.0) {
                bail!("{}: fov must be in (0, 180) degrees, got {fov}", props.loc);
            }
            let axis = props.string("fov_axis")?.unwrap_or_else(|| "x".to_string());
            sensor.fov_x = horizontal_fov(fov, &axis, sensor.width, sensor.height, props)?;
        }
        sensor.near_clip = props.float("near_clip", 0.01)?;
        sensor.far_clip = props.float("far_clip", 10_000.0)?;
        if !(sensor.near_clip > 0.0 && sensor.far_clip > sensor.near_clip) {
            bail!("{}: need 0 < near_clip < far_clip", props.loc);
        }
        let to_world = props.transform("to_world")?;
        sensor.projection = match props.kind.as_str() {
            "thinlens" => {
                let aperture_radius = props.float("aperture_radius", 0.0)?;
                let focus_distance = props.float("focus_distance", 0.0)?;
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
                props.float("focus_distance", 0.0)?; // meaningful only for thin-lens cameras
                Projection::Perspective
            }
        };
        // Mitsuba rejects scaled camera transforms; normalising the axes gives the same rays.
        sensor.to_world = Mat4::from_cols(
            to_world.x_axis.truncate().normalize().extend(0.0),
            to_world.y_axis.truncate().normalize().extend(0.0),
            to_world.z_axis.truncate().normalize().extend(0.0),
            to_world.w_axis,
        );
        self.warn_unused(props);
        Ok(sensor)
    }

    fn load_film(&mut self, props: &Props, sensor: &mut Sensor) -> Result<()> {
        if props.kind != "hdrfilm" {
            self.warn(&format!("{}: film type '{}' is treated as hdrfilm", props.loc, props.kind));
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
            sensor.filter = match f.kind.as_str() {
                "box" => Filter::Box { radius: f.float("radius", 0.5)? },
                "tent" => Filter::Tent { radius: f.float("radius", 1.0)? },
                "gaussian" => {
                    let stddev = f.float("stddev", 0.5)?;
                    Filter::Gaussian { stddev, radius: 4.0 * stddev }
                }
                other => {
                    self.warn(&format!("{}: rfilter '{other}' is not supported; using gaussian", f.loc));
                    f.mark_all_used();
                    Filter::Gaussian { stddev: 0.5, radius: 2.0 }
                }
            };
            if !(sensor.filter.radius() > 0.0 && sensor.filter.radius() <= 16.0) {
                bail!("{}: filter radius must be in (0, 16] pixels", f.loc);
            }
            self.warn_unused(&f);
        }
        for name in ["pixel_format", "component_format", "file_format"] {
            props.string(name)?; // output format choices: caustic writes what -o names
        }
        self.warn_unused(props);
        Ok(())
    }

    /// Mitsuba's `crop_offset_x/y`, `crop_width/height`: render only that window of the image.
    fn load_crop(&mut self, props: &Props, width: u32, height: u32) -> Result<Option<Crop>> {
        let x = props.integer("crop_offset_x", 0)?;
        let y = props.integer("crop_offset_y", 0)?;
        let w = props.integer("crop_width", width as i64)?;
        let h = props.integer("crop_height", height as i64)?;
        if x < 0 || y < 0 || w < 1 || h < 1 || x + w > width as i64 || y + h > height as i64 {
            bail!(
                "{}: the crop window ({x}, {y}) + {w}×{h} must lie inside the {width}×{height} film",
                props.loc
            );
        }
        let crop = Crop { x: x as u32, y: y as u32, width: w as u32, height: h as u32 };
        Ok((crop != Crop { x: 0, y: 0, width, height }).then_some(crop))
    }

    fn load_sampler(&mut self, props: &Props, sensor: &mut Sensor) -> Result<()> {
        sensor.sampler = match props.kind.as_str() {
            "independent" => SamplerKind::Independent,
            "stratified" => SamplerKind::Stratified,
            other => {
                self.warn(&format!("{}: sampler '{other}' is mapped to stratified", props.loc));
                SamplerKind::Stratified
            }
        };
        let spp = props.integer("sample_count", 4)?;
        if !(1..=1 << 24).contains(&spp) {
            bail!("{}: sample_count must be in [1, 16777216], got {spp}", props.loc);
        }
        sensor.spp = spp as u32;
        props.integer("seed", 0)?;
        props.boolean("jitter", true)?;
        props.integer("dimension", 0)?;
        self.warn_unused(props);
        Ok(())
    }
}
