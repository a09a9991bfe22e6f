//! What a backend accumulates: per pixel, the device's f32 sums folded into the host's f64 totals
//! (`PixelTotal`, `Accumulation`) on one schedule for both backends (`Folding`). `output::film`
//! develops them into an image.
use caustic_kernel::layout::PixelAccum;

/// One pixel's totals on the host: the device's f32 sums (`PixelAccum`) folded in every
/// `FOLD_SAMPLES` samples per pixel and at every read-back. A million samples of 0.1 summed in f32
/// came out 3.8e-5 high (each pass added 25.6 to a sum near 1e5, whose ulp is 0.0078, rounding the
/// same way every pass); f64 totals keep the device's sums small.
#[repr(C)]
#[derive(Clone, Copy, Default, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PixelTotal {
    pub sum: [f64; 3],
    pub count: f64,
    /// Sum of the squared estimates (unscaled: `fold` divides the kernel's square scale out).
    pub sum_sq: [f64; 3],
    pub invalid: f64,
}

/// Samples per pixel after which a backend folds its device's f32 sums into the host's f64 totals
/// and clears them. The sums then stay below 4096 × the pixel's mean, where the ulp of a pass's add
/// is 2⁻¹² of the sum's ulp at a million samples; the GPU reads its sums back once per 4096 spp
/// (once per 16 passes at the largest pass).
pub const FOLD_SAMPLES: u32 = 4096;

/// A backend's accumulated sums: one `PixelTotal` per pixel, and how their squares were summed.
#[derive(Clone, Debug, PartialEq)]
pub struct Accumulation {
    pub pixels: Vec<PixelTotal>,
    /// `None`: `sum_sq` sums each sample's square (camera paths). `Some(b)`: the sums came in `b`
    /// batches (passes) whose pixel sums `S` were resolved from splats, `sum_sq` summing `S²/k` for a
    /// pass of `k` samples, and the film estimates the variance from batch means: a light path adds
    /// to arbitrary pixels, so no per-sample square exists for a pixel.
    pub batches: Option<u32>,
}

/// Whether a render with these parameters estimates each pixel's variance from batch means (its
/// `Accumulation::batches`): light tracing's splats and the splatting film's gathered sums give a
/// pixel no per-sample square.
pub fn batch_means(params: &caustic_kernel::layout::FrameParams) -> bool {
    caustic_kernel::film_splat::words_per_pixel(params) > 0
}

impl Accumulation {
    pub fn new(pixels: usize, splatted: bool) -> Self {
        Accumulation { pixels: vec![PixelTotal::default(); pixels], batches: splatted.then_some(0) }
    }

    /// Adds a device's f32 sums (one `PixelAccum` per pixel) whose squares were scaled by
    /// `2^square_scale_log2` before squaring (`FrameParams::square_scale_log2`).
    pub fn fold(&mut self, device: &[PixelAccum], square_scale_log2: i32) {
        assert_eq!(self.pixels.len(), device.len(), "accumulations of different sizes");
        let unscale = 2f64.powi(-2 * square_scale_log2);
        for (a, b) in self.pixels.iter_mut().zip(device) {
            for c in 0..3 {
                a.sum[c] += b.sum[c] as f64;
                a.sum_sq[c] += b.sum_sq[c] as f64 * unscale;
            }
            a.count += b.count as f64;
            a.invalid += b.invalid as f64;
        }
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

/// A device's f32 sums and the host's f64 totals they fold into: what both backends keep, so that
/// both fold on the same schedule (every `FOLD_SAMPLES` samples per pixel, and at every read).
#[derive(Clone, Debug)]
pub struct Folding {
    /// Everything folded so far (and the batch count of splatted sums).
    pub total: Accumulation,
    /// Samples per pixel in the device's sums since they were last folded.
    pub unfolded: u32,
    pub square_scale_log2: i32,
}

impl Folding {
    pub fn new(pixels: usize, splatted: bool, square_scale_log2: i32) -> Self {
        Folding { total: Accumulation::new(pixels, splatted), unfolded: 0, square_scale_log2 }
    }

    /// Counts a pass of `samples` per pixel (and a batch, for splatted sums); whether the device's
    /// sums are due to be folded (`fold` them, then clear them).
    pub fn passed(&mut self, samples: u32) -> bool {
        self.unfolded += samples;
        if let Some(b) = &mut self.total.batches {
            *b += 1;
        }
        self.unfolded >= FOLD_SAMPLES
    }

    /// Folds the device's sums in (the caller clears them).
    pub fn fold(&mut self, device: &[PixelAccum]) {
        self.total.fold(device, self.square_scale_log2);
        self.unfolded = 0;
    }

    /// Replaces the totals (resuming from a checkpoint; the caller clears the device's sums).
    pub fn replace(&mut self, accum: &Accumulation) -> anyhow::Result<()> {
        anyhow::ensure!(
            accum.pixels.len() == self.total.pixels.len()
                && accum.batches.is_some() == self.total.batches.is_some(),
            "accumulation buffer of {} pixels ({}), expected {}",
            accum.pixels.len(),
            if accum.batches.is_some() { "splatted" } else { "per sample" },
            self.total.pixels.len()
        );
        self.total = accum.clone();
        self.unfolded = 0;
        Ok(())
    }
}
