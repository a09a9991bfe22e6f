//! Light records: the emitters that are not shapes (points, spots, projectors, directional, constant
//! and envmap, with its sampling tables), the selection probabilities over all lights, and the
//! power of two that scales the brightest emission to about 1 for squaring.
use super::materials::texels;
use crate::scene::{rgba, Emitter, IntegratorKind, Scene};
use caustic_kernel::layout::*;
use caustic_kernel::spectrum::luminance;
use glam::{Mat3, Vec3};
use std::f32::consts::PI;

/// Lights with their power and the emitter (shape or emitter element) each belongs to, for selection.
#[derive(Default)]
pub(crate) struct LightList {
    pub(crate) lights: Vec<Light>,
    powers: Vec<f32>,
    emitters: Vec<u32>,
    emitter_count: u32,
}

/// Light tracing's share of the selection probability spread evenly over emitters; the rest follows
/// power. Light paths are started where the power is, but power alone starves an emitter that is weak
/// overall and dominant somewhere (a spot light beside a sky, a small lamp beside a large one:
/// Veach's MIS scene) of samples, and that region's noise explodes.
pub(super) const LIGHT_TRACING_UNIFORM_SHARE: f64 = 0.5;

impl LightList {
    /// Starts a new emitter: the lights pushed until the next call belong to it.
    pub(super) fn begin_emitter(&mut self) {
        self.emitter_count += 1;
    }

    pub(super) fn push(&mut self, light: Light, power: f32) -> u32 {
        self.lights.push(light);
        self.powers.push(if power.is_finite() { power.max(0.0) } else { 0.0 });
        self.emitters.push(self.emitter_count - 1);
        self.lights.len() as u32 - 1
    }

    /// Selection weights: a mixture of power-proportional selection and a uniform choice of emitter
    /// followed by power-proportional selection among its lights (the triangles of a mesh emitter),
    /// `uniform_share` of the latter.
    ///
    /// Next-event estimation takes `uniform_share` 1, as Mitsuba's `path` and `direct` do (every
    /// emitter equally likely): the half-and-half mixture light tracing uses gave
    /// `emitter_spot_no_texture` (two spot lights beside a sky) 2.3x Mitsuba's MSE at equal spp, each
    /// spot being chosen a sixth of the time instead of a third (BENCHMARKS.md, "The 23 shared scenes").
    pub(super) fn selection_weights(&self, uniform_share: f64) -> Vec<f64> {
        let total: f64 = self.powers.iter().map(|&p| p as f64).sum();
        let mut per_emitter = vec![0.0f64; self.emitter_count as usize];
        let mut lights_per_emitter = vec![0u32; self.emitter_count as usize];
        for (&p, &e) in self.powers.iter().zip(&self.emitters) {
            per_emitter[e as usize] += p as f64;
            lights_per_emitter[e as usize] += 1;
        }
        let n = self.emitter_count.max(1) as f64;
        self.powers
            .iter()
            .zip(&self.emitters)
            .map(|(&p, &e)| {
                let by_power = if total > 0.0 { p as f64 / total } else { 0.0 };
                let group = per_emitter[e as usize];
                let within =
                    if group > 0.0 { p as f64 / group } else { 1.0 / lights_per_emitter[e as usize] as f64 };
                (1.0 - uniform_share) * by_power + uniform_share * within / n
            })
            .collect()
    }
}

/// Normalised inclusive CDF of non-negative weights (uniform when they sum to zero).
pub(crate) fn cdf_of(weights: &[f64]) -> Vec<f32> {
    let total: f64 = weights.iter().sum();
    let n = weights.len() as f64;
    let mut running = 0.0f64;
    let mut cdf: Vec<f32> = weights
        .iter()
        .map(|&w| {
            running += if total > 0.0 { w / total } else { 1.0 / n };
            running as f32
        })
        .collect();
    if let Some(last) = cdf.last_mut() {
        *last = 1.0;
    }
    cdf
}

fn rows_of(m: Mat3) -> [[f32; 4]; 3] {
    [0, 1, 2].map(|r| m.row(r).extend(0.0).to_array())
}

