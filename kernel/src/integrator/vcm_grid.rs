//! Vertex merging's hash grid over a pass's light vertex cache (`INTEGRATOR_VCM`), and the merge it
//! answers. The cache holds `MAX_LIGHT_VERTICES` slots per light path, one path per pixel (empty
//! slots have `depth` 0). Cells are twice the merging radius wide, so the sphere of radius `r`
//! around a point lies within the 2×2×2 cells nearest it; cells are hashed into as many buckets as
//! the cache has slots, and each bucket's vertices form a list, linked in one step over every slot
//! in parallel on both backends (`link`: an atomic exchange of the bucket's head), so that no prefix
//! sum over the buckets is needed.
//!
//! The grid's words, one `u32` buffer cleared before the pass: each bucket's head, then each slot's
//! successor in its bucket's list, both as a slot index plus one (0: the list ends).
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::bdpt::{bidirectional, within, CameraVertex, LightVertex, DISPERSED, MAX_LIGHT_VERTICES};
use super::bdpt_mis::{self, Merging};
use crate::bsdf::perturb::Shading;
use crate::bsdf::{Bsdf, TransportMode};
use crate::glam::Vec3;
use crate::layout::FrameParams;
use crate::shape::SurfacePoint;
use crate::spectrum::Rgb;
use crate::splat::AtomicWords;

/// The grid of a pass: its radius, cells per unit length and buckets.
#[derive(Clone, Copy)]
pub struct Grid {
    pub radius: f32,
    pub inv_cell: f32,
    pub buckets: u32,
}

impl Grid {
    #[inline]
    pub fn of(params: &FrameParams) -> Self {
        let radius = params.merge_radius;
        let inv_cell = if radius > 0.0 { 0.5 / radius } else { 0.0 };
        Grid { radius, inv_cell, buckets: slots(params) }
    }

    /// The grid's words (heads, then successors).
    #[inline]
    pub fn words(&self) -> u32 {
        2 * self.buckets
    }

    /// The bucket of cell (`x`, `y`, `z`): Teschner et al.'s spatial hash.
    #[inline]
    fn bucket_of_cell(&self, x: i32, y: i32, z: i32) -> u32 {
        let h = (x as u32).wrapping_mul(73_856_093)
            ^ (y as u32).wrapping_mul(19_349_663)
            ^ (z as u32).wrapping_mul(83_492_791);
        h % self.buckets
    }

    /// The bucket of the cell holding `p`.
    #[inline]
    fn bucket(&self, p: Vec3) -> u32 {
        let c = p * self.inv_cell;
        self.bucket_of_cell(c.x.floor() as i32, c.y.floor() as i32, c.z.floor() as i32)
    }
}

/// The light vertex cache's slots in a pass: `MAX_LIGHT_VERTICES` per pixel of the window.
#[inline]
pub fn slots(params: &FrameParams) -> u32 {
    params.width * params.height * MAX_LIGHT_VERTICES
}

/// Links cache slot `slot`'s vertex (if any) at the head of its bucket's list.
#[inline]
pub fn link<W: AtomicWords>(cache: &[LightVertex], grid: &Grid, slot: u32, words: &mut W) {
    let v = &cache[slot as usize];
    if v.depth > 0 {
        let next = words.exchange(grid.bucket(v.position()), slot + 1);
        words.exchange(grid.buckets + slot, next);
    }
}

/// The built grid over the cache, which camera paths merge with.
pub struct GridView<'a> {
    pub cache: &'a [LightVertex],
    pub words: &'a [u32],
    pub grid: Grid,
}

impl GridView<'_> {
    /// The merged estimate at the camera vertex `sp` (its `bsdf` and `shading`, its path state
    /// `camera`), before the camera path's throughput: every light vertex within the radius of `sp`
    /// whose path stays within `max_depth` and the bidirectional reach, the camera's BSDF towards
    /// where the light came from times the light path's throughput, over `π r² L` (`1/eta`), each
    /// weighted by `bdpt_mis::merge_weight`. The BSDF's cosine is the shading normal's, divided by the
    /// geometric normal's that the vertices' density per area carries (Veach's correction for shading
    /// normals, as light tracing applies it), and by the pass's wavelength's factor where either path
    /// dispersed. Nothing without merging (BDPT).
    #[allow(clippy::too_many_arguments)]
    pub fn merge(
        &self,
        bsdf: &Bsdf,
        shading: &Shading,
        sp: &SurfacePoint,
        camera: CameraVertex,
        max_depth: u32,
        merging: Merging,
    ) -> Rgb {
        let grid = self.grid;
        if !(merging.eta_sq > 0.0) || grid.buckets == 0 {
            return Rgb::ZERO;
        }
        let frame = shading.frame();
        let r_sq = grid.radius * grid.radius;
        let c = sp.p * grid.inv_cell - Vec3::splat(0.5);
        let (x0, y0, z0) = (c.x.floor() as i32, c.y.floor() as i32, c.z.floor() as i32);
        let mut seen = [u32::MAX; 8];
        let mut sum = Rgb::ZERO;
        let mut n = 0u32;
        while n < 8 {
            // (Wrapping: a cell index past i32's range, at a radius near zero, hashes as any other.)
            let (dx, dy, dz) = ((n & 1) as i32, ((n >> 1) & 1) as i32, (n >> 2) as i32);
            let b = grid.bucket_of_cell(x0.wrapping_add(dx), y0.wrapping_add(dy), z0.wrapping_add(dz));
            // Two of the eight cells may share a bucket: each bucket once.
            let mut repeated = false;
            let mut m = 0;
            while m < n {
                repeated = repeated || seen[m as usize] == b;
                m += 1;
            }
            seen[n as usize] = b;
            n += 1;
            if repeated {
                continue;
            }
            let mut j = self.words[b as usize];
            while j != 0 {
                let slot = j - 1;
                j = self.words[(grid.buckets + slot) as usize];
                // Its position and depth first, the rest of its 208 bytes only within the radius: on a
                // surface the eight cells' 16r² hold about five times the vertices of the radius's πr²
                // (and a bucket those of the cells that share its hash).
                let p = Vec3::from(self.cache[slot as usize].p);
                let length = camera.segments + (self.cache[slot as usize].depth & !DISPERSED);
                // The light path's vertices with a non-Dirac lobe up to this one: its slot in the path's
                // slots, plus one; the merged vertex is both paths' last.
                let light_smooth = slot % MAX_LIGHT_VERTICES + 1;
                if (p - sp.p).length_squared() > r_sq
                    || !within(max_depth, length)
                    || !bidirectional(length, camera.smooth + light_smooth - 1)
                {
                    continue;
                }
                let v = self.cache[slot as usize];
                let light_shading = v.shading();
                let towards_light = light_shading.frame().to_world(light_shading.wo);
                let cos_g = sp.ng.dot(towards_light).abs();
                if !(cos_g > 0.0) {
                    continue;
                }
                let wi = frame.to_local(towards_light);
                let ep = bsdf.eval_pdf(shading.wo, wi, TransportMode::Radiance);
                let rev = bsdf.pdf(wi, shading.wo, TransportMode::Importance);
                let weight = bdpt_mis::merge_weight(v.mis(), camera.mis, ep.pdf, rev, merging);
                let factor = camera.wavelength.factor(camera.dispersed || v.dispersed());
                sum += ep.f * v.throughput() * factor * (weight / cos_g);
            }
        }
        sum * merging.inv_eta
    }
}
