//! Seeded randomness for the sample generator: the tests' SplitMix64 (`tests/support/random.rs`)
//! and a smooth value noise built on it, so every sample is byte-identical on every run and every machine.

#[path = "../../tests/support/random.rs"]
mod seeded;
pub use seeded::SplitMix64;

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
