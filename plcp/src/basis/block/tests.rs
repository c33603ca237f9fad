//! Checks of the block basis: the idle refinement and rank-one updates
//! against refactorisation.

use super::*;

/// The pause of an idle refinement: after `REFINE_IDLE_RUN` small
/// corrections, 8 solves skipped; a small probe doubles the pause (to 64
/// at most); a large correction ends it.
#[test]
fn idle_refinement_pauses_and_resumes() {
    let mut s = Idle::default();
    for _ in 0..REFINE_IDLE_RUN - 1 {
        s = s.after(true);
        assert_eq!(s.skip, 0);
    }
    s = s.after(true);
    assert_eq!((s.pause, s.skip), (8, 8));
    for want in [16, 32, 64, 64] {
        s = s.after(true);
        assert_eq!((s.pause, s.skip), (want, want));
    }
    s = s.after(false);
    assert_eq!((s.run, s.pause, s.skip), (0, 0, 0));
}

/// Random pivots through every kind of transition; the block inverse must
/// agree with a freshly inverted dense basis after each.
#[test]
fn block_updates_agree_with_refactorisation() {
    updates_agree(
        |dim| {
            // a capacity of 1: the block's matrices grow as it does
            let mut b = BlockInverse::<f64>::with_capacity(dim, 1);
            // refined solves on this small basis too
            b.small_dim = 0;
            Box::new(b)
        },
        false,
    );
}

/// The same for the sparse LU with its eta file, on the sparse view of `M`
/// (with some entries zeroed, so that the pattern is really sparse).
#[test]
fn sparse_updates_agree_with_refactorisation() {
    updates_agree(|dim| Box::new(SparseLu::<f64>::new(dim)), true);
}

fn updates_agree(make: impl Fn(usize) -> Box<dyn BasisFactor<f64>>, sparse: bool) {
    let (p, n) = (3usize, 5usize);
    let dim = p + n;
    let mut seed = 12345u64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % 10_000) as f64 / 5_000.0 - 1.0
    };
    let mut m = Mat::<f64>::from_fn(dim, dim, |_, _| rnd());
    if sparse {
        for j in 0..dim {
            for i in 0..dim {
                if (i * 7 + j * 3) % 4 == 0 && i != j {
                    m[(i, j)] = 0.0;
                }
            }
        }
    }
    let csc = crate::matrix::Csc::from_dense(m.as_ref());
    let mr: MatrixRef<'_, f64> = if sparse {
        csc.as_ref()
    } else {
        m.as_ref().into()
    };
    let d = Col::<f64>::from_fn(dim, |_| rnd());
    let mut basis: Vec<Var> = (0..p)
        .map(Var::Artificial)
        .chain((0..n).map(Var::W))
        .collect();
    let mut block = make(dim);
    block.refactor(mr, &d, p, &basis).unwrap();
    let all: Vec<Var> = (0..p)
        .map(Var::U)
        .chain((0..n).map(Var::Z))
        .chain((0..n).map(Var::W))
        .chain((0..p).map(Var::Artificial))
        .chain([Var::Lambda])
        .collect();
    let mut done = 0;
    let mut k = 0usize;
    while done < 200 {
        k = (k + 7) % all.len();
        let v = all[k];
        if basis.contains(&v) {
            continue;
        }
        // the block basis alternates refined and plain solves (both must agree)
        block.set_refine(done % 2 == 0);
        let y = block.column(mr, &d, p, v);
        let r = (0..dim)
            .max_by(|&a, &b| y[a].abs().partial_cmp(&y[b].abs()).unwrap())
            .unwrap();
        if y[r].abs() < 0.3 {
            continue;
        }
        let leaving = basis[r];
        let updated = block.replace(mr, &d, p, r, leaving, v, &y);
        basis[r] = v;
        // the sparse LU asks for a refactorisation when its eta file is long
        assert!(updated || sparse, "the block update must apply");
        if !updated {
            block.refactor(mr, &d, p, &basis).unwrap();
        }
        let mut fresh = DenseInverse::<f64>::new(dim);
        fresh.refactor(mr, &d, p, &basis).unwrap();
        if done % 2 == 1 {
            // the first solve after a pivot: the block basis applies its
            // pending update in the same pass (the pivoting core's order)
            let probe = all[(k + 5) % all.len()];
            let a = block.column(mr, &d, p, probe);
            let b = fresh.column(mr, &d, p, probe);
            for i in 0..dim {
                assert!(
                    (a[i] - b[i]).abs() < 1e-8 * (1.0 + b[i].abs()),
                    "pivot {done}: {leaving} -> {v} at {r}: the fused solve for {probe} differs at {i}: {} vs {}",
                    a[i],
                    b[i]
                );
            }
        }
        for kk in 0..dim {
            let a = block.unit(kk);
            let b = fresh.unit(kk);
            for i in 0..dim {
                assert!(
                    (a[i] - b[i]).abs() < 1e-8 * (1.0 + b[i].abs()),
                    "pivot {done}: {leaving} -> {v} at {r}: B^-1 e_{kk} differs at {i}: {} vs {}",
                    a[i],
                    b[i]
                );
            }
        }
        let mut c = Col::<f64>::zeros(dim);
        c[(done * 3) % dim] = 1.0;
        let a = block.solve_transpose(&c);
        let b = fresh.solve_transpose(&c);
        for i in 0..dim {
            assert!(
                (a[i] - b[i]).abs() < 1e-8 * (1.0 + b[i].abs()),
                "transpose solve differs"
            );
        }
        // the fused solve and product against the plain ones
        let x = Col::<f64>::from_fn(dim, |i| (i as f64 * 0.37 + done as f64).sin());
        let a = var_column(mr, &d, p, all[(k + 3) % all.len()]);
        let (sa, bx) = block.solve_and_apply(mr, &d, p, &basis, &a, &x);
        let (sb, by) = fresh.solve_and_apply(mr, &d, p, &basis, &a, &x);
        // B (B^-1 a) = a checks the product independently of both inverses
        let back = apply(mr, &d, p, &basis, &sa);
        for i in 0..dim {
            assert!(
                (sa[i] - sb[i]).abs() < 1e-8 * (1.0 + sb[i].abs()),
                "fused solve differs"
            );
            assert!(
                (bx[i] - by[i]).abs() < 1e-12 * (1.0 + by[i].abs()),
                "fused product differs"
            );
            assert!(
                (back[i] - a[i]).abs() < 1e-8 * (1.0 + a[i].abs()),
                "B B^-1 a != a"
            );
        }
        done += 1;
    }
}
