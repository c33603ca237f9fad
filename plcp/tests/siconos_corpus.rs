//! The 20 LCP instances of the Siconos test suite, read at run time from
//! `../shared/lcp-corpus/siconos` (relative to the workspace root), or from
//! `$PLCP_SICONOS_DIR`. Skipped with a message when the folder is absent.
//!
//! Each instance is solved by Lemke's method with covering vector e in f64,
//! fx128 and f32. The Siconos error `||z - max(0, z - w)|| / ||q||` is computed
//! here from the returned `z` and `w = q + M z` recomputed in the working
//! precision (not from the solver's own `w`).
//!
//! Run with `--nocapture` to see the table of figures (status, pivots, error,
//! time) for every instance, including what happens on tobenna.

use faer::Col;
use plcp::io::siconos::{read_lcp, siconos_error};
use plcp::{solve_lcp, Lcp, Scalar, Settings, Status};
use std::path::PathBuf;
use std::time::Instant;

fn corpus_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("PLCP_SICONOS_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../shared/lcp-corpus/siconos"
            ))
        });
    if dir.is_dir() {
        Some(dir)
    } else {
        println!(
            "Siconos corpus not found at {}: skipped (set PLCP_SICONOS_DIR)",
            dir.display()
        );
        None
    }
}

/// The instances, as `lcp_<name>.dat`.
const NAMES: [&str; 20] = [
    "CPS_1",
    "CPS_2",
    "CPS_3",
    "CPS_4",
    "CPS_4bis",
    "CPS_5",
    "Pang_isolated_sol",
    "Pang_isolated_sol_perturbed",
    "deudeu",
    "deudeu_block",
    "enum_fails",
    "exp_murty",
    "exp_murty2",
    "inf_sol_perturbed",
    "mmc",
    "ortiz",
    "ortiz_block",
    "tobenna",
    "trivial",
    "trivial_block",
];

