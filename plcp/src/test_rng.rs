//! The generator of the unit tests' numbers (test builds only): xorshift64
//! (shifts 13, 7, 17), its top 53 bits as a number in `[0, 1)`. One copy for
//! the tests of `basis::sparse`, `residual` and `solver`, each seeded as it
//! was, so they draw the numbers (and test the instances) they drew before.

/// The numbers in `[0, 1)` from `seed` (nonzero: zero stays zero).
pub(crate) fn unit(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}
