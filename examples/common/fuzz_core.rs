//! The fuzz harness shared by `examples/fuzz.rs` (long runs) and
//! `tests/fuzz_short.rs` (the CI run). Not an example itself: cargo only
//! discovers `examples/*.rs` and `examples/*/main.rs`.
//!
//! Input `i` of a run with seed `s` is generated from
//! `ChaCha8Rng::seed_from_u64(s ^ mix(i))` alone, so any input can be
//! reproduced from `(s, i)` (`fuzz -- 1 --seed s --only i`).
//!
//! Targets, by `i % 8`:
//!
//! * 0, 1: a mutated plcp JSON problem -> `io::json::parse_plcp` (f64, and
//!   sometimes f32 / fx128) -> `plcp::solve` (Lemke and Wolfe, small pivot limit);
//! * 2: a mutated Siconos `.dat` file -> `io::siconos::parse_lcp_bytes` -> `solve_lcp`;
//! * 3: a mutated frames scene -> `Scene::from_bytes` -> system (9) -> `plcp::solve`
//!   (and sometimes the whole `Analysis::run`);
//! * 4..7: random small problems (order <= 9: `n <= 6`, `p <= 3`) with any
//!   values (zeros, huge, tiny, subnormal, non-finite) and random settings ->
//!   `plcp::solve` (Lemke, Wolfe) and `plcp::solve_lcp`, in f64 and sometimes
//!   f32 / fx128.
//!
//! Every call runs under `catch_unwind`; a panic hook records the message and
//! its location instead of printing it.
#![allow(dead_code)]
// index loops read like the formulas they build
#![allow(clippy::needless_range_loop)]

use faer::{Col, Mat};
use plcp::{BasisKind, Lcp, Method, Plcp, Scalar, Settings};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// Valid plcp JSON problems (mutation seeds).
pub const JSON_SAMPLES: &[&str] = &[
    r#"{"M": [[2, 1], [1, 2]], "q": [1, 1], "d": [-1, -0.5], "lambda_max": null, "free": 0, "lambda0": 0}"#,
    r#"{"M": [[0, 1, -1], [-1, 2, 0], [1, 0, 3]], "q": [0, 1, 2], "d": [1, -1, -2], "lambda_max": 10, "free": 1}"#,
    r#"{"M": [[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 1], [0, 0, 1, 1]], "q": [-1, 0.5, 1, 2], "d": [0, -1, -1, 1e-3], "lambda_max": "inf", "free": 0}"#,
    r#"{"M": [[0, 0, 1, -1], [0, 0, -1, 1], [-1, 1, 0, 0], [1, -1, 0, 0]], "q": [0, 0, 1, 1], "d": [-1, 1, 0, 0], "free": 2, "lambda0": 0.5}"#,
    r#"{"M": [[1e-8, 0], [0, 1e8]], "q": ["1e-3", "-2"], "d": [-1, "0"], "lambda_max": 1e6}"#,
];

/// Valid Siconos `.dat` texts (mutation seeds).
pub const DAT_SAMPLES: &[&str] = &[
    "2\n0\n2\n2\n2\t2\n2 1\n1 2\n-5 -6\n\nsome comment\n",
    "2\n0\n2\n2\n2\t2\n1 1\n1 1\n-1 -1\n\nRemark 4.1.14 CPS 2009\n",
    "3\n0\n3\n3\n3\t3\n1 2 2\n0 1 2\n0 0 1\n-1 -1 -1\n",
    "4\n0\n4\n4\n4\t4\n0 0 1 2\n0 0 3 1\n2 1 0 0\n1 3 0 0\n-1 -1 -1 -1\n",
    // sparse block: two 1x1 diagonal blocks
    "2\n1\n2\n2\n2\n2 2\n1 2\n1 2\n3 2\n0 1 2\n0 1\n0 4\n1 5\n-1 -1\n",
];

/// A minimal scene, used when no scene directory is given.
pub const TOML_FALLBACK: &str = r#"
[[node]]
id = "A"
x = 0.0
y = 0.0
[[node]]
id = "B"
x = 1.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
elements = 2
mass_per_length = 1.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[load]]
node = "B"
fy = -1.0
"#;

/// Replacement values for a number in a text input.
const EXTREMES: &[&str] = &[
    "0",
    "-0",
    "0.0",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-308",
    "-1e-308",
    "4.9e-324",
    "1e309",
    "-1e309",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "\"NaN\"",
    "\"inf\"",
    "\"-inf\"",
    "\"1e400\"",
    "99999999999999999999999",
    "-9223372036854775808",
    "9223372036854775807",
    "18446744073709551616",
    "4294967296",
    "100000",
    "100001",
    "8193",
    "3.5e38",
    "1e39",
    "1e-45",
    "-1",
    "1",
    "2",
    "1e15",
    "0x10",
    "1_0",
    "+1",
    "1e",
    ".",
    "",
];

