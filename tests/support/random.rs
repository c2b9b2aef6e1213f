//! The one seeded generator of the tests, benchmarks, examples and the `#[cfg(test)]` parts of
//! `src/raster`: SplitMix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number
//! generators", OOPSLA 2014). One 64-bit state, so every drawing, point set and hostile input is
//! the same on every run and every machine, and a failing test names the seed that reproduces it.
//!
//! Included by `#[path]` wherever it is used (see `tests/README.md`); it depends on nothing.
//! Every method is a fixed function of the stream: changing one changes the generated samples,
//! benchmark drawings and point sets, whose expected numbers depend on them.
// Each includer uses a different part.
#![allow(dead_code)]

/// The SplitMix64 generator: one 64-bit state, a golden-ratio step and a mixing function.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator whose whole sequence is fixed by `seed`.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1), from the top 53 bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [low, high).
    pub fn range(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.unit()
    }

    /// Uniform in [-amount, amount).
    pub fn jitter(&mut self, amount: f64) -> f64 {
        (2.0 * self.unit() - 1.0) * amount
    }

    /// True with probability `probability`.
    pub fn chance(&mut self, probability: f64) -> bool {
        self.unit() < probability
    }

    /// A number in `0..bound` (`bound` > 0), by the remainder of the next 64 bits.
    pub fn below(&mut self, bound: usize) -> usize {
        self.below_u64(bound as u64) as usize
    }

    /// [`below`](Self::below) for 64-bit bounds (file sizes, byte offsets).
    pub fn below_u64(&mut self, bound: u64) -> u64 {
        self.next_u64() % bound
    }

    /// A number in `0..count` (`count` > 0), by scaling a [`unit`](Self::unit) draw. Not the same
    /// numbers as [`below`](Self::below): the sample and benchmark generators use this one.
    pub fn index(&mut self, count: usize) -> usize {
        (self.unit() * count as f64) as usize % count
    }

    /// Standard normal, by the Box–Muller transform.
    pub fn gaussian(&mut self) -> f64 {
        let radius = (-2.0 * (1.0 - self.unit()).ln()).sqrt();
        radius * (std::f64::consts::TAU * self.unit()).cos()
    }

    /// Shuffles `items` in place (Fisher–Yates, indices by [`below`](Self::below)).
    pub fn shuffle<T>(&mut self, items: &mut [T]) {
        for last in (1..items.len()).rev() {
            items.swap(last, self.below(last + 1));
        }
    }

    /// Shuffles `items` in place (Fisher–Yates, indices by [`index`](Self::index)): the order
    /// the sample and benchmark generators draw their strokes in.
    pub fn shuffle_by_index<T>(&mut self, items: &mut [T]) {
        for last in (1..items.len()).rev() {
            items.swap(last, self.index(last + 1));
        }
    }
}
