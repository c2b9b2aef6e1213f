//! Seeded randomness for the sample generator: SplitMix64 (Steele, Lea & Flood 2014) and a smooth
//! value noise built on it, so every sample is byte-identical on every run and every machine.

/// The SplitMix64 generator: one 64-bit state, a golden-ratio step and a mixing function.
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

    /// True with probability `probability`.
    pub fn chance(&mut self, probability: f64) -> bool {
        self.unit() < probability
    }

    /// Uniform index in 0..count (count > 0).
    pub fn index(&mut self, count: usize) -> usize {
        (self.unit() * count as f64) as usize % count
    }

    /// Standard normal, by the Box–Muller transform.
    pub fn gaussian(&mut self) -> f64 {
        let radius = (-2.0 * (1.0 - self.unit()).ln()).sqrt();
        radius * (std::f64::consts::TAU * self.unit()).cos()
    }

    /// Shuffles `items` in place (Fisher–Yates).
    pub fn shuffle<T>(&mut self, items: &mut [T]) {
        for last in (1..items.len()).rev() {
            items.swap(last, self.index(last + 1));
        }
    }
}

/// Smooth noise in [-1, 1] at `(x, y)`: random values on the integer lattice, blended with a
/// smoothstep. Used for paper texture and uneven lighting.
pub fn value_noise(seed: u64, x: f64, y: f64) -> f64 {
    let (cell_x, cell_y) = (x.floor(), y.floor());
    let (fraction_x, fraction_y) = (smoothstep(x - cell_x), smoothstep(y - cell_y));
    let (ix, iy) = (cell_x as i64, cell_y as i64);
    let top = lerp(lattice(seed, ix, iy), lattice(seed, ix + 1, iy), fraction_x);
    let bottom = lerp(
        lattice(seed, ix, iy + 1),
        lattice(seed, ix + 1, iy + 1),
        fraction_x,
    );
    lerp(top, bottom, fraction_y)
}

fn lattice(seed: u64, x: i64, y: i64) -> f64 {
    let key = seed
        ^ (x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (y as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    SplitMix64::new(key).unit() * 2.0 - 1.0
}

/// 0 below 0, 1 above 1, and a smooth S in between.
pub fn smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}
