//! Emitters at infinity: `constant` (uniform radiance from every direction, sampled uniformly on the
//! sphere) and `envmap` (a lat-long image in Mitsuba's convention, importance-sampled in proportion
//! to luminance·sin θ interpolated bilinearly between its texels, as its radiance is: a cell between
//! four texels is chosen from the host's tables (`prepare::lights`), then a point in it from the
//! bilinear density of its corners. Sampled uniformly inside each cell instead, the error per sample
//! of the material previews under `museum.exr` was 1.037× Mitsuba's against 0.995× for the same
//! scene under a constant sky (BENCHMARKS.md, "The 23 shared scenes").
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::{beyond_scene, radiance, to_local, to_world, LightSample};
use crate::features;
use crate::glam::{Vec2, Vec3};
use crate::layout::{Light, SceneView, Texture, LIGHT_ENVMAP, NONE};
use crate::math::{INV_2PI, INV_4PI, INV_PI, PI};
use crate::sampling::{linear_pdf, sample_cdf, sample_linear, square_to_uniform_sphere};
use crate::spectrum::{luminance, Rgb};
use crate::texture::{rem, texel};

/// Radiance arriving from direction `dir` (the direction a ray escaping the scene travels).
pub fn eval(light: &Light, scene: &SceneView, dir: Vec3) -> Rgb {
    if light.kind == LIGHT_ENVMAP && features::has(scene.features, features::light(LIGHT_ENVMAP)) {
        let t = scene.textures[light.prim as usize];
        envmap_radiance(&t, scene.tables, direction_to_uv(to_local(light, dir))) * radiance(light)
    } else {
        radiance(light)
    }
}

/// Solid-angle density of `sample_*` producing `dir`, without the selection probability.
pub fn pdf(light: &Light, scene: &SceneView, dir: Vec3) -> f32 {
    if light.kind == LIGHT_ENVMAP && features::has(scene.features, features::light(LIGHT_ENVMAP)) {
        envmap_pdf(light, scene, dir)
    } else {
        INV_4PI
    }
}

fn envmap_pdf(light: &Light, scene: &SceneView, dir: Vec3) -> f32 {
    let t = scene.textures[light.prim as usize];
    let local = to_local(light, dir);
    let sin_theta = (local.x * local.x + local.z * local.z).sqrt();
    let (col, row, at) = envmap_cell(&t, direction_to_uv(local));
    let corners = cell_corners(light, &t, scene.tables, col, row);
    let pdf =
        cell_pmf(&t, scene.tables, light.table, col, row) * in_cell_density(corners, at) * cell_count(&t)
            / (2.0 * PI * PI * sin_theta.max(1e-20));
    if sin_theta > 0.0 {
        pdf
    } else {
        0.0
    }
}

pub fn sample_constant(light: &Light, p: Vec3, u: Vec2) -> LightSample {
    let wi = square_to_uniform_sphere(u);
    LightSample {
        wi,
        dist: beyond_scene(light, p),
        radiance: radiance(light),
        pdf: INV_4PI,
        delta: false,
        prim: NONE,
        light: NONE,
    }
}

pub fn sample_envmap(light: &Light, scene: &SceneView, p: Vec3, u: Vec2) -> LightSample {
    let t = scene.textures[light.prim as usize];
    let (rows, cols) = (t.height - 1, t.width);
    let row = sample_cdf(scene.tables, light.table, rows, u.y);
    let col = sample_cdf(scene.tables, conditional_offset(&t, light.table, row.index), cols, u.x);
    // The point in the cell: its row position from the density of the two rows of corners, then its
    // column position from the density along that row.
    let c = cell_corners(light, &t, scene.tables, col.index, row.index);
    let y = sample_linear(row.remapped, c[0] + c[1], c[2] + c[3]);
    let x = sample_linear(col.remapped, c[0] + (c[2] - c[0]) * y, c[1] + (c[3] - c[1]) * y);
    // Cell (c, r) spans u from texel centre c to c + 1 and v from texel row r to r + 1.
    let uv = Vec2::new((col.index as f32 + 0.5 + x) / cols as f32, (row.index as f32 + y) / rows as f32);
    let theta = uv.y * PI;
    let phi = uv.x * 2.0 * PI;
    let sin_theta = theta.sin();
    if sin_theta <= 0.0 {
        return LightSample::none();
    }
    let local = Vec3::new(phi.sin() * sin_theta, theta.cos(), -phi.cos() * sin_theta);
    let pdf = cell_pmf(&t, scene.tables, light.table, col.index, row.index)
        * in_cell_density(c, Vec2::new(x, y))
        * cell_count(&t)
        / (2.0 * PI * PI * sin_theta);
    if pdf <= 0.0 {
        return LightSample::none();
    }
    let wi = to_world(light, local);
    let radiance = envmap_radiance(&t, scene.tables, uv) * radiance(light);
    LightSample { wi, dist: beyond_scene(light, p), radiance, pdf, delta: false, prim: NONE, light: NONE }
}