/// Which target an input went to.
pub const TARGETS: [&str; 4] = ["json", "siconos", "toml", "random"];

thread_local! {
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Installs a panic hook that records the message and location of a panic
/// (in the panicking thread) instead of printing it.
pub fn install_hook() {
    std::panic::set_hook(Box::new(|info| {
        let msg = if let Some(s) = info.payload().downcast_ref::<&str>() {
            (*s).to_string()
        } else if let Some(s) = info.payload().downcast_ref::<String>() {
            s.clone()
        } else {
            "(non-string panic payload)".to_string()
        };
        let loc = info
            .location()
            .map(|l| format!("{}:{}", l.file(), l.line()))
            .unwrap_or_default();
        LAST_PANIC.with(|p| *p.borrow_mut() = Some(format!("{loc}: {msg}")));
    }));
}

/// Counts of a run.
#[derive(Default, Debug, Clone)]
pub struct Summary {
    /// Inputs run.
    pub inputs: u64,
    /// Inputs per target.
    pub per_target: [u64; 4],
    /// Calls made (readers and solvers).
    pub calls: u64,
    /// Panicking calls.
    pub panics: u64,
    /// Distinct panics (key: location and message with digits removed):
    /// count, first message, first input index, the input's description.
    pub distinct: BTreeMap<String, (u64, String, u64, String)>,
    /// Errors by reader/solver and first word of the message.
    pub errors: BTreeMap<String, u64>,
    /// Statuses by solver and precision.
    pub statuses: BTreeMap<String, u64>,
    /// Inputs that took more than `slow_secs` (index, seconds, description).
    pub slow: Vec<(u64, f64, String)>,
    /// Slowest input (index, seconds).
    pub slowest: (u64, f64),
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Description of the last input run.
    pub last_desc: String,
}

impl Summary {
    /// Merges another summary (another thread's share).
    pub fn merge(&mut self, o: Summary) {
        self.inputs += o.inputs;
        for k in 0..4 {
            self.per_target[k] += o.per_target[k];
        }
        self.calls += o.calls;
        self.panics += o.panics;
        for (k, v) in o.distinct {
            let e = self
                .distinct
                .entry(k)
                .or_insert((0, v.1.clone(), v.2, v.3.clone()));
            e.0 += v.0;
            if v.2 < e.2 {
                e.1 = v.1;
                e.2 = v.2;
                e.3 = v.3;
            }
        }
        for (k, v) in o.errors {
            *self.errors.entry(k).or_default() += v;
        }
        for (k, v) in o.statuses {
            *self.statuses.entry(k).or_default() += v;
        }
        self.slow.extend(o.slow);
        if o.slowest.1 > self.slowest.1 {
            self.slowest = o.slowest;
        }
    }

    /// The summary table.
    pub fn table(&self) -> String {
        let mut s = String::new();
        s += &format!(
            "inputs {}  (json {}, siconos {}, toml {}, random {})\n",
            self.inputs,
            self.per_target[0],
            self.per_target[1],
            self.per_target[2],
            self.per_target[3]
        );
        s += &format!(
            "calls {}  panics {}  distinct panics {}  inputs > 1 s: {}  slowest input #{} {:.3} s  wall {:.1} s\n",
            self.calls,
            self.panics,
            self.distinct.len(),
            self.slow.len(),
            self.slowest.0,
            self.slowest.1,
            self.seconds
        );
        s += "\noutcome                                             count\n";
        for (k, v) in &self.statuses {
            s += &format!("  status  {k:<42} {v:>10}\n");
        }
        for (k, v) in &self.errors {
            s += &format!("  error   {k:<42} {v:>10}\n");
        }
        for (k, (n, msg, idx, _)) in &self.distinct {
            s += &format!("  PANIC x{n} (first input #{idx}) {msg}\n      key {k}\n");
        }
        for (idx, secs, desc) in &self.slow {
            s += &format!("  SLOW input #{idx}: {secs:.2} s  {}\n", short(desc, 200));
        }
        s
    }
}

fn short(s: &str, n: usize) -> String {
    if s.len() <= n {
        s.to_string()
    } else {
        let mut end = n;
        while !s.is_char_boundary(end) {
            end -= 1;
        }
        format!("{}...", &s[..end])
    }
}

/// The per-input generator seed.
pub fn input_seed(seed: u64, i: u64) -> u64 {
    // splitmix64 of the index
    let mut z = i.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    seed ^ z ^ (z >> 31)
}

struct Ctx<'a> {
    sum: &'a mut Summary,
    index: u64,
    desc: String,
}

