//! Dynamic shares of one image's samples between processes (MPI ranks): rank 0 hands out sample
//! ranges one chunk at a time, each sized to about `TARGET_CHUNK` of the asking rank's measured
//! speed (so a slow rank takes fewer samples and holds nobody up), and decides when every rank
//! stops for a checkpoint. This is the bookkeeping alone, with no MPI in it (`mpi.rs` carries the
//! messages), so that it is tested without a launcher.
//!
//! Chunks are handed out in order from one counter, and a rank asks for work only once its last
//! chunk is finished. So when every rank has asked (a checkpoint, the end), the ranks' sums hold
//! exactly the samples `[0, next)`: a checkpoint written then is the one a single process writes,
//! and either kind of run resumes the other's.
use std::time::{Duration, Instant};

/// How long a chunk should take on the rank that gets it: long enough that a request per chunk
/// costs nothing (64 ranks ask 32 times a second), short enough that the last chunks balance.
const TARGET_CHUNK: Duration = Duration::from_secs(2);

/// What a rank does next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Work {
    /// Render the samples `[first, first + count)`.
    Chunk { first: u32, count: u32 },
    /// Every rank sums its accumulation into rank 0, which writes the checkpoint of `[0, done)`.
    Checkpoint { done: u32 },
    /// No more samples: the final sum, of `[0, done)`.
    Finish { done: u32 },
}

/// A chunk out on a rank.
#[derive(Clone, Copy, Debug)]
pub struct Held {
    pub first: u32,
    pub count: u32,
    pub since: Instant,
}

#[derive(Clone, Debug, PartialEq)]
enum Phase {
    Work,
    /// The ranks told so far to stop for a checkpoint, or to finish.
    Checkpoint(Vec<bool>),
    Finish(Vec<bool>),
}

/// Rank 0's record of who renders what.
pub struct Dispatcher {
    spp: u32,
    /// The first sample not handed out.
    next: u32,
    every: Option<Duration>,
    last_checkpoint: Instant,
    /// Samples per pixel finished since the last checkpoint: a checkpoint with nothing new is
    /// skipped, and one is only started once a chunk has finished since the last (so that, with
    /// checkpoints due all the time, a rank asking while another renders gets a chunk, not a wait).
    new_since: u64,
    phase: Phase,
    held: Vec<Option<Held>>,
    /// Samples per second of each rank's last chunk.
    rate: Vec<Option<f64>>,
    /// Samples per pixel each rank finished.
    samples: Vec<u64>,
    /// When each rank last asked (or the dispatcher started).
    heard: Vec<Instant>,
}

impl Dispatcher {
    /// `[0, start)` is already summed (a resumed checkpoint); `every`: the checkpoint interval.
    pub fn new(start: u32, spp: u32, ranks: usize, every: Option<Duration>, now: Instant) -> Dispatcher {
        Dispatcher {
            spp,
            next: start,
            every,
            last_checkpoint: now,
            new_since: 0,
            phase: Phase::Work,
            held: vec![None; ranks],
            rate: vec![None; ranks],
            samples: vec![0; ranks],
            heard: vec![now; ranks],
        }
    }

