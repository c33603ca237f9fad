//! Space scenes (`model = "space"`): nodes at `(x, y, z)` with six components
//! `x, y, z, rx, ry, rz`, loads `fx, fy, fz, mx, my, mz`, and what of them
//! the scene needs, found automatically.
//!
//! **The reduction.** A frame whose nodes lie in one plane with unit normal
//! `e3` decouples, section by section, into an in-plane problem (the plane's
//! translations, the rotation about `e3`; the axial force and the bending
//! moment about `e3`) and an out-of-plane one (the translation along `e3`,
//! the rotations about in-plane axes; the bending moment about the in-plane
//! normal of the member and the torque). The pipe's yield condition
//! `(M2^2 + M3^2)/Mp^2 + (T/Tp)^2 <= 1` (with `N` where `plastic_axial` is
//! given) has, at zero out-of-plane forces, the cross-section `|M3| <= Mp`
//! (with `N`: the bending-axial curve), and at zero in-plane forces the
//! bending-torsion curve in `(M2, T)`. So a scene whose loads are all in the
//! plane has the solution of the planar model with the out-of-plane unknowns
//! at zero (a feasible stress, zero out-of-plane motion: the planar path is
//! a solution of the space system), and one whose loads are all normal to the
//! plane that of the grillage model. The scene is then solved as that model
//! in the plane's axes:
//!
//! - the plane: the normal of the first three non-collinear nodes (all
//!   `[[node]]`s within `1e-12` of the extent of the plane); a straight
//!   scene (all nodes on one line `t`) takes the first that fits its loads
//!   of: the plane through `t` and the first force across `t` (planar), the
//!   plane normal to that force (grillage), the normal along the first
//!   moment across `t`, `z`, any plane through `t` (a rule that turns with
//!   the scene: a straight grillage scene written in space is solved as
//!   planar, in the plane of its loads, with the same numbers);
//! - the axes: the global ones when the normal is `z` (then the scene's `x, y`
//!   are used unchanged: a planar or grillage scene written as a space scene
//!   with `z = 0` gives the same numbers bit for bit); else `e1` the plane's
//!   direction nearest to global `x` (to `y` if `x` is nearly normal),
//!   `e3` the normal with its largest component positive, `e2 = e3 x e1`; the
//!   report's `x, y` (`z, rx, ry`) are then the components along `e1, e2`
//!   (`e3`, about `e1`, about `e2`), and the report names the axes;
//! - the loads: a component smaller than `1e-12` of the largest force (or
//!   moment) is rounding; loads in the plane give the planar model, normal
//!   to it the grillage; both (or nodes off one plane): the general space
//!   model, and the report says why;
//! - supports: a fixed set of global translations (rotations) must be
//!   spanned by the plane's axes (fix `x, y, z` together, or only axes that
//!   are the plane's); the components of the other model are left out.
//!
//! Every member needs `plastic_torque` (a pipe); `plastic_axial` is optional
//! as in a planar scene (refused in the general model). An arc's points
//! count in the plane check (`arc_axes` gives its in-plane axes).
//!
//! **The general space model** ([`crate::kind::Model::Space`]): six
//! components per node in global axes, element axes from
//! [`element_axes`], each section on the yield polyhedron
//! ([`crate::yield_surface::Polyhedron`]); the rows of `A` are in
//! [`crate::kind`]. `ReadOptions { reduce_space: false }` assembles every
//! space scene so (the check of the reduction).

use crate::kind::Model;

/// How a space scene was reduced: the model it is solved as, and the axes.
#[derive(Clone, Debug, PartialEq)]
pub struct Reduction {
    /// The model the scene is solved as.
    pub kind: Model,
    /// The axes `e1, e2, e3` (rows) in global coordinates: the plane is
    /// spanned by `e1, e2`, `e3` is its normal.
    pub axes: [[f64; 3]; 3],
    /// True if the axes are the global ones (the plane is `z = const`).
    pub global_axes: bool,
    /// Why: which loads decided the model.
    pub reason: String,
}

/// Relative tolerance of the plane and the load classification.
pub const PLANE_TOLERANCE: f64 = 1e-12;

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}

impl Reduction {
    /// Components of a global vector in the axes `e1, e2, e3` (exactly the
    /// vector when the axes are the global ones).
    pub fn to_local(&self, v: [f64; 3]) -> [f64; 3] {
        if self.global_axes {
            v
        } else {
            [
                dot(self.axes[0], v),
                dot(self.axes[1], v),
                dot(self.axes[2], v),
            ]
        }
    }