impl Ctx<'_> {
    /// Runs `f` under `catch_unwind`, counting a panic under `what`.
    fn call<R>(&mut self, what: &str, f: impl FnOnce() -> R) -> Option<R> {
        self.sum.calls += 1;
        match catch_unwind(AssertUnwindSafe(f)) {
            Ok(r) => Some(r),
            Err(_) => {
                let msg = LAST_PANIC
                    .with(|p| p.borrow_mut().take())
                    .unwrap_or_else(|| "(no message)".into());
                // distinct by the caller (without precision) and the panic's location
                let family: String = what
                    .split_whitespace()
                    .nth(1)
                    .unwrap_or("")
                    .split('/')
                    .take(2)
                    .collect::<Vec<_>>()
                    .join("/");
                let loc = msg
                    .split_whitespace()
                    .find(|w| w.contains(".rs:"))
                    .unwrap_or("")
                    .trim_end_matches(':');
                let key = format!("{family} @ {loc}");
                let msg = format!("[{what}] {msg}");
                self.sum.panics += 1;
                let e =
                    self.sum
                        .distinct
                        .entry(key)
                        .or_insert((0, msg, self.index, self.desc.clone()));
                e.0 += 1;
                None
            }
        }
    }
    fn error(&mut self, what: &str, e: &dyn std::fmt::Display) {
        let text = e.to_string();
        // the message's kind: the words after "file:line:col: " up to the first quote or number
        let tail = text.rsplit(": ").next().unwrap_or("");
        let kind: String = tail
            .split(|c: char| c.is_ascii_digit() || matches!(c, '\'' | '"' | '(' | '`' | ','))
            .next()
            .unwrap_or("")
            .trim()
            .chars()
            .take(36)
            .collect();
        *self
            .sum
            .errors
            .entry(format!("{what}: {kind}"))
            .or_default() += 1;
    }
    fn status(&mut self, what: &str, s: plcp::Status) {
        *self
            .sum
            .statuses
            .entry(format!("{what} {}", s.as_str()))
            .or_default() += 1;
    }
}

// ------------------------------------------------------------ mutation

fn number_spans(b: &[u8]) -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_digit() || (b[i] == b'-' && i + 1 < b.len() && b[i + 1].is_ascii_digit()) {
            let s = i;
            i += 1;
            while i < b.len()
                && (b[i].is_ascii_digit() || matches!(b[i], b'.' | b'e' | b'E' | b'+' | b'-'))
            {
                i += 1;
            }
            v.push((s, i));
        } else {
            i += 1;
        }
    }
    v
}

/// One to three random mutations of `src`.
pub fn mutate(rng: &mut ChaCha8Rng, src: &[u8]) -> Vec<u8> {
    let mut b = src.to_vec();
    let k = rng.gen_range(1..=3);
    for _ in 0..k {
        match rng.gen_range(0..10) {
            0 | 1 => {
                // byte flip
                if !b.is_empty() {
                    let i = rng.gen_range(0..b.len());
                    if rng.gen_bool(0.5) {
                        b[i] ^= 1 << rng.gen_range(0..8);
                    } else {
                        b[i] = *b"{}[],:=\"\n\t -.e0123456789\x00\xff"
                            .get(rng.gen_range(0..28))
                            .unwrap_or(&b'x');
                    }
                }
            }
            2 => {
                // truncation
                let l = rng.gen_range(0..=b.len());
                b.truncate(l);
            }
            3..=6 => {
                // number replacement
                let spans = number_spans(&b);
                if !spans.is_empty() {
                    let (s, e) = spans[rng.gen_range(0..spans.len())];
                    let rep = if rng.gen_bool(0.8) {
                        EXTREMES[rng.gen_range(0..EXTREMES.len())].to_string()
                    } else {
                        format!("{:e}", random_value(rng))
                    };
                    b.splice(s..e, rep.bytes());
                }
            }
            7 => {
                // delete a line
                let lines: Vec<&[u8]> = b.split(|&c| c == b'\n').collect();
                if lines.len() > 1 {
                    let drop = rng.gen_range(0..lines.len());
                    let out: Vec<&[u8]> = lines
                        .iter()
                        .enumerate()
                        .filter(|(i, _)| *i != drop)
                        .map(|(_, l)| *l)
                        .collect();
                    b = out.join(&b'\n');
                }
            }
            8 => {
                // duplicate a line
                let lines: Vec<Vec<u8>> = b.split(|&c| c == b'\n').map(|l| l.to_vec()).collect();
                if !lines.is_empty() {
                    let dup = rng.gen_range(0..lines.len());
                    let mut out = lines.clone();
                    out.insert(dup, lines[dup].clone());
                    b = out.join(&b'\n');
                }
            }
            _ => {
                // delete or insert a random range of bytes
                if !b.is_empty() {
                    let s = rng.gen_range(0..b.len());
                    let e = (s + rng.gen_range(1..8)).min(b.len());
                    if rng.gen_bool(0.5) {
                        b.drain(s..e);
                    } else {
                        let piece = b[s..e].to_vec();
                        b.splice(s..s, piece);
                    }
                }
            }
        }
    }
    b
}