    /// `rank` has finished what it held (if anything) and asks what to do next.
    pub fn request(&mut self, rank: usize, now: Instant) -> Work {
        self.heard[rank] = now;
        if let Some(h) = self.held[rank].take() {
            self.samples[rank] += h.count as u64;
            self.new_since += h.count as u64;
            let seconds = now.duration_since(h.since).as_secs_f64().max(1e-6);
            self.rate[rank] = Some(h.count as f64 / seconds);
        }
        let ranks = self.held.len();
        let told = |told: &mut Vec<bool>| {
            told[rank] = true;
            told.iter().all(|&t| t)
        };
        match &mut self.phase {
            Phase::Checkpoint(t) => {
                if told(t) {
                    self.end_checkpoint(now);
                }
                return Work::Checkpoint { done: self.next };
            }
            Phase::Finish(t) => {
                told(t);
                return Work::Finish { done: self.next };
            }
            Phase::Work => {}
        }
        if self.next >= self.spp {
            let mut t = vec![false; ranks];
            told(&mut t);
            self.phase = Phase::Finish(t);
            return Work::Finish { done: self.next };
        }
        let due = self.every.is_some_and(|every| now.duration_since(self.last_checkpoint) >= every);
        if due && self.new_since > 0 {
            let mut t = vec![false; ranks];
            if told(&mut t) {
                self.end_checkpoint(now);
            } else {
                self.phase = Phase::Checkpoint(t);
            }
            return Work::Checkpoint { done: self.next };
        }
        let remaining = self.spp - self.next;
        // Guided self-scheduling: never more than a share of what is left, so that the last
        // chunks are small and the ranks end together.
        let guided = remaining.div_ceil(2 * ranks as u32).max(1);
        let want = self.rate[rank].map_or(1.0, |r| r * TARGET_CHUNK.as_secs_f64());
        let count = (want.min(u32::MAX as f64) as u32).clamp(1, guided).min(remaining);
        let first = self.next;
        self.next += count;
        self.held[rank] = Some(Held { first, count, since: now });
        Work::Chunk { first, count }
    }

    fn end_checkpoint(&mut self, now: Instant) {
        self.phase = Phase::Work;
        self.last_checkpoint = now;
        self.new_since = 0;
    }

    /// Every rank has been told to finish.
    pub fn finished(&self) -> bool {
        matches!(&self.phase, Phase::Finish(t) if t.iter().all(|&t| t))
    }

    /// Samples per pixel each rank finished.
    pub fn samples(&self) -> &[u64] {
        &self.samples
    }

    /// Samples per pixel handed out and finished (for the progress bar).
    pub fn finished_total(&self) -> u64 {
        self.samples.iter().sum()
    }

    /// A rank the render waits for that has been silent too long: one holding a chunk for more
    /// than `limit` and twenty times what its last chunk's speed predicts, or one that has not
    /// asked for `limit` while the others wait for it (a checkpoint or the end). With its chunk,
    /// if it holds one.
    pub fn stalled(&self, now: Instant, limit: Duration) -> Option<(usize, Option<Held>)> {
        let waited_on = |rank: usize| match &self.phase {
            Phase::Work => true,
            Phase::Checkpoint(t) | Phase::Finish(t) => !t[rank],
        };
        (0..self.held.len()).filter(|&r| waited_on(r)).find_map(|rank| {
            let silent = now.duration_since(self.heard[rank]);
            let expected = match (self.held[rank], self.rate[rank]) {
                (Some(h), Some(rate)) => Duration::from_secs_f64(20.0 * h.count as f64 / rate.max(1e-9)),
                _ => Duration::ZERO,
            };
            (silent > limit.max(expected)).then_some((rank, self.held[rank]))
        })
    }

