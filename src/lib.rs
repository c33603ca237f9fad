//! Integration crate: see `examples/`, `tests/` and `benches/`.
//!
//! It also holds the seeded random instance generators shared by the benches
//! and the report programs, so that a number in a report can be reproduced
//! from `(n, seed)` alone, and the formulations of the everyday parametric
//! paths (LASSO, efficient frontier, parametric QP) in [`everyday`].

pub mod everyday;

pub mod random {
    //! Seeded random PLCPs.
    //!
    //! ```
    //! let inst = plcp_workspace::random::dense_monotone(20, 7);
    //! assert_eq!(inst.problem.n(), 20);
    //! // the same seed gives the same problem
    //! let again = plcp_workspace::random::dense_monotone(20, 7);
    //! assert_eq!(inst.problem.q()[3], again.problem.q()[3]);
    //! ```

    use faer::{Col, Mat};
    use plcp::{Path, Plcp, Settings};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A generated problem and how it was made.
    #[derive(Clone, Debug)]
    pub struct RandomPlcp {
        /// The problem (standard form, `lambda0 = 0`).
        pub problem: Plcp<f64>,
        /// Order.
        pub n: usize,
        /// Seed of the ChaCha8 generator.
        pub seed: u64,
    }

    /// A standard normal sample (Box-Muller; `rand` 0.8 has no normal distribution
    /// without `rand_distr`).
    pub(crate) fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
        let u1: f64 = 1.0 - rng.gen::<f64>(); // in (0, 1]
        let u2: f64 = rng.gen::<f64>();
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }

    /// A dense monotone PLCP `w = q + L d + M z` of order `n`:
    ///
    /// * `M = B B' / n + 0.1 I` with `B` standard Gaussian (symmetric positive
    ///   definite, smallest eigenvalue at least 0.1: a unique solution for every `L`);
    /// * `q` uniform in `[0.1, 1]` (so the path starts from `z = 0` with no start phase);
    /// * `d` Gaussian minus 0.5 (most entries negative: the `w` reach zero one after
    ///   another as `L` rises);
    /// * `lambda_max` infinite (see [`bench_instance`] for the benches' choice).
    ///
    /// The draws are in this order from `ChaCha8Rng::seed_from_u64(seed)`: `B`
    /// row by row, then `q`, then `d`.
    pub fn dense_monotone(n: usize, seed: u64) -> RandomPlcp {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut b = Mat::<f64>::zeros(n, n);
        for i in 0..n {
            for j in 0..n {
                b[(i, j)] = gaussian(&mut rng);
            }
        }
        let mut q = Col::<f64>::zeros(n);
        for i in 0..n {
            q[i] = 0.1 + 0.9 * rng.gen::<f64>();
        }
        let mut d = Col::<f64>::zeros(n);
        for i in 0..n {
            d[i] = gaussian(&mut rng) - 0.5;
        }
        let bbt = &b * b.transpose();
        let scale = 1.0 / n.max(1) as f64;
        let m = Mat::<f64>::from_fn(n, n, |i, j| {
            bbt[(i, j)] * scale + if i == j { 0.1 } else { 0.0 }
        });
        let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
            .expect("generated data are finite and consistent");
        RandomPlcp { problem, n, seed }
    }

    /// The parameter midway between the `k`-th and `(k+1)`-th breakpoints
    /// (1-based) of `path`; `None` if it has fewer than `k + 1`.
    pub fn midway_after_breakpoint(path: &Path<f64>, k: usize) -> Option<f64> {
        if k == 0 || path.breakpoints.len() < k + 1 {
            return None;
        }
        Some(0.5 * (path.breakpoints[k - 1].lambda + path.breakpoints[k].lambda))
    }

    /// The benches' instance: [`dense_monotone`]`(n, seed)` with `lambda_max`
    /// midway between the `n/2`-th and `(n/2 + 1)`-th breakpoints of its full path
    /// (traced once here by Lemke's method with infinite `lambda_max`), so that a
    /// timed solve does about `n/2` pivots and ends with `Reached`. If the full
    /// path has fewer breakpoints, `lambda_max` stays infinite (the whole path).
    pub fn bench_instance(n: usize, seed: u64) -> RandomPlcp {
        let mut inst = dense_monotone(n, seed);
        let full =
            plcp::solve(&inst.problem, &Settings::default()).expect("default settings are valid");
        if let Some(lm) = midway_after_breakpoint(&full, n / 2) {
            inst.problem = inst
                .problem
                .clone()
                .with_range(0.0, Some(lm))
                .expect("lambda_max > 0");
        }
        inst
    }

    /// The same instance as [`bench_instance`] (same problem, same `lambda_max`),
    /// found more cheaply: the first solve stops after `n/2 + 2` pivots
    /// (`max_pivots`) instead of tracing the whole path, which halves the set-up
    /// cost of the large benches. The pivot sequence does not depend on
    /// `max_pivots`, so the breakpoints, and `lambda_max`, are the same.
    ///
    /// ```
    /// use plcp_workspace::random::{bench_instance, path_instance};
    /// let (a, b) = (bench_instance(40, 3), path_instance(40, 3));
    /// assert_eq!(a.problem.lambda_max(), b.problem.lambda_max());
    /// ```
    pub fn path_instance(n: usize, seed: u64) -> RandomPlcp {
        let mut inst = dense_monotone(n, seed);
        let settings = Settings {
            max_pivots: Some(n / 2 + 2),
            ..Settings::default()
        };
        let head = plcp::solve(&inst.problem, &settings).expect("default settings are valid");
        if let Some(lm) = midway_after_breakpoint(&head, n / 2) {
            inst.problem = inst
                .problem
                .clone()
                .with_range(0.0, Some(lm))
                .expect("lambda_max > 0");
        }
        inst
    }
}

/// The README's Rust examples, run as doc tests so that the user's guide
/// stays true (`cargo test --workspace --release` runs them).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeExamples;