    /// One line for the report: what the space scene was solved as, and why.
    pub fn summary(&self) -> String {
        let (dropped, kept) = match self.kind {
            Model::Space => {
                return format!(
                    "space scene solved as the general space model ({}): six components per node in the global axes, each section on the inscribed yield polyhedron",
                    self.reason
                )
            }
            Model::Planar => (
                "the out-of-plane translation, the rotations about in-plane axes, the torques and the bending moments about in-plane axes",
                "translations along e1, e2 reported as x, y, the rotation about e3 as rz",
            ),
            Model::Grillage => (
                "the in-plane translations, the rotation about the normal, the axial forces and the bending moments about the normal",
                "the translation along e3 reported as z, the rotations about e1, e2 as rx, ry",
            ),
        };
        let axes = if self.global_axes {
            "the global axes (e1 = x, e2 = y, e3 = z)".to_string()
        } else {
            let f = |v: [f64; 3]| format!("({:.6}, {:.6}, {:.6})", v[0], v[1], v[2]);
            format!(
                "e1 = {}, e2 = {}, e3 = {}",
                f(self.axes[0]),
                f(self.axes[1]),
                f(self.axes[2])
            )
        };
        format!(
            "space scene solved as {} ({}): left out {} (zero: no load drives them and the planar section's yield set is the cross-section of the pipe's); axes {}; {}",
            self.kind.as_str(),
            self.reason,
            dropped,
            axes,
            kept
        )
    }
}

/// A load of a space scene: force and moment in global axes.
pub(crate) type SpaceLoad = ([f64; 3], [f64; 3]);