// ------------------------------------------------------------ random values

/// A value from a distribution that favours the troublesome ones.
pub fn random_value(rng: &mut ChaCha8Rng) -> f64 {
    match rng.gen_range(0..20) {
        0..=2 => 0.0,
        3 => -0.0,
        4 => [1.0, -1.0, 2.0, -2.0, 0.5][rng.gen_range(0..5)],
        5..=9 => rng.gen_range(-1.0..1.0),
        10 | 11 => {
            let e = rng.gen_range(-308..=308);
            let s = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
            s * rng.gen_range(1.0..10.0) * 10f64.powi(e)
        }
        12 => {
            let e = rng.gen_range(-40..=40);
            rng.gen_range(-1.0..1.0) * 10f64.powi(e)
        }
        13 => [
            f64::MAX,
            -f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            3.4e38,
            -3.4e38,
        ][rng.gen_range(0..7)],
        14 => [
            1e-45,
            1.2e-38,
            f32::MAX as f64,
            f32::MIN_POSITIVE as f64,
            1e-12,
            1e12,
        ][rng.gen_range(0..6)],
        15 => f64::from(rng.gen_range(-5i32..=5)),
        16 => 1.0 + rng.gen_range(-1.0..1.0) * 1e-12,
        17 => [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][rng.gen_range(0..3)],
        _ => rng.gen_range(-100.0..100.0),
    }
}

/// A random small mixed problem's data, before any check.
#[derive(Clone, Debug)]
pub struct RawProblem {
    /// `M` by rows.
    pub m: Vec<Vec<f64>>,
    /// `q`.
    pub q: Vec<f64>,
    /// `d`.
    pub d: Vec<f64>,
    /// Number of free variables.
    pub free: usize,
    /// `lambda0`.
    pub lambda0: f64,
    /// `lambda_max`.
    pub lambda_max: Option<f64>,
}

impl RawProblem {
    /// The problem as plcp JSON (non-finite values as strings).
    pub fn to_json(&self) -> String {
        fn num(v: f64) -> String {
            if v.is_finite() {
                format!("{v:e}")
            } else {
                format!("\"{v}\"")
            }
        }
        let rows: Vec<String> = self
            .m
            .iter()
            .map(|r| {
                format!(
                    "[{}]",
                    r.iter().map(|&v| num(v)).collect::<Vec<_>>().join(", ")
                )
            })
            .collect();
        let vec = |v: &[f64]| v.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ");
        format!(
            "{{\"M\": [{}], \"q\": [{}], \"d\": [{}], \"lambda_max\": {}, \"free\": {}, \"lambda0\": {}}}",
            rows.join(", "),
            vec(&self.q),
            vec(&self.d),
            self.lambda_max.map_or("null".into(), num),
            self.free,
            num(self.lambda0)
        )
    }
}

