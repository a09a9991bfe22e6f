//! Checkpoints of long renders: the accumulation buffer with what it holds (samples done, seed, the
//! render's total) and a fingerprint of the scene buffers, so that `render --checkpoint FILE` resumes
//! exactly where an interrupted run stopped, and refuses a file written for another scene or
//! settings. Random numbers are a function of (seed, pixel, sample, dimension): the resumed render
//! is the image an uninterrupted one would have produced.
use crate::buffers::SceneBuffers;
use crate::film::Accumulation;
use anyhow::{bail, Context, Result};
use caustic_kernel::layout::PixelAccum;
use std::hash::{Hash, Hasher};
use std::path::Path;

/// Version 2: the header carries the batch count of splatted (light-traced) sums.
const MAGIC: &[u8; 8] = b"CAUSTCK2";
const HEADER: usize = 36;

#[derive(Clone, Debug, PartialEq)]
pub struct Checkpoint {
    /// Fingerprint of the scene buffers and sampling settings (`fingerprint`).
    pub scene: u64,
    pub seed: u32,
    /// Samples per pixel of the whole render, and how many are in `accum`.
    pub spp_total: u32,
    pub spp_done: u32,
    pub accum: Accumulation,
}

/// Identifies what the accumulation buffer belongs to: every buffer the kernel reads (so a changed
/// scene file, `-D` value or crop gives another fingerprint), the seed and the total sample count.
pub fn fingerprint(buffers: &SceneBuffers, seed: u32, spp_total: u32) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for bytes in [
        bytemuck::bytes_of(&buffers.params),
        bytemuck::cast_slice(&buffers.nodes),
        bytemuck::cast_slice(&buffers.prims),
        bytemuck::cast_slice(&buffers.attributes),
        bytemuck::cast_slice(&buffers.materials),
        bytemuck::cast_slice(&buffers.lights),
        bytemuck::cast_slice(&buffers.textures),
        bytemuck::cast_slice(&buffers.tables),
    ] {
        bytes.hash(&mut h);
    }
    (seed, spp_total).hash(&mut h);
    h.finish()
}

impl Checkpoint {
    /// Writes the checkpoint next to `path` and renames it into place, so that an interruption
    /// while writing leaves the previous checkpoint intact.
    pub fn save(&self, path: &Path) -> Result<()> {
        let floats: &[f32] = bytemuck::cast_slice(&self.accum.pixels);
        let mut bytes = Vec::with_capacity(HEADER + floats.len() * 4);
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&self.scene.to_le_bytes());
        let batches = self.accum.batches.unwrap_or(u32::MAX);
        for v in [self.seed, self.spp_total, self.spp_done, floats.len() as u32, batches] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        for v in floats {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let partial = path.with_extension("partial");
        std::fs::write(&partial, &bytes)
            .with_context(|| format!("cannot write the checkpoint {}", partial.display()))?;
        std::fs::rename(&partial, path)
            .with_context(|| format!("cannot move the checkpoint into place at {}", path.display()))
    }

    pub fn load(path: &Path) -> Result<Checkpoint> {
        let bytes =
            std::fs::read(path).with_context(|| format!("cannot read the checkpoint {}", path.display()))?;
        let word =
            |at: usize| -> Option<u32> { Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?)) };
        if bytes.len() < HEADER || &bytes[..8] != MAGIC {
            bail!("{} is not a caustic checkpoint", path.display());
        }
        let scene = u64::from_le_bytes(bytes[8..16].try_into().unwrap());
        let (seed, spp_total, spp_done, count) =
            (word(16).unwrap(), word(20).unwrap(), word(24).unwrap(), word(28).unwrap() as usize);
        let batches = word(32).unwrap();
        let per_pixel = std::mem::size_of::<PixelAccum>() / 4;
        if bytes.len() != HEADER + count * 4 || count % per_pixel != 0 {
            bail!(
                "{}: truncated checkpoint ({} bytes, expected {})",
                path.display(),
                bytes.len(),
                HEADER + count * 4
            );
        }
        let floats: Vec<f32> =
            bytes[HEADER..].chunks_exact(4).map(|c| f32::from_le_bytes(c.try_into().unwrap())).collect();
        let accum = Accumulation {
            pixels: bytemuck::pod_collect_to_vec(&floats),
            batches: (batches != u32::MAX).then_some(batches),
        };
        Ok(Checkpoint { scene, seed, spp_total, spp_done, accum })
    }
}
