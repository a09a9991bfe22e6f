//! Checkpoints of long renders: the accumulation buffer with what it holds (samples done, seed, the
//! render's total) and a fingerprint of the scene buffers, so that `render --checkpoint FILE` resumes
//! exactly where an interrupted run stopped, and refuses a file written for another scene or
//! settings. Random numbers are a function of (seed, pixel, sample, dimension): the resumed render
//! is the image an uninterrupted one would have produced. A CRC-32 of the header and the sums closes
//! the file, so that a damaged checkpoint is refused instead of resumed into a wrong image.
use crate::backend::accumulation::Accumulation;
use crate::backend::accumulation::PixelTotal;
use crate::prepare::buffers::SceneBuffers;
use anyhow::{bail, Context, Result};
use std::hash::{Hash, Hasher};
use std::path::Path;

/// Version 4: the sums are the host's f64 totals (`accumulation::PixelTotal`). (Version 3 ended the file with
/// a CRC-32 of everything before it; version 2 added the batch count of splatted, light-traced, sums
/// to the header.)
const MAGIC: &[u8; 8] = b"CAUSTCK4";
const HEADER: usize = 36;
/// The checksum after the sums.
const TRAILER: usize = 4;

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
        let floats: &[f64] = bytemuck::cast_slice(&self.accum.pixels);
        let mut bytes = Vec::with_capacity(HEADER + floats.len() * 8 + TRAILER);
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&self.scene.to_le_bytes());
        let batches = self.accum.batches.unwrap_or(u32::MAX);
        for v in [self.seed, self.spp_total, self.spp_done, floats.len() as u32, batches] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        for v in floats {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let checksum = crc32fast::hash(&bytes);
        bytes.extend_from_slice(&checksum.to_le_bytes());
        crate::system::files::write(path, &bytes).context("cannot save the checkpoint")
    }

    pub fn load(path: &Path) -> Result<Checkpoint> {
        let bytes = crate::system::files::read_own(path, "the checkpoint")?;
        let word =
            |at: usize| -> Option<u32> { Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?)) };
        if bytes.len() >= 8 && bytes[..7] == MAGIC[..7] && bytes[..8] != MAGIC[..] {
            bail!("{} is a checkpoint of another caustic version; remove it to start afresh", path.display());
        }
        if bytes.len() < HEADER + TRAILER || &bytes[..8] != MAGIC {
            bail!("{} is not a caustic checkpoint", path.display());
        }
        let scene = u64::from_le_bytes(bytes[8..16].try_into().unwrap());
        let (seed, spp_total, spp_done, count) =
            (word(16).unwrap(), word(20).unwrap(), word(24).unwrap(), word(28).unwrap() as usize);
        let batches = word(32).unwrap();
        let per_pixel = std::mem::size_of::<PixelTotal>() / 8;
        let expected = count.checked_mul(8).and_then(|b| b.checked_add(HEADER + TRAILER));
        if expected != Some(bytes.len()) || count % per_pixel != 0 {
            bail!(
                "{}: truncated or damaged checkpoint ({} bytes; its header says {count} values)",
                path.display(),
                bytes.len(),
            );
        }
        let (content, trailer) = bytes.split_at(bytes.len() - TRAILER);
        if crc32fast::hash(content) != u32::from_le_bytes(trailer.try_into().unwrap()) {
            bail!("{}: damaged checkpoint (checksum mismatch); remove it to start afresh", path.display());
        }
        let floats: Vec<f64> =
            content[HEADER..].chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect();
        let accum = Accumulation {
            pixels: bytemuck::pod_collect_to_vec(&floats),
            batches: (batches != u32::MAX).then_some(batches),
        };
        // Sums no render can make (a checksum guards against damage, not against a crafted file):
        // every value finite, squares and invalid counts not negative.
        let possible = |p: &PixelTotal| {
            let values = p.sum.iter().chain(&p.sum_sq).chain([&p.count, &p.invalid]);
            values.clone().all(|v| v.is_finite()) && p.sum_sq.iter().all(|&v| v >= 0.0) && p.invalid >= 0.0
        };
        if let Some(i) = accum.pixels.iter().position(|p| !possible(p)) {
            bail!(
                "{}: the checkpoint's sums for pixel {i} are not ones a render makes ({:?}); remove it to start \
                 afresh",
                path.display(),
                accum.pixels[i]
            );
        }
        Ok(Checkpoint { scene, seed, spp_total, spp_done, accum })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Checkpoint {
        let pixels = (0..6)
            .map(|i| PixelTotal {
                sum: [i as f64, 0.5, 2.0],
                count: 4.0,
                sum_sq: [1.0, 0.25, i as f64],
                invalid: 0.0,
            })
            .collect();
        Checkpoint {
            scene: 0x1234_5678_9abc_def0,
            seed: 7,
            spp_total: 16,
            spp_done: 4,
            accum: Accumulation { pixels, batches: Some(3) },
        }
    }

    fn temp(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("caustic-checkpoint-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    #[test]
    fn round_trip() {
        let path = temp("round-trip.ckpt");
        sample().save(&path).unwrap();
        assert_eq!(Checkpoint::load(&path).unwrap(), sample());
    }

    /// One flipped bit anywhere, header or sums, and the file is refused with its name.
    #[test]
    fn impossible_sums_are_refused() {
        let dir = std::env::temp_dir().join(format!("caustic-checkpoint-sums-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("c.ckpt");
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            let mut c = sample();
            c.accum.pixels[2].sum_sq[1] = bad;
            c.save(&path).unwrap();
            let e = format!("{:#}", Checkpoint::load(&path).unwrap_err());
            assert!(e.contains("c.ckpt") && e.contains("pixel 2"), "{bad}: {e}");
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_damaged_checkpoint_is_refused() {
        let path = temp("damaged.ckpt");
        sample().save(&path).unwrap();
        let good = std::fs::read(&path).unwrap();
        for at in [12, 17, 25, 33, HEADER, HEADER + 37, good.len() - 1] {
            let mut bad = good.clone();
            bad[at] ^= 0x10;
            std::fs::write(&path, &bad).unwrap();
            let e = format!("{:#}", Checkpoint::load(&path).unwrap_err());
            assert!(e.contains("damaged.ckpt") && e.contains("damaged"), "byte {at}: {e}");
        }
    }

    #[test]
    fn an_older_version_is_named_as_such() {
        let path = temp("old.ckpt");
        sample().save(&path).unwrap();
        let mut old = std::fs::read(&path).unwrap();
        old[..8].copy_from_slice(b"CAUSTCK2");
        std::fs::write(&path, &old).unwrap();
        let e = format!("{:#}", Checkpoint::load(&path).unwrap_err());
        assert!(e.contains("old.ckpt") && e.contains("another caustic version"), "{e}");
    }
}