/// A random small problem: `n <= 6` complementary pairs, `p <= 3` free variables.
pub fn random_problem(rng: &mut ChaCha8Rng) -> RawProblem {
    let p = if rng.gen_bool(0.6) {
        0
    } else {
        rng.gen_range(1..=3)
    };
    let n = rng.gen_range(if p == 0 { 1 } else { 0 }..=6);
    let dim = n + p;
    let mut m = vec![vec![0.0; dim]; dim];
    let style = rng.gen_range(0..8);
    match style {
        0 => {
            // PSD: B B' with B of random rank
            let r = rng.gen_range(0..=dim);
            let b: Vec<Vec<f64>> = (0..dim)
                .map(|_| (0..r).map(|_| random_value(rng)).collect())
                .collect();
            for i in 0..dim {
                for j in 0..dim {
                    m[i][j] = (0..r).map(|k| b[i][k] * b[j][k]).sum();
                }
            }
        }
        1 => {
            // diagonal
            for (i, row) in m.iter_mut().enumerate() {
                row[i] = random_value(rng);
            }
        }
        2 => {
            // all zero or all one
            let v = if rng.gen_bool(0.5) { 0.0 } else { 1.0 };
            for row in &mut m {
                row.fill(v);
            }
        }
        3 => {
            // skew plus a small diagonal (bimatrix-like)
            for i in 0..dim {
                for j in 0..i {
                    let v = random_value(rng);
                    m[i][j] = v;
                    m[j][i] = -v;
                }
                m[i][i] = if rng.gen_bool(0.5) {
                    0.0
                } else {
                    random_value(rng)
                };
            }
        }
        4 => {
            // mixed KKT-like: zero free block, coupling blocks
            for i in 0..dim {
                for j in 0..dim {
                    if !(i < p && j < p) {
                        m[i][j] = random_value(rng);
                    }
                }
            }
        }
        5 => {
            // duplicated rows/columns
            for i in 0..dim {
                for j in 0..dim {
                    m[i][j] = random_value(rng);
                }
            }
            if dim > 1 {
                let (a, b) = (rng.gen_range(0..dim), rng.gen_range(0..dim));
                m[b] = m[a].clone();
            }
        }
        _ => {
            for row in m.iter_mut() {
                for v in row.iter_mut() {
                    *v = random_value(rng);
                }
            }
        }
    }
    // occasional scale of the whole matrix
    if rng.gen_bool(0.15) {
        let s = 10f64.powi(rng.gen_range(-300..=300));
        for row in &mut m {
            for v in row {
                *v *= s;
            }
        }
    }
    let q: Vec<f64> = (0..dim).map(|_| random_value(rng)).collect();
    let d: Vec<f64> = (0..dim).map(|_| random_value(rng)).collect();
    let lambda0 = if rng.gen_bool(0.8) {
        0.0
    } else {
        random_value(rng)
    };
    let lambda_max = match rng.gen_range(0..4) {
        0 => None,
        1 => Some(f64::INFINITY),
        _ => Some(random_value(rng)),
    };
    RawProblem {
        m,
        q,
        d,
        free: p,
        lambda0,
        lambda_max,
    }
}

fn random_settings<T: Scalar>(rng: &mut ChaCha8Rng, n: usize) -> Settings<T> {
    let mut s = Settings::<T> {
        max_pivots: Some(rng.gen_range(1..=40)),
        ..Settings::default()
    };
    if rng.gen_bool(0.2) {
        s.scaling = false;
    }
    if rng.gen_bool(0.2) {
        s.basis = BasisKind::Dense;
    }
    if rng.gen_bool(0.1) {
        s.refactor_period = Some(rng.gen_range(1..5));
    }
    if rng.gen_bool(0.05) {
        s.covering = Some(Col::from_fn(n, |_| T::from_f64(random_value(rng))));
    } else if rng.gen_bool(0.1) {
        s.covering = Some(Col::from_fn(n, |_| T::from_f64(rng.gen_range(0.01..100.0))));
    }
    if rng.gen_bool(0.03) {
        s.pivot_tol_eps = random_value(rng);
    }
    if rng.gen_bool(0.03) {
        s.max_cond_eps = random_value(rng);
    }
    s
}

// ------------------------------------------------------------ the solver calls

fn solve_plcp<T: Scalar>(cx: &mut Ctx, rng: &mut ChaCha8Rng, pb: &Plcp<T>, tag: &str) {
    for method in [Method::Lemke, Method::Wolfe] {
        let mut s = random_settings::<T>(rng, pb.n());
        s.method = method;
        let what = format!(
            "solve/{}/{}",
            if method == Method::Lemke {
                "lemke"
            } else {
                "wolfe"
            },
            T::NAME
        );
        let probe = random_value(rng);
        let how = format!(
            "{tag} {what} (max_pivots {:?}, scaling {}, basis {:?}, refactor_period {:?}, covering {:?}, pivot_tol_eps {}, max_cond_eps {})",
            s.max_pivots,
            s.scaling,
            s.basis,
            s.refactor_period,
            s.covering.as_ref().map(|c| (0..c.nrows()).map(|i| c[i].to_f64()).collect::<Vec<_>>()),
            s.pivot_tol_eps,
            s.max_cond_eps
        );
        let r = cx.call(&how, || {
            let r = plcp::solve(pb, &s);
            if let Ok(path) = &r {
                // evaluate the path and write it as JSON: both must not panic
                let l = T::from_f64(probe);
                let _ = path.at(l);
                let _ = path.at(path.lambda_reached);
                let _ = plcp::io::json::path_json(pb, path, &[probe], 0.0);
            }
            r.map(|p| p.status)
        });
        match r {
            Some(Ok(st)) => cx.status(&what, st),
            Some(Err(e)) => cx.error(&what, &e),
            None => {}
        }
    }
}