/// An envmap's sampling tables (marginal CDF over the `height - 1` cell rows, then one conditional
/// CDF of `width` cells per row; see `light::infinite`), its power per unit scale and area, and the
/// luminance its tables leave out of every texel: with `compensate`, they follow the luminance above
/// the texels' mean (`mis_compensation`), else 0. The kernel samples inside a cell from the same
/// texel weights, so the offset travels with the light (`Light::params[0]`).
fn envmap_distribution(t: &Texture, texels: &[f32], compensate: bool) -> (Vec<f32>, f32, f32) {
    let (w, h) = (t.width as usize, t.height as usize);
    let luminances: Vec<f64> =
        texels.chunks_exact(3).map(|c| luminance(Vec3::from_slice(c)).max(0.0) as f64).collect();
    let offset = if compensate { compensation_offset(&luminances) } else { 0.0 };
    let lum = |x: usize, y: usize| luminances[y * w + x];
    let sin_theta = |y: usize| (PI as f64 * y as f64 / (h - 1) as f64).sin();
    // Each cell's mean over its four corners, weighted by sin θ (dω = sin θ dθ dφ), less `offset`.
    let cell = |c: usize, r: usize, offset: f64| {
        let c1 = (c + 1) % w;
        let at = |x: usize, y: usize| (lum(x, y) - offset).max(0.0) * sin_theta(y);
        0.25 * (at(c, r) + at(c1, r) + at(c, r + 1) + at(c1, r + 1))
    };
    let mut marginal = Vec::with_capacity(h - 1);
    let mut conditional = Vec::with_capacity((h - 1) * w);
    let mut power = 0.0f64;
    for r in 0..h - 1 {
        let cells: Vec<f64> = (0..w).map(|c| cell(c, r, offset)).collect();
        power += (0..w).map(|c| cell(c, r, 0.0)).sum::<f64>();
        marginal.push(cells.iter().sum::<f64>());
        conditional.extend(cdf_of(&cells));
    }
    // ∫ luminance dω over the sphere, by the cells' mean values: the power light selection uses,
    // compensated or not.
    let cell_solid_angle = (2.0 * PI as f64 / w as f64) * (PI as f64 / (h - 1) as f64);
    let mut table = cdf_of(&marginal);
    table.extend(conditional);
    (table, (power * cell_solid_angle) as f32, offset as f32)
}

/// What MIS compensation subtracts from each texel's luminance: the mean over the texels, or
/// nothing when the map is nearly constant (mean − minimum within 1% of the mean), where it would
/// leave almost no direction to sample. Mitsuba's rule (`src/emitters/envmap.cpp`).
fn compensation_offset(luminances: &[f64]) -> f64 {
    let mean = luminances.iter().sum::<f64>() / luminances.len().max(1) as f64;
    let min = luminances.iter().copied().fold(f64::INFINITY, f64::min);
    if mean - min <= 0.01 * mean {
        0.0
    } else {
        mean
    }
}

