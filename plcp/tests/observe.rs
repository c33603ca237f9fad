//! Streaming against storing: an observed trace hands over the very numbers
//! `plcp::solve` stores (bit for bit), a stop ends the trace early, and the
//! compact path evaluates like the full one.

use faer::{Col, Mat};
use plcp::{solve_observed, Control, Keep, Progress};
use plcp::{Method, Path, Plcp, Segment, Settings, Status};
use std::cell::RefCell;
use std::rc::Rc;

/// A deterministic generator (no dependency on a random crate's stream).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// `M = A A' + 0.1 I` (monotone), `q > 0`, `d` mostly negative: many events.
fn monotone(n: usize, seed: u64) -> Plcp<f64> {
    let mut r = Lcg(seed);
    let a = Mat::from_fn(n, n, |_, _| r.next());
    let m = Mat::from_fn(n, n, |i, j| {
        (0..n).map(|k| a[(i, k)] * a[(j, k)]).sum::<f64>() + if i == j { 0.1 } else { 0.0 }
    });
    let q = Col::from_fn(n, |_| 1.0 + r.next().abs());
    let d = Col::from_fn(n, |_| r.next() - 0.6);
    Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(1e3))
        .unwrap()
}

/// A mixed problem (Wolfe): `0 = B' z - u + b`, an equality block of size 2.
fn mixed(seed: u64) -> Plcp<f64> {
    let (p, n) = (2, 8);
    let mut r = Lcg(seed);
    let a = Mat::from_fn(n, n, |_, _| r.next());
    let b = Mat::from_fn(n, p, |_, _| r.next());
    let dim = p + n;
    let m = Mat::from_fn(dim, dim, |i, j| match (i < p, j < p) {
        (true, true) => {
            if i == j {
                -1.0
            } else {
                0.0
            }
        }
        (true, false) => -b[(j - p, i)],
        (false, true) => b[(i - p, j)],
        (false, false) => {
            let (i, j) = (i - p, j - p);
            (0..n).map(|k| a[(i, k)] * a[(j, k)]).sum::<f64>() + if i == j { 0.1 } else { 0.0 }
        }
    });
    let q = Col::from_fn(dim, |i| {
        if i < p {
            r.next()
        } else {
            1.0 + r.next().abs()
        }
    });
    let d = Col::from_fn(dim, |i| if i < p { 0.0 } else { r.next() - 0.6 });
    Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), p)
        .unwrap()
        .with_range(0.0, Some(1e3))
        .unwrap()
}

fn same_segment(a: &Segment<f64>, b: &Segment<f64>) -> bool {
    let bits = |x: &Col<f64>, y: &Col<f64>| {
        x.nrows() == y.nrows() && (0..x.nrows()).all(|i| x[i].to_bits() == y[i].to_bits())
    };
    a.lambda_from.to_bits() == b.lambda_from.to_bits()
        && a.lambda_to.to_bits() == b.lambda_to.to_bits()
        && a.unbounded == b.unbounded
        && a.basis == b.basis
        && bits(&a.z_from, &b.z_from)
        && bits(&a.dz, &b.dz)
        && bits(&a.w_from, &b.w_from)
        && bits(&a.dw, &b.dw)
        && bits(&a.u_from, &b.u_from)
        && bits(&a.du, &b.du)
}

fn same_ends(a: &Path<f64>, b: &Path<f64>) {
    assert_eq!(a.status, b.status);
    assert_eq!(a.lambda_reached.to_bits(), b.lambda_reached.to_bits());
    assert_eq!(a.breakpoints, b.breakpoints);
    assert_eq!(a.info.pivots, b.info.pivots);
    assert_eq!(a.info.residual, b.info.residual);
    for i in 0..a.end.z.nrows() {
        assert_eq!(a.end.z[i].to_bits(), b.end.z[i].to_bits());
        assert_eq!(a.end.w[i].to_bits(), b.end.w[i].to_bits());
    }
    for j in 0..a.end.u.nrows() {
        assert_eq!(a.end.u[j].to_bits(), b.end.u[j].to_bits());
    }
}

fn problems() -> Vec<(Plcp<f64>, Settings<f64>)> {
    let mut out = Vec::new();
    for seed in 1..5 {
        out.push((monotone(12, seed), Settings::default()));
        let no_scaling = Settings {
            scaling: false,
            ..Settings::default()
        };
        out.push((monotone(9, seed + 10), no_scaling));
        let wolfe = Settings {
            method: Method::Wolfe,
            ..Settings::default()
        };
        out.push((mixed(seed + 20), wolfe));
        // Lemke on a Schur reduction: shown after the trace
        out.push((mixed(seed + 30), Settings::default()));
    }
    out
}

#[test]
fn streaming_and_storing_give_the_same_bits() {
    for (k, (problem, settings)) in problems().into_iter().enumerate() {
        let stored = plcp::solve(&problem, &settings).unwrap();
        assert!(stored.segments.len() >= 2, "case {k}: too few segments");
        for keep in [
            Keep::All,
            Keep::Nothing,
            Keep::Compact {
                checkpoint_every: 3,
            },
        ] {
            let shared = Rc::new(RefCell::new(Vec::new()));
            let sink = shared.clone();
            let run = solve_observed(
                &problem,
                &settings,
                move |s: &Segment<f64>, _: &Progress<'_, f64>| {
                    sink.borrow_mut().push(s.clone());
                    Control::Continue
                },
                keep,
            )
            .unwrap();
            let seen = shared.borrow();
            assert_eq!(seen.len(), stored.segments.len(), "case {k} {keep:?}");
            for (a, b) in seen.iter().zip(&stored.segments) {
                assert!(same_segment(a, b), "case {k} {keep:?}: segment differs");
            }
            same_ends(&run.path, &stored);
            match keep {
                Keep::All => {
                    assert_eq!(run.path.segments.len(), stored.segments.len());
                    for (a, b) in run.path.segments.iter().zip(&stored.segments) {
                        assert!(same_segment(a, b));
                    }
                }
                _ => assert!(run.path.segments.is_empty(), "case {k} {keep:?}"),
            }
        }
    }
}