fn solve_lcp_in<T: Scalar>(cx: &mut Ctx, rng: &mut ChaCha8Rng, lcp: &Lcp<T>, tag: &str) {
    let s = random_settings::<T>(rng, lcp.n());
    let what = format!("solve_lcp/{}", T::NAME);
    let how =
        format!(
        "{tag} {what} (max_pivots {:?}, scaling {}, basis {:?}, refactor_period {:?}, covering {:?})",
        s.max_pivots,
        s.scaling,
        s.basis,
        s.refactor_period,
        s.covering.as_ref().map(|c| (0..c.nrows()).map(|i| c[i].to_f64()).collect::<Vec<_>>()),
    );
    let r = cx.call(&how, || {
        plcp::solve_lcp(lcp, &s).map(|sol| {
            let _ = plcp::io::siconos::siconos_error(lcp.q(), sol.z.as_ref(), sol.w.as_ref());
            sol.status
        })
    });
    match r {
        Some(Ok(st)) => cx.status(&what, st),
        Some(Err(e)) => cx.error(&what, &e),
        None => {}
    }
}

fn run_json(cx: &mut Ctx, rng: &mut ChaCha8Rng, bytes: &[u8]) {
    let r = cx.call("parse_plcp f64", || {
        plcp::io::json::parse_plcp::<f64>(bytes, "fuzz.json")
    });
    match r {
        Some(Ok(pb)) => {
            cx.status("parse_plcp", plcp::Status::Reached);
            if pb.dim() <= 12 {
                solve_plcp(cx, rng, &pb, "json");
            }
        }
        Some(Err(e)) => cx.error("parse_plcp", &e),
        None => {}
    }
    if rng.gen_bool(0.25) {
        match cx.call("parse_plcp f32", || {
            plcp::io::json::parse_plcp::<f32>(bytes, "fuzz.json")
        }) {
            Some(Ok(pb)) if pb.dim() <= 12 => solve_plcp(cx, rng, &pb, "json"),
            Some(Err(e)) => cx.error("parse_plcp/f32", &e),
            _ => {}
        }
    }
    if rng.gen_bool(0.1) {
        if let Some(Ok(pb)) = cx.call("parse_plcp fx128", || {
            plcp::io::json::parse_plcp::<faer::fx128>(bytes, "fuzz.json")
        }) {
            if pb.dim() <= 12 {
                solve_plcp(cx, rng, &pb, "json");
            }
        }
    }
}

fn run_dat(cx: &mut Ctx, rng: &mut ChaCha8Rng, bytes: &[u8]) {
    // the bytes as a file holds them: a mutated byte that breaks UTF-8 is an error
    let r = cx.call("parse_lcp f64", || {
        plcp::io::siconos::parse_lcp_bytes::<f64>(bytes, "fuzz.dat")
    });
    match r {
        Some(Ok(lcp)) => {
            cx.status("parse_lcp", plcp::Status::Reached);
            if lcp.n() <= 12 {
                solve_lcp_in(cx, rng, &lcp, "dat");
                if rng.gen_bool(0.2) {
                    let l32: Lcp<f32> = lcp.cast();
                    solve_lcp_in(cx, rng, &l32, "dat");
                }
            }
        }
        Some(Err(e)) => cx.error("parse_lcp", &e),
        None => {}
    }
    if rng.gen_bool(0.2) {
        if let Some(Err(e)) = cx.call("parse_lcp f32", || {
            plcp::io::siconos::parse_lcp_bytes::<f32>(bytes, "fuzz.dat")
        }) {
            cx.error("parse_lcp/f32", &e);
        }
    }
}

/// Largest `elements = n` handed to the scene reader: `Scene::from_toml`
/// checks a whole frame for massless mechanisms with dense linear algebra, so
/// a mutated `elements = 8193` takes seconds to parse (reported separately,
/// see the stiff report's 1000-element cantilever); such inputs are counted
/// and skipped to keep a million-input run within minutes.
pub const MAX_FUZZ_ELEMENTS: i64 = 2000;

fn too_many_elements(text: &str) -> bool {
    // TOML integers: decimal with `_` and `+`, or 0x / 0o / 0b literals
    let parse = |v: &str| -> Option<i64> {
        let v: String = v
            .trim()
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == '+')
            .filter(|c| *c != '_' && *c != '+')
            .collect();
        let (digits, radix) = match v.get(..2) {
            Some("0x") => (&v[2..], 16),
            Some("0o") => (&v[2..], 8),
            Some("0b") => (&v[2..], 2),
            _ => (v.as_str(), 10),
        };
        i64::from_str_radix(digits, radix).ok()
    };
    text.lines().any(|l| {
        let l = l.trim_start();
        l.starts_with("elements")
            && l.split_once('=').is_some_and(|(_, v)| {
                // unparsable or beyond i64: let the reader judge it, unless long
                parse(v).map_or(v.trim().len() > 6, |n| n > MAX_FUZZ_ELEMENTS)
            })
    })
}