/// Light records of the emitters that are not shapes; returns the environment light's index.
pub(super) fn emitter_lights(
    scene: &Scene,
    kind: IntegratorKind,
    textures: &[Texture],
    tables: &mut Vec<f32>,
    lights: &mut LightList,
    (centre, radius): (Vec3, f32),
) -> u32 {
    let mut env_light = NONE;
    let disk_area = PI * radius * radius;
    let bsphere = [centre.x, centre.y, centre.z, radius];
    for e in &scene.emitters {
        let mut light = Light { prim: NONE, table: NONE, position: bsphere, ..Default::default() };
        let power = match e {
            Emitter::Point { position, intensity } => {
                light.kind = LIGHT_POINT;
                light.radiance = rgba(*intensity);
                light.position = position.extend(0.0).to_array();
                4.0 * PI * luminance(Vec3::from(*intensity))
            }
            Emitter::Spot { to_world, intensity, cutoff_angle, beam_width, texture } => {
                let (cutoff, beam) =
                    (cutoff_angle.to_radians(), beam_width.to_radians().min(cutoff_angle.to_radians()));
                light.kind = LIGHT_SPOT;
                light.radiance = rgba(*intensity);
                light.position = to_world.w_axis.truncate().extend(0.0).to_array();
                let inv_transition = if cutoff > beam { 1.0 / (cutoff - beam) } else { 0.0 };
                light.params = [cutoff.cos(), beam.cos(), cutoff, inv_transition];
                light.to_local = rows_of(orthonormal(Mat3::from_mat4(*to_world)).transpose());
                light.texture = texture.unwrap_or(NONE);
                let mean = texture.map_or(1.0, |t| luminance(Vec3::from(scene.textures[t as usize].mean())));
                // Solid angle of the cone out to the middle of the falloff ramp.
                2.0 * PI * (1.0 - (0.5 * (cutoff + beam)).cos()) * luminance(Vec3::from(*intensity)) * mean
            }
            Emitter::Projector { to_world, irradiance, texture, fov_x, aspect } => {
                let tan_x = (0.5 * fov_x.to_radians()).tan();
                let tan_y = tan_x / aspect;
                let image_area = 4.0 * tan_x * tan_y;
                light.kind = LIGHT_PROJECTOR;
                light.radiance = rgba(*irradiance);
                light.texture = texture.unwrap_or(NONE);
                light.position = to_world.w_axis.truncate().extend(0.0).to_array();
                light.params = [tan_x, tan_y, 0.0, image_area];
                light.to_local = rows_of(orthonormal(Mat3::from_mat4(*to_world)).transpose());
                let mean = texture.map_or(1.0, |t| luminance(Vec3::from(scene.textures[t as usize].mean())));
                // Power: π · value · image area (`light::projector`).
                PI * image_area * luminance(Vec3::from(*irradiance)) * mean
            }
            Emitter::Directional { direction, irradiance } => {
                light.kind = LIGHT_DIRECTIONAL;
                light.radiance = rgba(*irradiance);
                light.to_local = rows_of(frame_with_z(direction.normalize()).transpose());
                disk_area * luminance(Vec3::from(*irradiance))
            }
            Emitter::Constant { radiance } => {
                light.kind = LIGHT_CONSTANT;
                light.radiance = rgba(*radiance);
                disk_area * 4.0 * PI * luminance(Vec3::from(*radiance))
            }
            Emitter::Envmap { texture, to_world, scale, mis_compensation } => {
                let t = &textures[*texture as usize];
                let texels = texels(t, tables);
                // Light tracing draws emission from these tables alone, with nothing to cover the
                // directions compensation leaves out: compensation is for NEE beside BSDF sampling.
                let compensate =
                    *mis_compensation && matches!(kind, IntegratorKind::Path | IntegratorKind::Direct { .. });
                let (table, integral, offset) = envmap_distribution(t, texels, compensate);
                light.kind = LIGHT_ENVMAP;
                light.params[0] = offset;
                light.prim = *texture;
                light.radiance = [*scale; 4];
                light.table = tables.len() as u32;
                light.to_local = rows_of(to_world.inverse());
                tables.extend(table);
                disk_area * scale * integral
            }
        };
        lights.begin_emitter();
        let index = lights.push(light, power);
        if matches!(e, Emitter::Constant { .. } | Emitter::Envmap { .. }) {
            env_light = index;
        }
    }
    env_light
}

/// Gram-Schmidt on the columns: rotations from transforms that may carry scale.
fn orthonormal(m: Mat3) -> Mat3 {
    let z = m.z_axis.normalize();
    let x = (m.x_axis - z * m.x_axis.dot(z)).normalize();
    Mat3::from_cols(x, z.cross(x), z)
}

/// A rotation whose third column is `z`.
fn frame_with_z(z: Vec3) -> Mat3 {
    let (x, y) = z.any_orthonormal_pair();
    Mat3::from_cols(x, y, z)
}

/// `FrameParams::square_scale_log2`: the power of two that brings the scene's brightest emission
/// (radiance, intensity or irradiance; an envmap's scale times its largest texel) to about 1, so
/// that samples up to ~1e19 times it square within f32's range (and samples down to 1e-19 of it
/// do not underflow). Radiance 1e30 squared in f32 was +Inf; 0 where nothing emits.
pub(super) fn square_scale_log2(lights: &[Light], textures: &[Texture], tables: &[f32]) -> i32 {
    let brightest = lights
        .iter()
        .map(|l| {
            let mut m = l.radiance[..3].iter().fold(0.0f64, |m, &c| m.max(c.abs() as f64));
            let texture = if l.kind == LIGHT_ENVMAP { l.prim } else { l.texture };
            if texture != NONE && textures[texture as usize].kind == TEXTURE_CHECKERBOARD {
                let t = &textures[texture as usize];
                m *= t.color0[..3].iter().chain(&t.color1[..3]).fold(0.0f64, |m, &c| m.max(c.abs() as f64));
            } else if texture != NONE {
                m *= texels(&textures[texture as usize], tables)
                    .iter()
                    .fold(0.0f64, |m, &c| m.max(c.abs() as f64));
            }
            m
        })
        .filter(|m| m.is_finite() && *m > 0.0)
        .fold(0.0f64, f64::max);
    if brightest > 0.0 {
        (-brightest.log2().round()).clamp(-100.0, 100.0) as i32
    } else {
        0
    }
}