/// The plane of the nodes and the model of the loads; `Err` says why the
/// scene needs the general space model.
pub(crate) fn reduce(points: &[[f64; 3]], loads: &[SpaceLoad]) -> Result<Reduction, String> {
    let fscale = loads.iter().fold(0.0f64, |s, l| s.max(norm(l.0)));
    let mscale = loads.iter().fold(0.0f64, |s, l| s.max(norm(l.1)));
    let p0 = points[0];
    let (mut far, mut extent) = (p0, 0.0f64);
    for &p in points {
        let d = norm(sub(p, p0));
        if d > extent {
            (far, extent) = (p, d);
        }
    }
    if extent == 0.0 {
        return Err("all nodes coincide".into());
    }
    let t = unit(sub(far, p0));
    let (mut best, mut off) = (None, 0.0f64);
    for &p in points {
        let c = cross(sub(far, p0), sub(p, p0));
        let d = norm(c);
        if d > off {
            (best, off) = (Some(c), d);
        }
    }
    let tol = PLANE_TOLERANCE * extent;
    let candidates: Vec<[f64; 3]> = if off > tol * extent {
        let n = best.expect("a point off the line");
        vec![unit(n)]
    } else {
        // a straight scene: the plane of the line and the first force across
        // it (planar), the plane normal to that force (grillage), the normal
        // along the first moment across the line, z, any
        let mut c = Vec::new();
        let across = |v: [f64; 3]| {
            let a = dot(v, t);
            sub(v, [a * t[0], a * t[1], a * t[2]])
        };
        if let Some(fp) = loads
            .iter()
            .map(|l| across(l.0))
            .find(|fp| norm(*fp) > PLANE_TOLERANCE * fscale)
        {
            c.push(unit(cross(t, fp)));
            c.push(unit(fp));
        }
        if let Some(mp) = loads
            .iter()
            .map(|l| across(l.1))
            .find(|mp| norm(*mp) > PLANE_TOLERANCE * mscale)
        {
            c.push(unit(mp));
        }
        if t[2] == 0.0 {
            c.push([0.0, 0.0, 1.0]);
        }
        let other = if t[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        c.push(unit(cross(t, other)));
        c
    };
    let mut last = String::new();
    for n in candidates {
        if let Some((i, d)) = points
            .iter()
            .map(|&p| dot(n, sub(p, p0)).abs())
            .enumerate()
            .find(|&(_, d)| d > tol)
        {
            last = format!(
                "the nodes are not in one plane: node {} is {d:e} off the plane of the others",
                i + 1
            );
            continue;
        }
        let r = axes(n);
        let mut inplane = false;
        let mut normal = false;
        for l in loads {
            let (f, m) = (r.to_local(l.0), r.to_local(l.1));
            let fz = |v: f64| v.abs() > PLANE_TOLERANCE * fscale;
            let mz = |v: f64| v.abs() > PLANE_TOLERANCE * mscale;
            inplane |= fz(f[0]) || fz(f[1]) || mz(m[2]);
            normal |= fz(f[2]) || mz(m[0]) || mz(m[1]);
        }
        let (kind, reason) = match (inplane, normal) {
            (_, false) => (
                Model::Planar,
                "the nodes lie in one plane and every load acts in it",
            ),
            (false, true) => (
                Model::Grillage,
                "the nodes lie in one plane and every load acts normal to it",
            ),
            (true, true) => {
                last = "the loads act both in the plane of the nodes and normal to it".into();
                continue;
            }
        };
        return Ok(Reduction {
            kind,
            reason: reason.into(),
            ..r
        });
    }
    general(points, &last)
}

/// The general space model (no reduction): global axes, `reason` says why.
pub(crate) fn general(points: &[[f64; 3]], reason: &str) -> Result<Reduction, String> {
    if points.iter().all(|p| *p == points[0]) {
        return Err("all nodes coincide".into());
    }
    Ok(Reduction {
        kind: Model::Space,
        axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        global_axes: true,
        reason: reason.into(),
    })
}

/// The in-plane axes `(u, v)` of an arc in the plane with normal `n`
/// (unit): `u` the plane's direction nearest global `x` (`y` when `n` is
/// within about 25 degrees of `x`), `v = n x u`; exactly `x, y` when `n` is
/// `+z`, so an arc of the x-y plane has the planar arc's points bit for bit.
/// Angles run counter-clockwise about `n` from `u`.
/// With `reference` (an arc's `reference` key) `u` is its part in the plane
/// instead; `None` when that part is zero.
pub(crate) fn arc_axes(n: [f64; 3], reference: Option<[f64; 3]>) -> Option<([f64; 3], [f64; 3])> {
    let g = match reference {
        Some(g) => g,
        None if n[0] == 0.0 && n[1] == 0.0 && n[2] > 0.0 => {
            return Some(([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]))
        }
        None if n[0].abs() < 0.9 => [1.0, 0.0, 0.0],
        None => [0.0, 1.0, 0.0],
    };
    let gn = dot(g, n);
    let w = sub(g, [gn * n[0], gn * n[1], gn * n[2]]);
    let across = norm(w) > 1e-6 * norm(g);
    if !across {
        return None;
    }
    let u = unit(w);
    Some((u, cross(n, u)))
}

/// The point of an arc (centre `c`, radius `r`, in-plane axes `u, v`) at
/// `angle` degrees.
pub(crate) fn arc_point(c: [f64; 3], r: f64, (u, v): ([f64; 3], [f64; 3]), angle: f64) -> [f64; 3] {
    let (s, co) = angle.to_radians().sin_cos();
    [
        c[0] + r * (co * u[0] + s * v[0]),
        c[1] + r * (co * u[1] + s * v[1]),
        c[2] + r * (co * u[2] + s * v[2]),
    ]
}

/// The unit vector along `v`, if `v` is finite and not zero.
pub(crate) fn unit_of(v: &[f64]) -> Option<[f64; 3]> {
    if v.len() != 3 || v.iter().any(|x| !x.is_finite() || x.abs() > 1e100) {
        return None;
    }
    let w = [v[0], v[1], v[2]];
    let n = norm(w);
    (n > 0.0).then(|| unit(w))
}

/// The axes `[e1, e2, e3]` of an element of a general space frame with unit
/// direction `e1`: `e3` is the part of the orientation vector `v` normal to
/// `e1`, `e2 = e3 x e1`. Without an `orientation` key `v` is global `z`
/// (`x` for an element within `1e-6` rad of vertical), so an element of the
/// x-y plane has the planar element's axes: `e2` the direction turned 90
/// degrees counter-clockwise, `e3 = z`. The pipe's bending is isotropic, so
/// the choice matters only through the polyhedron's longitudes (the pure
/// bending about `e2` and `e3` is exact); `Err` when `v` is along `e1`.
pub fn element_axes(e1: [f64; 3], v: Option<[f64; 3]>) -> Result<[[f64; 3]; 3], String> {
    let v = match v {
        Some(v) => v,
        None if e1[0].hypot(e1[1]) < 1e-6 => [1.0, 0.0, 0.0],
        None => [0.0, 0.0, 1.0],
    };
    let along = dot(v, e1);
    let n = sub(v, [along * e1[0], along * e1[1], along * e1[2]]);
    let (nv, nn) = (norm(v), norm(n));
    let ok = nv > 0.0 && nn > 1e-6 * nv;
    if !ok {
        return Err(format!(
            "the orientation vector {v:?} is zero or along the member: give a direction across it (the element's local e3)"
        ));
    }
    // the planar element's exact axes when e1 lies in the x-y plane and v = z
    let (e2, e3) = if e1[2] == 0.0 && v[0] == 0.0 && v[1] == 0.0 && v[2] > 0.0 {
        ([-e1[1], e1[0], 0.0], [0.0, 0.0, 1.0])
    } else {
        let e3 = unit(n);
        (cross(e3, e1), e3)
    };
    Ok([e1, e2, e3])
}

/// The axes of the plane with normal `n`.
fn axes(n: [f64; 3]) -> Reduction {
    let global = n[0] == 0.0 && n[1] == 0.0;
    let axes = if global {
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    } else {
        let k = (0..3)
            .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
            .unwrap_or(2);
        let e3 = if n[k] < 0.0 { [-n[0], -n[1], -n[2]] } else { n };
        let g = if e3[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let gn = dot(g, e3);
        let e1 = unit(sub(g, [gn * e3[0], gn * e3[1], gn * e3[2]]));
        let e2 = cross(e3, e1);
        [e1, e2, e3]
    };
    Reduction {
        kind: Model::Planar,
        axes,
        global_axes: global,
        reason: String::new(),
    }
}

/// The fixed components of the reduced model from the six global ones
/// (`[x, y, z, rx, ry, rz]`), by [`crate::kind::Component::index`]; `Err`
/// when a support fixes directions skew to the plane's axes.
pub(crate) fn local_fixed(r: &Reduction, fixed: [bool; 6]) -> Result<[bool; 6], String> {
    let mut local = [false; 6];
    for (part, base) in [("translations", 0), ("rotations", 3)] {
        let mut count = 0;
        for i in 0..3 {
            // e_i lies in the span of the fixed global axes
            let e = r.axes[i];
            let inside = (0..3).all(|g| fixed[base + g] || e[g].abs() <= PLANE_TOLERANCE);
            local[base + i] = inside;
            count += usize::from(inside);
        }
        let given = (0..3).filter(|&g| fixed[base + g]).count();
        if count != given {
            return Err(format!(
                "the fixed {part} are skew to the axes of the frame's plane (fix all three, or only those along the plane's axes)"
            ));
        }
    }
    // slots x, y, rz, z, rx, ry
    let slots = [local[0], local[1], local[5], local[2], local[3], local[4]];
    Ok(match r.kind {
        Model::Planar => [slots[0], slots[1], slots[2], false, false, false],
        Model::Grillage => [false, false, false, slots[3], slots[4], slots[5]],
        Model::Space => slots,
    })
}

/// A load in the model's components, by [`crate::kind::Component::index`].
pub(crate) fn local_load(r: &Reduction, l: SpaceLoad) -> [f64; 6] {
    let (f, m) = (r.to_local(l.0), r.to_local(l.1));
    match r.kind {
        Model::Planar => [f[0], f[1], m[2], 0.0, 0.0, 0.0],
        Model::Grillage => [0.0, 0.0, 0.0, f[2], m[0], m[1]],
        Model::Space => [f[0], f[1], m[2], f[2], m[0], m[1]],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vertical_plane_is_found_with_its_axes() {
        let pts = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 2.0]];
        let r = reduce(&pts, &[([0.0, 0.0, -1.0], [0.0; 3])]).unwrap();
        assert_eq!(r.kind, Model::Planar);
        assert!(!r.global_axes);
        assert_eq!(r.axes[2], [0.0, 1.0, 0.0]);
        let r = reduce(&pts, &[([0.0, 1.0, 0.0], [0.0; 3])]).unwrap();
        assert_eq!(r.kind, Model::Grillage);
        let r = reduce(&pts, &[([0.0, 1.0, 1.0], [0.0; 3])]).unwrap();
        assert_eq!(r.kind, Model::Space);
        assert!(r.reason.contains("both in the plane"), "{}", r.reason);
        let r = reduce(
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [1.0, 1.0, 1.0],
            ],
            &[([0.0, 1.0, 0.0], [0.0; 3])],
        )
        .unwrap();
        assert_eq!(r.kind, Model::Space);
        assert!(r.reason.contains("not in one plane"), "{}", r.reason);
    }

    #[test]
    fn skew_supports_are_refused() {
        let pts = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 1.0, 2.0]];
        let r = reduce(&pts, &[([0.0, 0.0, -1.0], [0.0; 3])]).unwrap();
        assert!(local_fixed(&r, [true, false, false, false, false, false]).is_err());
        assert_eq!(
            local_fixed(&r, [true, true, true, true, true, true]).unwrap(),
            [true, true, true, false, false, false]
        );
        // z is e2 of this plane
        assert_eq!(
            local_fixed(&r, [false, false, true, false, false, false]).unwrap(),
            [false, true, false, false, false, false]
        );
    }
}