fn run_toml(cx: &mut Ctx, rng: &mut ChaCha8Rng, bytes: &[u8]) {
    let text = String::from_utf8_lossy(bytes).into_owned();
    if too_many_elements(&text) {
        *cx.sum
            .statuses
            .entry("toml skipped (elements > 2000)".into())
            .or_default() += 1;
        return;
    }
    // the lossy text only screens out huge element counts; the reader gets the bytes
    let r = cx.call("Scene::from_bytes", || {
        frames::Scene::from_bytes(bytes, "fuzz.toml")
    });
    let scene = match r {
        Some(Ok(s)) => s,
        Some(Err(e)) => {
            cx.error("from_toml", &e);
            return;
        }
        None => return,
    };
    cx.status("from_toml", plcp::Status::Reached);
    // a mutated `elements = 100000` parses, but system (9) of such a frame is
    // a dense matrix far too large for a fuzz input: assemble small frames only
    if scene.frame.nodes.len() > 40 {
        *cx.sum
            .statuses
            .entry("toml skipped (large frame)".into())
            .or_default() += 1;
        return;
    }
    let sys = match cx.call("System::assemble", || {
        frames::System::assemble(&scene.frame)
    }) {
        Some(s) => s,
        None => return,
    };
    let pb = match cx.call("System::plcp", || sys.plcp::<f64>(None)) {
        Some(Ok(p)) => p,
        Some(Err(e)) => {
            cx.error("System::plcp", &e);
            return;
        }
        None => return,
    };
    let mut s = Settings::<f64>::with_method(Method::Wolfe);
    s.max_pivots = Some(rng.gen_range(1..=200));
    if let Some(r) = cx.call("toml solve/wolfe", || plcp::solve(&pb, &s)) {
        match r {
            Ok(p) => cx.status("toml solve/wolfe/f64", p.status),
            Err(e) => cx.error("toml solve/wolfe", &e),
        }
    }
    if rng.gen_bool(0.3) {
        let mut opts = frames::AnalysisOptions {
            samples: 21,
            ..Default::default()
        };
        if rng.gen_bool(0.3) {
            opts.solve.precision =
                [plcp::Precision::F32, plcp::Precision::F128][rng.gen_range(0..2)];
        }
        if rng.gen_bool(0.2) {
            opts.solve.method = Method::Lemke;
        }
        if rng.gen_bool(0.2) {
            opts.solve.lambda_max = Some(random_value(rng));
        }
        if rng.gen_bool(0.1) {
            opts.t_end = Some(random_value(rng));
        }
        let how = format!(
            "toml Analysis::run ({:?}, t_end {:?})",
            opts.solve, opts.t_end
        );
        let r = cx.call(&how, || {
            frames::Analysis::run(scene, &opts).map(|a| {
                let _ = a.to_text();
                let _ = a.to_json();
                a.solution.status
            })
        });
        match r {
            Some(Ok(st)) => cx.status("Analysis::run", st),
            Some(Err(e)) => cx.error("Analysis::run", &e),
            None => {}
        }
    }
}

fn run_random(cx: &mut Ctx, rng: &mut ChaCha8Rng) {
    let raw = random_problem(rng);
    cx.desc = format!("random problem (plcp JSON): {}", raw.to_json());
    let dim = raw.q.len();
    let m = Mat::<f64>::from_fn(dim, dim, |i, j| raw.m[i][j]);
    let q = Col::<f64>::from_fn(dim, |i| raw.q[i]);
    let d = Col::<f64>::from_fn(dim, |i| raw.d[i]);
    let r = cx.call("Plcp::mixed", || {
        Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), raw.free)
            .and_then(|p| p.with_range(raw.lambda0, raw.lambda_max))
    });
    let pb = match r {
        Some(Ok(p)) => Some(p),
        Some(Err(e)) => {
            cx.error("Plcp::new", &e);
            None
        }
        None => None,
    };
    if let Some(pb) = pb {
        solve_plcp(cx, rng, &pb, "random");
        if rng.gen_bool(0.15) {
            let p32: Plcp<f32> = pb.cast();
            solve_plcp(cx, rng, &p32, "random");
        }
        if rng.gen_bool(0.05) {
            let p128: Plcp<faer::fx128> = pb.cast();
            solve_plcp(cx, rng, &p128, "random");
        }
    }
    // the plain LCP on the complementary block
    if raw.free == 0 {
        let r = cx.call("Lcp::new", || Lcp::new(m.as_ref(), q.as_ref()));
        match r {
            Some(Ok(lcp)) => {
                solve_lcp_in(cx, rng, &lcp, "random");
                if rng.gen_bool(0.1) {
                    let l128: Lcp<faer::fx128> = lcp.cast();
                    solve_lcp_in(cx, rng, &l128, "random");
                }
            }
            Some(Err(e)) => cx.error("Lcp::new", &e),
            None => {}
        }
    }
}