/// Mitsuba's lat-long parametrisation: u from the azimuth about +y (0 at -z), v = θ / π from +y.
#[inline]
fn direction_to_uv(d: Vec3) -> Vec2 {
    Vec2::new(d.x.atan2(-d.z) * INV_2PI, d.y.clamp(-1.0, 1.0).acos() * INV_PI)
}

#[inline]
fn cell_count(t: &Texture) -> f32 {
    (t.width * (t.height - 1)) as f32
}

/// The cell containing `uv` and the position in it (each coordinate in [0, 1]): columns start at
/// texel centres (wrapping in u), rows at texel rows.
fn envmap_cell(t: &Texture, uv: Vec2) -> (u32, u32, Vec2) {
    let w = t.width as f32;
    let x = uv.x * w - 0.5;
    let x = x - (x / w).floor() * w;
    let col = (x as u32).min(t.width - 1);
    let y = uv.y * (t.height - 1) as f32;
    let row = (y as u32).min(t.height - 2);
    let at = Vec2::new((x - col as f32).clamp(0.0, 1.0), (y - row as f32).clamp(0.0, 1.0));
    (col, row, at)
}

/// What the host's tables weight texel (`x`, `y`) by: its luminance above the MIS compensation's
/// offset (`Light::params[0]`), times sin θ of its row (`prepare::lights::envmap_distribution`).
fn texel_weight(light: &Light, t: &Texture, tables: &[f32], x: u32, y: u32) -> f32 {
    let sin_theta = (PI * y as f32 / (t.height - 1) as f32).sin();
    (luminance(texel(t, tables, x, y)).max(0.0) - light.params[0]).max(0.0) * sin_theta
}

/// The weights of cell (`col`, `row`)'s corners: upper left, upper right, lower left, lower right
/// (upper: row `row`, nearer +y).
fn cell_corners(light: &Light, t: &Texture, tables: &[f32], col: u32, row: u32) -> [f32; 4] {
    let next = (col + 1) % t.width;
    [
        texel_weight(light, t, tables, col, row),
        texel_weight(light, t, tables, next, row),
        texel_weight(light, t, tables, col, row + 1),
        texel_weight(light, t, tables, next, row + 1),
    ]
}

/// The density of a point `at` of a cell with corner weights `c`, relative to the uniform one: the
/// bilinear interpolant over its mean (1 where the corners weigh nothing: the cell is then sampled
/// uniformly, if at all), as `sample_envmap` draws it.
fn in_cell_density(c: [f32; 4], at: Vec2) -> f32 {
    linear_pdf(at.y, c[0] + c[1], c[2] + c[3])
        * linear_pdf(at.x, c[0] + (c[2] - c[0]) * at.y, c[1] + (c[3] - c[1]) * at.y)
}

#[inline]
fn conditional_offset(t: &Texture, table: u32, row: u32) -> u32 {
    table + (t.height - 1) + row * t.width
}

/// Probability of the cell: the marginal row probability times the conditional column probability,
/// read back from the inclusive CDFs.
fn cell_pmf(t: &Texture, tables: &[f32], table: u32, col: u32, row: u32) -> f32 {
    let row_pmf = cdf_step(tables, table, row);
    let col_pmf = cdf_step(tables, conditional_offset(t, table, row), col);
    row_pmf * col_pmf
}

#[inline]
fn cdf_step(tables: &[f32], first: u32, i: u32) -> f32 {
    let prev = if i == 0 { 0.0 } else { tables[(first + i - 1) as usize] };
    tables[(first + i) as usize] - prev
}

/// Mitsuba's envmap lookup: bilinear between texels, whose centres sit at u = (x + ½) / width
/// (wrapping) and v = y / (height - 1) (clamped at the poles).
fn envmap_radiance(t: &Texture, tables: &[f32], uv: Vec2) -> Rgb {
    let w = t.width;
    let u = uv.x - uv.x.floor();
    let v = uv.y.clamp(0.0, 1.0);
    let px = u * w as f32 - 0.5;
    let py = v * (t.height - 1) as f32;
    let (x0f, y0f) = (px.floor(), py.floor());
    let (fx, fy) = (px - x0f, py - y0f);
    let xa = rem((x0f as i32 + w as i32) as u32, w);
    let xb = rem(xa + 1, w);
    let ya = (y0f as u32).min(t.height - 1);
    let yb = (ya + 1).min(t.height - 1);
    let top = texel(t, tables, xa, ya) * (1.0 - fx) + texel(t, tables, xb, ya) * fx;
    let bottom = texel(t, tables, xa, yb) * (1.0 - fx) + texel(t, tables, xb, yb) * fx;
    top * (1.0 - fy) + bottom * fy
}
