//! Handing out samples to devices: which sample ranges are finished, which are running, which a lost
//! device gave back, and how many samples per pixel the accumulation holds as one unbroken prefix
//! `[0, done)` (what a checkpoint may claim). Random numbers are a function of (seed, pixel, sample,
//! dimension), so any partition of `[0, spp)` into passes on any devices sums to the one estimator.
use super::accumulation::Accumulation;
use std::collections::BTreeMap;

/// What lanes are and report lives in `device`, beside the `Backend` they make one of; named here
/// too, as the pass loop's users (the tests) know them.
pub use super::device::{Event, Lanes, Lost, SampleRange};

/// Which samples are handed out and finished.
pub struct Samples {
    /// The first sample never handed out.
    next: u32,
    /// Ranges a lost device gave back, handed out again before new ones.
    returned: Vec<SampleRange>,
    /// Finished ranges by first sample (disjoint).
    finished: BTreeMap<u32, u32>,
    /// `[0, prefix)` is finished.
    prefix: u32,
    /// Samples per pixel finished in all (in any order).
    finished_total: u32,
}

impl Samples {
    /// `[0, start)` already in the accumulation (a resumed render).
    pub fn new(start: u32) -> Self {
        let mut finished = BTreeMap::new();
        if start > 0 {
            finished.insert(0, start);
        }
        Samples { next: start, returned: Vec::new(), finished, prefix: start, finished_total: start }
    }

    /// Samples per pixel finished as one unbroken prefix.
    pub fn prefix(&self) -> u32 {
        self.prefix
    }

    /// Samples per pixel finished in all.
    pub fn finished_total(&self) -> u32 {
        self.finished_total
    }

    /// The next range to render, at most `want` samples, never at or past `stop` unless given back.
    pub fn claim(&mut self, want: u32, stop: u32) -> Option<SampleRange> {
        if let Some((first, count)) = self.returned.pop() {
            let take = count.min(want.max(1));
            if take < count {
                self.returned.push((first + take, count - take));
            }
            return Some((first, take));
        }
        (self.next < stop).then(|| {
            let count = want.max(1).min(stop - self.next);
            let range = (self.next, count);
            self.next += count;
            range
        })
    }

    pub fn finish(&mut self, (first, count): SampleRange) {
        self.finished.insert(first, count);
        self.finished_total += count;
        while let Some(&count) = self.finished.get(&self.prefix) {
            self.prefix += count;
        }
    }

    /// Ranges lost with a device: no longer finished (if they were), to be rendered again.
    pub fn give_back(&mut self, ranges: &[SampleRange]) {
        for &(first, count) in ranges {
            if self.finished.remove(&first).is_some() {
                self.finished_total -= count;
                self.prefix = self.prefix.min(first);
            }
            self.returned.push((first, count));
        }
    }
}

/// An accumulation that sums those of several devices: what `add` gives (kept apart so it reads
/// as a reduction where it is used).
pub fn reduce<'a>(mut parts: impl Iterator<Item = &'a Accumulation>) -> Option<Accumulation> {
    let mut total = parts.next()?.clone();
    for p in parts {
        total.add(p);
    }
    Some(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prefix_follows_out_of_order_finishes_and_losses() {
        let mut s = Samples::new(2);
        let a = s.claim(3, 100).unwrap();
        let b = s.claim(4, 100).unwrap();
        assert_eq!((a, b), ((2, 3), (5, 4)));
        s.finish(b);
        assert_eq!((s.prefix(), s.finished_total()), (2, 6));
        s.finish(a);
        assert_eq!(s.prefix(), 9);
        // The device that did `a` is lost: its samples go back, the prefix with them.
        s.give_back(&[a]);
        assert_eq!((s.prefix(), s.finished_total()), (2, 6));
        assert_eq!(s.claim(2, 100), Some((2, 2)));
        assert_eq!(s.claim(8, 100), Some((4, 1)));
        assert_eq!(s.claim(8, 12), Some((9, 3)));
        assert_eq!(s.claim(8, 12), None);
        for r in [(2, 2), (4, 1), (9, 3)] {
            s.finish(r);
        }
        assert_eq!((s.prefix(), s.finished_total()), (12, 12));
    }
}