    /// The chunks out on ranks: `(rank, chunk)`.
    pub fn held(&self) -> impl Iterator<Item = (usize, Held)> + '_ {
        self.held.iter().enumerate().filter_map(|(r, h)| h.map(|h| (r, h)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs ranks of the given speeds (seconds per sample per pixel) on a simulated clock: every
    /// sample is handed out once, checkpoints fall where every rank has finished what it held,
    /// and the fast rank takes more.
    fn simulate(speeds: &[f64], spp: u32, every: Option<Duration>) -> (Vec<u64>, Vec<u32>) {
        let t0 = Instant::now();
        let mut d = Dispatcher::new(0, spp, speeds.len(), every, t0);
        // Each rank's next request time.
        let mut at: Vec<f64> = vec![0.0; speeds.len()];
        let mut covered = vec![0u32; spp as usize];
        let mut checkpoints = Vec::new();
        // Ranks waiting in a checkpoint's sum: (its `done`, when they arrived).
        let mut in_checkpoint: Vec<Option<(u32, f64)>> = vec![None; speeds.len()];
        while !d.finished() {
            let rank = (0..speeds.len()).min_by(|&a, &b| at[a].total_cmp(&at[b])).unwrap();
            let now = t0 + Duration::from_secs_f64(at[rank]);
            match d.request(rank, now) {
                Work::Chunk { first, count } => {
                    assert!(in_checkpoint.iter().all(Option::is_none), "a chunk during a checkpoint");
                    for s in first..first + count {
                        covered[s as usize] += 1;
                    }
                    at[rank] += count as f64 * speeds[rank];
                }
                Work::Checkpoint { done } => {
                    // Every sample before `done` was finished by a rank now waiting in the sum.
                    in_checkpoint[rank] = Some((done, at[rank]));
                    at[rank] = f64::INFINITY; // waits in the collective
                    if in_checkpoint.iter().all(Option::is_some) {
                        assert!(in_checkpoint.iter().all(|c| c.unwrap().0 == done));
                        assert!(d.held().next().is_none(), "a chunk out at a checkpoint");
                        checkpoints.push(done);
                        // The sum ends when the last rank arrives.
                        let last = in_checkpoint.iter().map(|c| c.unwrap().1).fold(0.0, f64::max);
                        at.iter_mut().for_each(|a| *a = last);
                        in_checkpoint.iter_mut().for_each(|c| *c = None);
                    }
                }
                Work::Finish { done } => {
                    assert_eq!(done, spp);
                    at[rank] = f64::INFINITY;
                }
            }
            if at.iter().all(|a| a.is_infinite()) && !d.finished() {
                panic!("every rank waits and the render is not finished");
            }
        }
        assert!(covered.iter().all(|&c| c == 1), "a sample handed out twice or never");
        assert_eq!(d.finished_total(), spp as u64);
        (d.samples().to_vec(), checkpoints)
    }

    #[test]
    fn a_slow_rank_takes_fewer_samples_and_each_sample_goes_once() {
        let (samples, _) = simulate(&[0.001, 0.02], 4096, None);
        assert!(samples[0] > 10 * samples[1], "{samples:?}");
        let (samples, _) = simulate(&[0.01, 0.01, 0.01], 999, None);
        let (lo, hi) = (samples.iter().min().unwrap(), samples.iter().max().unwrap());
        assert!(hi - lo <= hi / 4, "equal ranks, unequal shares: {samples:?}");
    }

    #[test]
    fn checkpoints_are_prefixes_at_common_rests() {
        let (_, checkpoints) = simulate(&[0.001, 0.003], 20_000, Some(Duration::from_secs(3)));
        assert!(checkpoints.len() >= 3, "{checkpoints:?}");
        assert!(checkpoints.windows(2).all(|w| w[0] < w[1]), "{checkpoints:?}");
        // Interval 0: a checkpoint whenever something new was rendered, never an empty one.
        let (_, checkpoints) = simulate(&[0.01, 0.02], 64, Some(Duration::ZERO));
        assert!(checkpoints.len() >= 2 && checkpoints.windows(2).all(|w| w[0] < w[1]), "{checkpoints:?}");
    }

    #[test]
    fn one_rank_alone_renders_everything() {
        let (samples, checkpoints) = simulate(&[0.01], 100, Some(Duration::from_millis(200)));
        assert_eq!(samples, vec![100]);
        assert!(!checkpoints.is_empty());
    }

    #[test]
    fn a_silent_rank_is_named_with_its_chunk() {
        let t0 = Instant::now();
        let mut d = Dispatcher::new(0, 1000, 2, None, t0);
        let s = |x: f64| t0 + Duration::from_secs_f64(x);
        assert!(matches!(d.request(0, s(0.0)), Work::Chunk { .. }));
        let Work::Chunk { first, .. } = d.request(1, s(0.0)) else { panic!() };
        for i in 1..100 {
            d.request(0, s(i as f64 * 0.06));
        }
        assert_eq!(d.stalled(s(1.0), Duration::from_secs(5)).map(|x| x.0), None);
        let (rank, held) = d.stalled(s(6.0), Duration::from_secs(5)).expect("rank 1 is silent");
        assert_eq!((rank, held.map(|h| h.first)), (1, Some(first)));
    }
}