/// What the README's table says about the solutions.
enum Known {
    /// Nothing (checked only through the Siconos error).
    Nothing,
    /// The unique solution.
    Unique(Vec<f64>),
    /// A set of solutions: the largest violation of its defining conditions.
    Set(&'static str, fn(&[f64]) -> f64),
}

fn known(name: &str) -> Known {
    match name {
        "deudeu" | "deudeu_block" => Known::Unique(vec![4.0 / 3.0, 7.0 / 3.0]),
        "ortiz" | "ortiz_block" => Known::Unique(vec![2.0 / 3.0, 0.0, 1.0 / 3.0, 0.0]),
        // M = diag(1, ..., 9), q = -e: z_i = 1/i with 1-based i, so 1/(i+1) here.
        "trivial" | "trivial_block" => {
            Known::Unique((0..9).map(|i| 1.0 / (i + 1) as f64).collect())
        }
        "CPS_2" => Known::Unique(vec![0.0, 1.0, 3.0]),
        "CPS_4" => Known::Unique(vec![2.0, 2.0, 2.0, 92.0]),
        "CPS_4bis" => Known::Unique(vec![3.0, 3.0, 0.0, 83.0]),
        "Pang_isolated_sol" => Known::Unique(vec![1.0, 0.0, 0.0]),
        // The README lists (0, 1) and (1, 0, 1e-4) for these two, but with the
        // files' data (M column-major) each has a ray of solutions, of which the
        // listed point is the end: CPS_5 has M = [[1, -1], [-1, 1]], q = (1, -1),
        // so w = 0 and z = (t, 1 + t), t >= 0; inf_sol_perturbed has
        // w2 = z1 - 1 = -w3, so z1 = 1, and w1 = z3 - z2 - 1e-4 = 0: z = (1, t, t + 1e-4).
        // Lemke may end anywhere on the ray, so the test checks the set.
        "CPS_5" => Known::Set("z = (t, 1 + t), t >= 0", |z| {
            (z[1] - z[0] - 1.0).abs().max(-z[0])
        }),
        "inf_sol_perturbed" => Known::Set("z = (1, t, t + 1e-4), t >= 0", |z| {
            (z[0] - 1.0)
                .abs()
                .max((z[2] - z[1] - 1e-4).abs())
                .max(-z[1])
        }),
        // M = [[1, 1], [1, 1]], q = (-1, -1): z1 + z2 = 1, z >= 0.
        "CPS_1" => Known::Set("z1 + z2 = 1, z >= 0", |z| {
            (z[0] + z[1] - 1.0).abs().max(-z[0]).max(-z[1])
        }),
        _ => Known::Nothing,
    }
}

/// What a precision must achieve.
struct Spec {
    /// Largest Siconos error of a solved instance.
    error_tol: f64,
    /// Largest `max_i |z_i - z*_i| / max(1, |z*_i|)` against a known solution,
    /// or violation of a known solution set.
    solution_tol: f64,
    /// Instances allowed to deviate from the f64 expectation in this precision,
    /// each with the reason: a status other than solved where a solution is
    /// expected (a solution they do claim is checked like any other), or, for
    /// the two secondary-ray instances, a solution claim that meets
    /// `error_tol` (the perturbation that makes them unsolvable is below the
    /// precision's resolution).
    exceptions: &'static [(&'static str, &'static str)],
    /// tobenna must be solved, on the exact lexicographic path (see
    /// [`TOBENNA_PIVOTS`]).
    tobenna_solved: bool,
}

/// tobenna is a polymatrix game (8 players of 4 strategies, positive costs)
/// in the form `M = [[A, -E'], [E, 0]]`, `q = (0, -e)`, `A > 0` entrywise:
/// `z'Mz = x'Ax > 0` for `x >= 0, x != 0`, and `z'Mz = 0` forces `x = 0`,
/// where `(M + M')z = 0`; so `M` is copositive-plus, the LCP is feasible
/// (uniform strategies, `v = 0`), and Lemke's method with the lexicographic
/// rule ends on a solution, not a secondary ray (Miller and Zucker 1991). An
/// independent exact computation (lexicographic Lemke over rationals, Python
/// `fractions`, covering vector e, ties by the rows of `B^{-1}` in index
/// order) ends after 127 pivots with `z_0 = 45/83`, `z_1 = 38/83`, and
/// `z_32..39 = 6272/11, 4874/11, 9629/22, 2528/11, 40994/83, 40205/83,
/// 14263/83, 24686/83`; our path must be that one.
const TOBENNA_PIVOTS: usize = 127;

struct Outcome {
    status: Status,
    pivots: usize,
    error: f64,
    seconds: f64,
}

fn solve<T: Scalar>(lcp: &Lcp<T>) -> (Outcome, Vec<f64>) {
    let start = Instant::now();
    let sol = solve_lcp(lcp, &Settings::<T>::default()).expect("valid settings");
    let seconds = start.elapsed().as_secs_f64();
    let (m, q) = (lcp.m(), lcp.q());
    let n = lcp.n();
    let w = Col::<T>::from_fn(n, |i| (0..n).fold(q[i], |a, j| a + m[(i, j)] * sol.z[j]));
    let error = siconos_error(q, sol.z.as_ref(), w.as_ref());
    let z = (0..n).map(|i| sol.z[i].to_f64()).collect();
    (
        Outcome {
            status: sol.status,
            pivots: sol.info.pivots,
            error,
            seconds,
        },
        z,
    )
}

/// Solves every instance in `T`; returns the failures (after printing the table).
fn run_corpus<T: Scalar>(spec: &Spec) -> Vec<String> {
    let Some(dir) = corpus_dir() else {
        return vec![];
    };
    let mut failures = Vec::new();
    println!(
        "\n{:<28} {:>4} {:<15} {:>7} {:>10} {:>10}  ({})",
        "instance",
        "n",
        "status",
        "pivots",
        "error",
        "seconds",
        T::NAME
    );
    for name in NAMES {
        let file = dir.join(format!("lcp_{name}.dat"));
        let lcp = match read_lcp::<T>(&file) {
            Ok(l) => l,
            Err(e) => {
                failures.push(format!("{name}: does not parse: {e}"));
                continue;
            }
        };
        let n = lcp.n();
        let max_pivots = 50 * n + 1000; // the documented default limit
        let (o, z) = solve(&lcp);
        println!(
            "{:<28} {:>4} {:<15} {:>7} {:>10.2e} {:>10.2e}",
            name,
            n,
            o.status.as_str(),
            o.pivots,
            o.error,
            o.seconds
        );
        let mut fail = |why: String| failures.push(format!("{name} ({}): {why}", T::NAME));
        if o.pivots > max_pivots + 1 {
            fail(format!(
                "{} pivots, beyond the limit {max_pivots}",
                o.pivots
            ));
        }
        let exception = spec.exceptions.iter().find(|(m, _)| *m == name);
        match name {
            // Lemke with covering vector e ends on a secondary ray on these two:
            // CPS_3 is a bimatrix game (solutions exist, Lemke's method with e
            // does not reach one), Pang_isolated_sol_perturbed has no solution.
            "CPS_3" | "Pang_isolated_sol_perturbed" => {
                let tolerated =
                    exception.is_some() && o.status.is_success() && o.error <= spec.error_tol;
                if o.status != Status::SecondaryRay && !tolerated {
                    fail(format!(
                        "status {} (Siconos error {:.2e}), expected secondary_ray",
                        o.status.as_str(),
                        o.error
                    ));
                }
                if tolerated {
                    println!("  {name}: tolerated: {}", exception.unwrap().1);
                }
                continue;
            }
            // The hardest instance (highly degenerate, 8 zero diagonal entries,
            // 32 zeros in q): record what happens; assert only that a status
            // comes back within the pivot limit and that a claimed solution is one.
            "tobenna" => {
                println!(
                    "  tobenna ({}): status {}, {} pivots, Siconos error {:.3e}, {:.3} s",
                    T::NAME,
                    o.status.as_str(),
                    o.pivots,
                    o.error,
                    o.seconds
                );
                if o.status.is_success() && !within(o.error, spec.error_tol) {
                    fail(format!(
                        "claims solved, but the Siconos error is {:.3e}",
                        o.error
                    ));
                }
                if spec.tobenna_solved {
                    if !o.status.is_success() || o.pivots != TOBENNA_PIVOTS {
                        fail(format!(
                            "status {} after {} pivots, expected solved after {TOBENNA_PIVOTS} (the exact lexicographic path)",
                            o.status.as_str(),
                            o.pivots
                        ));
                    }
                    let v = [
                        6272.0 / 11.0,
                        4874.0 / 11.0,
                        9629.0 / 22.0,
                        2528.0 / 11.0,
                        40994.0 / 83.0,
                        40205.0 / 83.0,
                        14263.0 / 83.0,
                        24686.0 / 83.0,
                    ];
                    let exact = [45.0 / 83.0, 38.0 / 83.0].iter().chain(&v[..]);
                    let got = z[..2].iter().chain(&z[32..]);
                    let dev = exact
                        .zip(got)
                        .map(|(a, b)| (a - b).abs() / a.abs().max(1.0))
                        .fold(0.0, f64::max);
                    if !within(dev, spec.solution_tol) {
                        fail(format!("z deviates from the exact solution by {dev:.2e}"));
                    }
                }
                continue;
            }
            _ => {}
        }
        if !o.status.is_success() {
            match exception {
                Some((_, why)) => println!("  {name}: tolerated: {why}"),
                None => fail(format!("status {}, expected solved", o.status.as_str())),
            }
            continue;
        }
        if !within(o.error, spec.error_tol) {
            fail(format!(
                "Siconos error {:.3e} > {:.1e}",
                o.error, spec.error_tol
            ));
        }
        match known(name) {
            Known::Nothing => {}
            Known::Unique(zs) => {
                let dev = zs
                    .iter()
                    .zip(&z)
                    .map(|(a, b)| (a - b).abs() / a.abs().max(1.0))
                    .fold(0.0, f64::max);
                if !within(dev, spec.solution_tol) {
                    fail(format!("z = {z:?}, expected {zs:?} (deviation {dev:.2e})"));
                }
            }
            Known::Set(what, violation) => {
                let v = violation(&z);
                if !within(v, spec.solution_tol) {
                    fail(format!(
                        "z = {z:?} is not in the solution set {what} ({v:.2e})"
                    ));
                }
            }
        }
        // Murty's example: Lemke's method takes 2^6 pivots.
        if name == "exp_murty2" {
            println!("  exp_murty2 ({}): {} pivots", T::NAME, o.pivots);
            if o.pivots != 64 {
                fail(format!("{} pivots, expected 2^6 = 64", o.pivots));
            }
        }
    }
    failures
}

/// `x <= tol`, false for NaN.
fn within(x: f64, tol: f64) -> bool {
    x <= tol
}

fn check(failures: Vec<String>) {
    assert!(
        failures.is_empty(),
        "{} failure(s):\n  {}",
        failures.len(),
        failures.join("\n  ")
    );
}

#[test]
fn corpus_f64() {
    check(run_corpus::<f64>(&Spec {
        error_tol: 1e-12,
        solution_tol: 1e-9,
        exceptions: &[],
        tobenna_solved: true,
    }));
}

/// fx128 (eps = 4.9e-32): tighter than f64. The error is computed in fx128
/// (the corpus gives 1e-31 or less); the known solutions are compared after
/// rounding `z` to f64, hence 1e-12 there.
#[test]
fn corpus_fx128() {
    check(run_corpus::<faer::fx128>(&Spec {
        error_tol: 1e-24,
        solution_tol: 1e-12,
        exceptions: &[],
        tobenna_solved: true,
    }));
}

/// f32: eps = 1.2e-7; the tolerances are 1e-4 (Siconos error) and 1e-3
/// (deviation from a known solution).
#[test]
fn corpus_f32() {
    check(run_corpus::<f32>(&Spec {
        error_tol: 1e-4,
        solution_tol: 1e-3,
        exceptions: &[
            (
                "Pang_isolated_sol_perturbed",
                "q1 = -1e-4 is what makes it unsolvable; relative to the data that is \
                 below f32's pivot tolerance (1e4 eps = 1.2e-3), so f32 sees Pang_isolated_sol \
                 and a claimed solution has Siconos error 1e-4/sqrt(2) = 7e-5, within the f32 \
                 tolerance: the two instances cannot be told apart in f32",
            ),
            (
                "mmc",
                "entries up to 2.3e5 beside unit slack columns: the engine's 1-norm condition \
                 estimate of a basis is ~1e7, so cond * eps(f32) ~ 1 and it stops with \
                 ill_conditioned (its documented threshold), asking for a higher precision",
            ),
            (
                "enum_fails",
                "q has entries of 1e-4 down to 1e-9 against M of order 1: f32 may report it \
                 ill-conditioned (a claimed solution must still meet the tolerance)",
            ),
            (
                "Pang_isolated_sol",
                "M is singular (cond ~1e16): f32 may report it ill-conditioned \
                 (a claimed solution must still meet the tolerance)",
            ),
        ],
        // f32 (cond ~2.4e4 on this path, pivot noise 128 eps cond ~ 0.36 of a
        // column) loses the degenerate path: not asserted
        tobenna_solved: false,
    }));
}

/// Every file parses in every precision, and each `*_block` file (sparse-block
/// storage) gives exactly the matrix and vector of its dense twin.
#[test]
fn corpus_parses_and_block_twins_agree() {
    let Some(dir) = corpus_dir() else {
        return;
    };
    for name in NAMES {
        let file = dir.join(format!("lcp_{name}.dat"));
        let a = read_lcp::<f64>(&file).unwrap_or_else(|e| panic!("{e}"));
        read_lcp::<f32>(&file).unwrap_or_else(|e| panic!("{e}"));
        read_lcp::<faer::fx128>(&file).unwrap_or_else(|e| panic!("{e}"));
        assert!(a.n() >= 2, "{name}");
    }
    let sizes = [("deudeu", 2), ("ortiz", 4), ("trivial", 9)];
    for (twin, n) in sizes {
        let dense = read_lcp::<f64>(&dir.join(format!("lcp_{twin}.dat"))).unwrap();
        let block = read_lcp::<f64>(&dir.join(format!("lcp_{twin}_block.dat"))).unwrap();
        assert_eq!((dense.n(), block.n()), (n, n), "{twin}");
        for i in 0..n {
            for j in 0..n {
                assert_eq!(dense.m()[(i, j)], block.m()[(i, j)], "{twin} M({i}, {j})");
            }
            assert_eq!(dense.q()[i], block.q()[i], "{twin} q[{i}]");
        }
    }
    // Spot checks of the column-major reading: ortiz's second printed line is
    // the second column of M; tobenna is 40 x 40.
    let ortiz = read_lcp::<f64>(&dir.join("lcp_ortiz.dat")).unwrap();
    assert_eq!(
        (0..4).map(|i| ortiz.m()[(i, 1)]).collect::<Vec<_>>(),
        vec![1.0, 2.0, 1.0, 0.0]
    );
    assert_eq!(
        read_lcp::<f64>(&dir.join("lcp_tobenna.dat")).unwrap().n(),
        40
    );
    assert_eq!(read_lcp::<f64>(&dir.join("lcp_mmc.dat")).unwrap().n(), 26);
}
