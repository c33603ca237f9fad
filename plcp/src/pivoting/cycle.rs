//! The cycle guard: a basis that comes back ends the float trace.
//!
//! In exact arithmetic the lexicographic rule returns to a basis only around
//! a closed loop: a path component that is a loop (a singular monotone `M`
//! can have one, `docs/limits.md`), which the exact tracer reports as
//! `secondary_ray` (no solution beyond on this path). In floats the trace
//! can also circle where the steps of the path fall below the rounding of
//! its values (a basis condition near `1 / eps`, or a cluster of
//! breakpoints closer together than the working precision resolves): the
//! ratio test reads rounding, and the trace went through the same few bases
//! until the pivot limit, turning back in `L` at every lap (a LASSO path in
//! fx128 at `t = 0`: a cycle of four bases, 2968 turning points in 6000
//! pivots, where the exact path has 567 pivots and ends on a secondary ray).
//! A float trace cannot tell the two apart, so a repeat is `ill_conditioned`
//! with both readings in its message; exact arithmetic decides.
//!
//! The guard keeps a 128-bit fingerprint of the set of basic variables (the
//! XOR of one random key per variable, updated in O(1) a pivot) and the
//! fingerprints seen in the current trace. A repeat ends the trace at once,
//! naming the two pivots, instead of spending the pivot limit: the caller
//! escalates or reads the status. A false repeat
//! needs two different bases with the same 128-bit fingerprint (about
//! `pivots^2 / 2^129`). Memory: 16 bytes and a hash-table slot a pivot.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// The fingerprints are random already: the table hashes them as they are.
#[derive(Default)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = self.0.rotate_left(8) ^ u64::from(b);
        }
    }
    fn write_u128(&mut self, v: u128) {
        self.0 = v as u64;
    }
}

/// The fingerprint of the current basis and the pivots at which each
/// fingerprint of this trace was seen.
#[derive(Default)]
pub(crate) struct CycleGuard {
    key: u128,
    seen: HashMap<u128, usize, BuildHasherDefault<KeyHasher>>,
}

/// The key of the variable with engine index `i` (splitmix64, twice).
fn var_key(i: usize) -> u128 {
    fn mix(mut z: u64) -> u64 {
        z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    let i = i as u64;
    (u128::from(mix(2 * i)) << 64) | u128::from(mix(2 * i + 1))
}

impl CycleGuard {
    /// The fingerprint of the basis whose variables have the engine indices
    /// `basic`.
    pub(crate) fn fingerprint(basic: impl Iterator<Item = usize>) -> u128 {
        basic.fold(0, |k, i| k ^ var_key(i))
    }

    /// A new trace from the basis of fingerprint `key`: nothing seen yet.
    pub(crate) fn start(&mut self, key: u128) {
        self.seen.clear();
        self.key = key;
    }

    /// The fingerprint recomputed from the basis (after pivots made
    /// elsewhere), keeping what was seen.
    pub(crate) fn rekey(&mut self, key: u128) {
        self.key = key;
    }

    /// One pivot: `leaving` out, `entering` in (engine indices).
    pub(crate) fn pivot(&mut self, leaving: usize, entering: usize) {
        self.key ^= var_key(leaving) ^ var_key(entering);
    }

    /// Marks the current basis as seen at pivot `pivots`; `Some(k)` if it
    /// was seen before, at pivot `k`.
    pub(crate) fn visit(&mut self, pivots: usize) -> Option<usize> {
        match self.seen.insert(self.key, pivots) {
            Some(k) if k != pivots => Some(k),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_basis_that_comes_back_is_seen_and_others_are_not() {
        let mut g = CycleGuard::default();
        g.start(CycleGuard::fingerprint([0, 1, 2].into_iter()));
        assert_eq!(g.visit(0), None);
        g.pivot(1, 3); // {0, 2, 3}
        assert_eq!(g.visit(1), None);
        g.pivot(2, 4); // {0, 3, 4}
        assert_eq!(g.visit(2), None);
        g.pivot(4, 1); // {0, 1, 3}
        assert_eq!(g.visit(3), None);
        g.pivot(3, 2); // {0, 1, 2} again
        assert_eq!(g.visit(4), Some(0));
        // recomputed from the basis: the same fingerprint
        let k = g.key;
        g.rekey(CycleGuard::fingerprint([2, 0, 1].into_iter()));
        assert_eq!(g.key, k);
        // a new trace forgets
        g.start(CycleGuard::fingerprint([0, 1, 2].into_iter()));
        assert_eq!(g.visit(5), None);
    }

    #[test]
    fn keys_differ_for_the_first_indices() {
        let keys: std::collections::HashSet<u128> = (0..100_000).map(var_key).collect();
        assert_eq!(keys.len(), 100_000);
    }
}