#[test]
fn compact_path_evaluates_as_the_full_one() {
    for (k, (problem, settings)) in problems().into_iter().enumerate() {
        let stored = plcp::solve(&problem, &settings).unwrap();
        let run = solve_observed(
            &problem,
            &settings,
            |_: &Segment<f64>, _: &Progress<'_, f64>| Control::Continue,
            Keep::Compact {
                checkpoint_every: 4,
            },
        )
        .unwrap();
        let compact = run.compact.as_ref().unwrap();
        assert_eq!(compact.len(), stored.segments.len());
        for (s, seg) in stored.segments.iter().enumerate() {
            assert_eq!(
                compact.basis(s).as_ref(),
                Some(&seg.basis),
                "case {k} basis {s}"
            );
            let hi = if seg.unbounded {
                seg.lambda_from + 1.0
            } else {
                seg.lambda_to
            };
            for t in [0.25, 0.5, 0.75] {
                let l = seg.lambda_from + t * (hi - seg.lambda_from);
                let full = stored.at(l).unwrap();
                let got = compact.at(&problem, &settings, l).unwrap().unwrap();
                let scale = full
                    .z
                    .iter()
                    .chain(full.w.iter())
                    .chain(full.u.iter())
                    .fold(1.0f64, |m, v| m.max(v.abs()));
                let exact = compact.checkpoint(compact.segment_at(l).unwrap()).is_some();
                for (a, b) in full
                    .z
                    .iter()
                    .chain(full.w.iter())
                    .chain(full.u.iter())
                    .zip(got.z.iter().chain(got.w.iter()).chain(got.u.iter()))
                {
                    if exact {
                        assert_eq!(a.to_bits(), b.to_bits(), "case {k} seg {s}: checkpoint");
                    } else {
                        assert!(
                            (a - b).abs() <= 1e-9 * scale,
                            "case {k} seg {s} at L = {l}: {a} vs {b}"
                        );
                    }
                }
            }
        }
        let outside = -1.0
            - stored
                .segments
                .iter()
                .fold(0.0f64, |m, s| m.max(s.lambda_to.abs()));
        assert!(stored.at(outside).is_none());
        assert!(compact.at(&problem, &settings, outside).unwrap().is_none());
    }
}

#[test]
fn an_observer_stops_the_trace() {
    for (k, (problem, settings)) in problems().into_iter().enumerate() {
        let stored = plcp::solve(&problem, &settings).unwrap();
        let mut count = 0;
        let run = solve_observed(
            &problem,
            &settings,
            move |_: &Segment<f64>, p: &Progress<'_, f64>| {
                count += 1;
                assert_eq!(p.index + 1, count);
                if count == 2 {
                    Control::Stop
                } else {
                    Control::Continue
                }
            },
            Keep::All,
        )
        .unwrap();
        let path = &run.path;
        assert_eq!(path.status, Status::StoppedByObserver, "case {k}");
        assert_eq!(path.segments.len(), 2);
        assert_eq!(path.lambda_reached, stored.segments[1].lambda_to);
        assert!(path.info.pivots <= stored.info.pivots);
        // the breakpoints up to the stop are the stored ones
        for (a, b) in path.breakpoints.iter().zip(&stored.breakpoints) {
            assert_eq!(a.lambda, b.lambda);
            assert_eq!(a.leaving, b.leaving);
        }
        assert!(path.message.contains("stopped by the observer"));
    }
}

#[test]
fn progress_carries_the_event_at_the_segment_start() {
    let problem = monotone(12, 7);
    let stored = plcp::solve(&problem, &Settings::default()).unwrap();
    let seen = Rc::new(RefCell::new(Vec::new()));
    let sink = seen.clone();
    solve_observed(
        &problem,
        &Settings::default(),
        move |s: &Segment<f64>, p: &Progress<'_, f64>| {
            sink.borrow_mut().push((
                s.lambda_from,
                p.breakpoint.map(|b| (b.lambda, b.leaving, b.residual)),
                p.pivots,
            ));
            Control::Continue
        },
        Keep::Nothing,
    )
    .unwrap();
    let seen = seen.borrow();
    assert!(seen[0].1.is_none() || stored.breakpoints[0].segment == 0);
    for (k, (from, bp, pivots)) in seen.iter().enumerate().skip(1) {
        let (l, leaving, res) = bp.expect("an event before every later segment");
        assert_eq!(l, *from);
        let b = stored
            .breakpoints
            .iter()
            .rev()
            .find(|b| b.segment == k)
            .unwrap();
        assert_eq!((b.lambda, b.leaving), (l, leaving));
        assert_eq!(b.residual, res);
        assert!(*pivots >= k);
    }
}

#[test]
fn the_compact_path_is_smaller() {
    let problem = monotone(60, 3);
    let stored = plcp::solve(&problem, &Settings::default()).unwrap();
    let run = solve_observed(
        &problem,
        &Settings::default(),
        |_: &Segment<f64>, _: &Progress<'_, f64>| Control::Continue,
        Keep::Compact {
            checkpoint_every: 0,
        },
    )
    .unwrap();
    assert!(stored.segments.len() > 10);
    assert!(stored.info.path_bytes > 0);
    // two full segments against all of them
    assert!(
        run.path.info.path_bytes * 4 < stored.info.path_bytes,
        "{} vs {}",
        run.path.info.path_bytes,
        stored.info.path_bytes
    );
}