/// Runs one input; returns its target.
pub fn run_one(sum: &mut Summary, seed: u64, i: u64, scenes: &[String]) -> usize {
    let mut rng = ChaCha8Rng::seed_from_u64(input_seed(seed, i));
    let target = match i % 8 {
        0 | 1 => 0,
        2 => 1,
        3 => 2,
        _ => 3,
    };
    let mut cx = Ctx {
        sum,
        index: i,
        desc: String::new(),
    };
    let keep = rng.gen_bool(0.03); // sometimes the valid input itself
    let bytes_of = |src: &str, rng: &mut ChaCha8Rng| -> Vec<u8> {
        if keep {
            src.as_bytes().to_vec()
        } else {
            mutate(rng, src.as_bytes())
        }
    };
    match target {
        0 => {
            let src = JSON_SAMPLES[rng.gen_range(0..JSON_SAMPLES.len())];
            let b = bytes_of(src, &mut rng);
            cx.desc = format!("json input:\n{}", String::from_utf8_lossy(&b));
            run_json(&mut cx, &mut rng, &b);
        }
        1 => {
            let src = DAT_SAMPLES[rng.gen_range(0..DAT_SAMPLES.len())];
            let b = bytes_of(src, &mut rng);
            cx.desc = format!("siconos .dat input:\n{}", String::from_utf8_lossy(&b));
            run_dat(&mut cx, &mut rng, &b);
        }
        2 => {
            let src = if scenes.is_empty() {
                TOML_FALLBACK
            } else {
                scenes[rng.gen_range(0..scenes.len())].as_str()
            };
            let b = bytes_of(src, &mut rng);
            cx.desc = format!("toml scene:\n{}", String::from_utf8_lossy(&b));
            run_toml(&mut cx, &mut rng, &b);
        }
        _ => run_random(&mut cx, &mut rng),
    }
    cx.sum.last_desc = std::mem::take(&mut cx.desc);
    target
}

/// Reads every `*.toml` in `dir` and its subfolders (the stiff and pipe-whip
/// scenes, planar and grillage), sorted by path; empty if absent.
pub fn read_scenes(dir: &std::path::Path) -> Vec<String> {
    fn collect(dir: &std::path::Path, files: &mut Vec<std::path::PathBuf>) {
        let Ok(rd) = std::fs::read_dir(dir) else {
            return;
        };
        for p in rd.filter_map(|e| e.ok()).map(|e| e.path()) {
            if p.is_dir() {
                collect(&p, files);
            } else if p.extension().is_some_and(|x| x == "toml") {
                files.push(p);
            }
        }
    }
    let mut files = Vec::new();
    collect(dir, &mut files);
    files.sort();
    files
        .iter()
        .filter_map(|p| std::fs::read_to_string(p).ok())
        .collect()
}

/// Runs inputs `range` (with `seed`) in this thread; inputs over `slow_secs`
/// are listed. `progress` is called every 2^16 inputs.
pub fn run_range(
    seed: u64,
    range: std::ops::Range<u64>,
    scenes: &[String],
    slow_secs: f64,
    current: Option<&std::sync::atomic::AtomicU64>,
    mut progress: impl FnMut(&Summary),
) -> Summary {
    let mut sum = Summary::default();
    let t0 = Instant::now();
    for i in range {
        if let Some(c) = current {
            c.store(i, std::sync::atomic::Ordering::Relaxed);
        }
        let t = Instant::now();
        let target = run_one(&mut sum, seed, i, scenes);
        let secs = t.elapsed().as_secs_f64();
        sum.inputs += 1;
        sum.per_target[target] += 1;
        if secs > sum.slowest.1 {
            sum.slowest = (i, secs);
        }
        if secs > slow_secs {
            sum.slow.push((
                i,
                secs,
                format!("target {} (reproduce with --only {i})", TARGETS[target]),
            ));
        }
        if sum.inputs % 65536 == 0 {
            sum.seconds = t0.elapsed().as_secs_f64();
            progress(&sum);
        }
    }
    sum.seconds = t0.elapsed().as_secs_f64();
    sum
}
