//! Yield surfaces of a critical section: the matrix `N` of system (9) for a
//! section whose yield condition couples the bending moment `M` with a second
//! force `F` of its element (the torque `T` of a grillage member, or the axial
//! force of a planar member that asks for the interaction).
//!
//! In the normalised plane `(m, f) = (M / Mp, F / Fp)` the smooth interaction
//! curve is replaced by a convex polygon of `k` facets (`k` a multiple of 4:
//! 4, 8, 16, 32, ...). Each facet is one yield mode:
//!
//! ```text
//! y*_i = Mp (c_i - n_i . (M / Mp, F / Fp)) >= 0,    n_i unit normal, c_i > 0 its offset
//! ```
//!
//! so the column of `N` of facet `i` is `(n_i,m, n_i,f Mp / Fp)` over the
//! section's `(M, F)`, and its capacity `X*_i = c_i Mp` (moment units, like the
//! bending-only modes `+-M <= Mp`).
//!
//! **The polygon is inscribed, always.** Its vertices lie on the curve at equal
//! steps of the curve's parameter in each quadrant, and the four points
//! `(+-1, 0)`, `(0, +-1)` are vertices. So the polygon is a safe (inner)
//! approximation: collapse loads computed with it are lower bounds of those of
//! the smooth curve, rising to them as `k` doubles; pure bending (`F = 0`) and
//! pure `F` are capacities of the curve exactly, so a member that carries no
//! torque (or no axial force) behaves exactly as a bending-only member. The
//! polygon is symmetric about both axes.
//!
//! The curves:
//!
//! - [`Curve::BendingTorsion`]: a thin-walled pipe in bending and torsion,
//!   `m^2 + f^2 <= 1` (vertices at the angles `2 pi i / k`, facet offsets
//!   `cos(pi / k)`);
//! - [`Curve::BendingAxial`]: a thin-walled pipe in bending and axial force,
//!   `|m| <= cos(pi f / 2)`.
//!
//! ```
//! use frames::yield_surface::{Curve, Polygon};
//! let p = Polygon::new(Curve::BendingTorsion, 8).unwrap();
//! assert_eq!(p.facets().len(), 8);
//! // inscribed: the radius along 22.5 degrees is cos(pi / 8) < 1, along 45 degrees it is 1
//! let r = |deg: f64| p.radius(deg.to_radians());
//! assert!((r(22.5) - (std::f64::consts::PI / 8.0).cos()).abs() < 1e-15);
//! assert!((r(45.0) - 1.0).abs() < 1e-15);
//! assert!(Polygon::new(Curve::BendingTorsion, 6).is_err());
//! ```

use std::f64::consts::PI;

/// The smooth interaction curve a polygon approximates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Curve {
    /// `(M/Mp)^2 + (T/Tp)^2 <= 1` (thin-walled pipe, bending and torsion).
    BendingTorsion,
    /// `|M/Mp| <= cos(pi N / (2 Np))` (thin-walled pipe, bending and axial force).
    BendingAxial,
}

impl Curve {
    /// The point of the curve in the first quadrant at parameter `t` in `[0, 1]`,
    /// from `(1, 0)` at `t = 0` to `(0, 1)` at `t = 1`.
    fn point(self, t: f64) -> [f64; 2] {
        match self {
            Curve::BendingTorsion => {
                let a = 0.5 * PI * t;
                [a.cos(), a.sin()]
            }
            Curve::BendingAxial => [(0.5 * PI * t).cos(), t],
        }
    }

    /// A short description, e.g. `(M/Mp)^2 + (T/Tp)^2 <= 1`.
    pub fn describe(self) -> &'static str {
        match self {
            Curve::BendingTorsion => "(M/Mp)^2 + (T/Tp)^2 <= 1",
            Curve::BendingAxial => "|M/Mp| <= cos(pi N / (2 Np))",
        }
    }

    /// The name of the second force: `"T"` or `"N"`.
    pub fn second(self) -> &'static str {
        match self {
            Curve::BendingTorsion => "T",
            Curve::BendingAxial => "N",
        }
    }
}

/// One facet: `n . (m, f) <= offset` in the normalised plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Facet {
    /// Unit normal `(n_m, n_f)`.
    pub normal: [f64; 2],
    /// Offset `c > 0` (distance of the facet from the origin).
    pub offset: f64,
}

impl Facet {
    /// The angle of the normal in degrees, in `[0, 360)`.
    pub fn angle_degrees(&self) -> f64 {
        let a = self.normal[1].atan2(self.normal[0]).to_degrees();
        if a < 0.0 {
            a + 360.0
        } else {
            a
        }
    }
}

/// An inscribed polygon of `k` facets approximating a [`Curve`].
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    curve: Curve,
    facets: Vec<Facet>,
}

impl Polygon {
    /// The polygon of `k` facets; `k` must be a multiple of 4, from 4 to 256
    /// (every facet is a complementary variable of the PLCP, held densely).
    pub fn new(curve: Curve, k: usize) -> Result<Polygon, String> {
        if !(4..=256).contains(&k) || k & 3 != 0 {
            return Err(format!(
                "the number of facets must be a multiple of 4 from 4 to 256 (4, 8, 16, 32, ...), got {k}"
            ));
        }
        let q = k / 4;
        // vertices counter-clockwise, starting at (1, 0)
        let mut first: Vec<[f64; 2]> = (0..=q).map(|i| curve.point(i as f64 / q as f64)).collect();
        // exact axis points (cos(pi/2) is not exactly 0)
        first[0] = [1.0, 0.0];
        first[q] = [0.0, 1.0];
        let mut vertices: Vec<[f64; 2]> = first.clone();
        vertices.extend(first.iter().rev().skip(1).map(|v| [-v[0], v[1]]));
        let lower: Vec<[f64; 2]> = vertices[1..vertices.len() - 1]
            .iter()
            .rev()
            .map(|v| [v[0], -v[1]])
            .collect();
        vertices.extend(lower);
        debug_assert_eq!(vertices.len(), k);
        let facets = (0..k)
            .map(|i| {
                let (a, b) = (vertices[i], vertices[(i + 1) % k]);
                // outward normal of the edge a -> b (counter-clockwise polygon)
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let len = dx.hypot(dy);
                let normal = [dy / len, -dx / len];
                let offset = 0.5 * (normal[0] * (a[0] + b[0]) + normal[1] * (a[1] + b[1]));
                Facet { normal, offset }
            })
            .collect();
        Ok(Polygon { curve, facets })
    }

    /// The curve approximated.
    pub fn curve(&self) -> Curve {
        self.curve
    }

    /// The facets, counter-clockwise from the one next to `(1, 0)` in the first quadrant.
    pub fn facets(&self) -> &[Facet] {
        &self.facets
    }

    /// The distance from the origin to the boundary along the direction `angle`
    /// (radians) in the normalised plane.
    pub fn radius(&self, angle: f64) -> f64 {
        let (c, s) = (angle.cos(), angle.sin());
        self.facets
            .iter()
            .filter_map(|f| {
                let p = f.normal[0] * c + f.normal[1] * s;
                (p > 0.0).then(|| f.offset / p)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The largest `s` with `s (m, f)` inside the polygon (the load factor of a
    /// section whose normalised forces are `(m, f)` per unit load).
    pub fn load_factor(&self, m: f64, f: f64) -> f64 {
        self.facets
            .iter()
            .filter_map(|fa| {
                let p = fa.normal[0] * m + fa.normal[1] * f;
                (p > 0.0).then(|| fa.offset / p)
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// One facet of a [`Polyhedron`]: `n . (m2, m3, t) <= offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Facet3 {
    /// Unit outward normal `(n_m2, n_m3, n_t)`.
    pub normal: [f64; 3],
    /// Offset `c > 0` (distance of the facet's plane from the origin).
    pub offset: f64,
}

/// An inscribed polyhedron of the pipe's bending-torsion surface
/// `m2^2 + m3^2 + t^2 <= 1` (`m2 = M2/Mp`, `m3 = M3/Mp`, `t = T/Tp`), for the
/// general space model (not assembled yet: see `docs/space-frames.md`).
///
/// **How the facets are built.** A latitude-longitude grid with the polar
/// axis along `t` (the bending is isotropic, so rotating `(m2, m3)` by a
/// multiple of `2 pi / k` maps the grid to itself): `k` longitudes at the
/// angles `2 pi i / k` from the `m2` axis, `k` a multiple of 4 (the `m2` and
/// `m3` axes are meridians), and the latitudes `2 pi j / k`, `|j| < k / 4`,
/// of the polygon of `k` facets (the equator among them), with the two poles.
/// Every vertex is on the sphere. The facets are the quadrilaterals between
/// neighbouring latitudes and longitudes (isosceles trapezoids: planar) and
/// the triangles at the poles: `k (k/2 - 2) + 2 k = k^2 / 2` facets. The
/// meridians through the `m2` and `m3` axes are rings of edges, so the
/// cross-sections `m2 = 0` and `m3 = 0` are exactly the [`Polygon`] of `k`
/// facets of [`Curve::BendingTorsion`], and pure bending about any axis at a
/// longitude (and pure torsion) is a capacity exactly.
///
/// **Size.** Each facet is one yield mode of a section: `k^2 / 2` per section
/// against `k` for the grillage polygon, so `p = e k^2` modes for `e`
/// elements (`k = 16`: 128 per section), while the free block (coordinates
/// and member forces) does not depend on `k`. A pivot costs about the PLCP's
/// dimension, so the time of a path grows with `k^2` per pivot times the
/// number of facets a flowing section's stress crosses (growing with `k`).
#[derive(Clone, Debug, PartialEq)]
pub struct Polyhedron {
    facets: Vec<Facet3>,
    planarity: f64,
}

impl Polyhedron {
    /// The polyhedron of `k` longitudes (`k` a multiple of 4 from 4 to 256).
    pub fn new(k: usize) -> Result<Polyhedron, String> {
        // the same rule as the polygons
        Polygon::new(Curve::BendingTorsion, k)?;
        let q = k / 4;
        let lat = |j: isize| -> (f64, f64) {
            // exact at the equator and the poles
            match j {
                0 => (1.0, 0.0),
                j if j == q as isize => (0.0, 1.0),
                j if j == -(q as isize) => (0.0, -1.0),
                j => {
                    let a = 2.0 * PI * j as f64 / k as f64;
                    (a.cos(), a.sin())
                }
            }
        };
        let lon = |i: usize| -> (f64, f64) {
            let i = i % k;
            let off_axis = i % q;
            if off_axis == 0 {
                // exact on the axes
                [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][i / q]
            } else {
                let a = 2.0 * PI * i as f64 / k as f64;
                (a.cos(), a.sin())
            }
        };
        let vertex = |i: usize, j: isize| -> [f64; 3] {
            let (cl, sl) = lat(j);
            let (co, so) = lon(i);
            [cl * co, cl * so, sl]
        };
        let mut facets = Vec::with_capacity(k * k / 2);
        let mut planarity = 0.0f64;
        let mut push = |pts: &[[f64; 3]]| {
            // outward normal from the first three points, averaged offset
            let (a, b, c) = (pts[0], pts[1], pts[2]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let mut n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            n = n.map(|x| x / len);
            let centre: [f64; 3] = [0, 1, 2].map(|d| pts.iter().map(|p| p[d]).sum::<f64>());
            if n[0] * centre[0] + n[1] * centre[1] + n[2] * centre[2] < 0.0 {
                n = n.map(|x| -x);
            }
            let offset = pts
                .iter()
                .map(|p| n[0] * p[0] + n[1] * p[1] + n[2] * p[2])
                .sum::<f64>()
                / pts.len() as f64;
            // planar: every vertex on the facet's plane (to rounding)
            for p in pts {
                let off = (n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - offset).abs();
                planarity = planarity.max(off);
            }
            facets.push(Facet3 { normal: n, offset });
        };
        let q = q as isize;
        for i in 0..k {
            for j in -q..q {
                let (a, b) = (vertex(i, j), vertex(i + 1, j));
                let (c, d) = (vertex(i + 1, j + 1), vertex(i, j + 1));
                if j == -q {
                    push(&[a, c, d]); // south cap: a = b is the pole
                } else if j + 1 == q {
                    push(&[a, b, c]); // north cap: c = d is the pole
                } else {
                    push(&[a, b, c, d]);
                }
            }
        }
        Ok(Polyhedron { facets, planarity })
    }

    /// The largest distance of a vertex from its facet's plane (rounding
    /// only: the quadrilaterals are isosceles trapezoids).
    pub fn planarity(&self) -> f64 {
        self.planarity
    }

    /// The facets.
    pub fn facets(&self) -> &[Facet3] {
        &self.facets
    }

    /// The largest `s` with `s u` inside the polyhedron (the load factor of a
    /// section whose normalised forces are `u = (m2, m3, t)` per unit load);
    /// the smooth surface's is `1 / |u|`, a bound from above.
    pub fn load_factor(&self, u: [f64; 3]) -> f64 {
        self.facets
            .iter()
            .filter_map(|f| {
                let p = f.normal[0] * u[0] + f.normal[1] * u[1] + f.normal[2] * u[2];
                (p > 0.0).then(|| f.offset / p)
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// One facet of a [`Polytope`]: `n . (m2, m3, t, n) <= offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Facet4 {
    /// Unit outward normal `(n_m2, n_m3, n_t, n_n)`.
    pub normal: [f64; 4],
    /// Offset `c > 0` (distance of the facet's hyperplane from the origin).
    pub offset: f64,
}

/// The pipe's yield condition with bending, torsion and axial force,
/// `m <= g(t, n)` with `m = |(m2, m3)|` (`m2 = M2/Mp`, `m3 = M3/Mp`,
/// `t = T/Tp`, `n = N/Np`) and
///
/// ```text
/// g(t, n) = s cos(pi n / (2 s)),   s = sqrt(1 - t^2),   |n| <= s
/// ```
///
/// (a thin-walled pipe whose torque is carried by a uniform shear: by von
/// Mises the axial stress left is `s sigma_y`, and the bending-axial curve
/// of the planar model `|m| <= cos(pi n / 2)` is scaled by it). At `n = 0`
/// it is the sphere of [`Polyhedron`], at `t = 0` the [`Curve::BendingAxial`]
/// curve; the set is convex (the image of a convex set of wall stresses).
pub fn pipe_surface(t: f64, n: f64) -> f64 {
    let s = (1.0 - t * t).max(0.0).sqrt();
    if n.abs() >= s {
        0.0
    } else {
        s * (0.5 * PI * n / s).cos()
    }
}

/// An inscribed polytope of [`pipe_surface`] in `(m2, m3, t, n)`, for the
/// general space model with `plastic_axial`.
///
/// **How the facets are built** (a product: the bending is isotropic). The
/// vertices are `(r cos phi_i, r sin phi_i, t, n)` with `phi_i = 2 pi i / k`
/// the `k` longitudes of [`Polyhedron`] and `(t, n, r = g(t, n))` the nodes of
/// a grid on the disk `t^2 + n^2 <= 1`: rows at the latitudes
/// `t_j = sin(2 pi j / k)`, `|j| <= k / 4`, and on row `j` the columns
/// `n = s_j u_i`, `u_i = 4 i / k`, `|i| <= k / 4` (`s_j = cos(2 pi j / k)`),
/// so `r = s_j cos(pi u_i / 2)`: every vertex on the surface, `r = 0` on
/// the disk's rim. Their convex hull is `gauge_K(m2, m3) <= rho(t, n)` with
/// `K` the longitudes' `k`-gon and `rho` the concave piecewise-linear upper
/// hull of the lifted grid `(t, n, r)`: each grid cell is split into two
/// triangles along the diagonal that keeps the lifted surface concave (at
/// the poles, one triangle), and every facet is a pair (edge of `K`,
/// triangle): `nu . (m2, m3) / cos(pi / k) <= alpha + beta t + gamma n`,
/// normalised. [`Polytope::new`] checks that every lifted node is on or
/// below every triangle's plane (the hull is exact) and refuses otherwise.
///
/// Row `j = 0` (`t = 0`) holds the vertices of the [`Curve::BendingAxial`]
/// polygon of `k` facets and column `i = 0` (`n = 0`) the latitudes of
/// [`Polyhedron`], so the cross-sections `m2 = t = 0` and `n = 0` are exactly
/// the planar model's polygon and the bending-torsion polyhedron of the same
/// `k`.
///
/// **Size.** `k` edges times `8 q^2 - 4 q` triangles (`q = k / 4`):
/// `k = 4`: 16 facets per section, 8: 192, 16: 1792, 32: 15360 (about
/// `k^3 / 2`, against `k^2 / 2` without the axial force).
#[derive(Clone, Debug, PartialEq)]
pub struct Polytope {
    facets: Vec<Facet4>,
    triangles: usize,
}

impl Polytope {
    /// The polytope of `k` longitudes (`k` a multiple of 4 from 4 to 64:
    /// 15360 facets per section at 32, 126 976 at 64).
    pub fn new(k: usize) -> Result<Polytope, String> {
        Polygon::new(Curve::BendingTorsion, k)?;
        if k > 64 {
            return Err(format!(
                "the bending-torsion-axial polytope takes at most 64 longitudes (k^3 / 2 facets per section), got {k}"
            ));
        }
        let q = (k / 4) as isize;
        let exact_trig = |j: isize| -> (f64, f64) {
            // (cos, sin) of 2 pi j / k, exact at the axes
            match j {
                0 => (1.0, 0.0),
                j if j == q => (0.0, 1.0),
                j if j == -q => (0.0, -1.0),
                j => {
                    let a = 2.0 * PI * j as f64 / k as f64;
                    (a.cos(), a.sin())
                }
            }
        };
        // the lifted grid: node (i, j) -> (t, n, r)
        let node = |i: isize, j: isize| -> [f64; 3] {
            let (s, t) = exact_trig(j);
            let u = i as f64 / q as f64;
            let r = match i {
                0 => s,
                i if i.abs() == q => 0.0,
                _ => s * (0.5 * PI * u).cos(),
            };
            [t, s * u, r]
        };
        // the concave interpolant's triangles: (alpha, beta, gamma) with r = alpha + beta t + gamma n
        let plane = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| -> [f64; 3] {
            let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
            let det = u[0] * v[1] - u[1] * v[0];
            let (ru, rv) = (b[2] - a[2], c[2] - a[2]);
            let beta = (ru * v[1] - rv * u[1]) / det;
            let gamma = (u[0] * rv - v[0] * ru) / det;
            [a[2] - beta * a[0] - gamma * a[1], beta, gamma]
        };
        let at = |p: [f64; 3], x: [f64; 3]| p[0] + p[1] * x[0] + p[2] * x[1];
        let mut planes: Vec<[f64; 3]> = Vec::new();
        for j in -q..q {
            for i in -q..q {
                let (a, b) = (node(i, j), node(i + 1, j));
                let (c, d) = (node(i + 1, j + 1), node(i, j + 1));
                if j == -q {
                    planes.push(plane(a, c, d)); // a = b: the south pole
                } else if j + 1 == q {
                    planes.push(plane(a, b, c)); // c = d: the north pole
                } else {
                    // the diagonal a-c if d is below the plane of (a, b, c), else b-d
                    let p = plane(a, b, c);
                    if d[2] <= at(p, d) {
                        planes.push(p);
                        planes.push(plane(a, c, d));
                    } else {
                        planes.push(plane(a, b, d));
                        planes.push(plane(b, c, d));
                    }
                }
            }
        }
        // the hull is exact: no node above a triangle's plane
        for j in -q..=q {
            for i in -q..=q {
                let x = node(i, j);
                for p in &planes {
                    if x[2] > at(*p, x) + 1e-13 {
                        return Err(format!(
                            "the lifted grid of {k} longitudes is not concave at node ({i}, {j})"
                        ));
                    }
                }
            }
        }
        // the longitudes' k-gon: edge normals and offset
        let kgon: Vec<([f64; 2], f64)> = (0..k)
            .map(|i| {
                let (a, b) = (lon_point(i, k), lon_point(i + 1, k));
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let len = dx.hypot(dy);
                let nu = [dy / len, -dx / len];
                let c = 0.5 * (nu[0] * (a[0] + b[0]) + nu[1] * (a[1] + b[1]));
                (nu, c)
            })
            .collect();
        let mut facets = Vec::with_capacity(k * planes.len());
        for (nu, c) in &kgon {
            for p in &planes {
                let raw = [nu[0] / c, nu[1] / c, -p[1], -p[2]];
                let len = raw.iter().map(|x| x * x).sum::<f64>().sqrt();
                facets.push(Facet4 {
                    normal: raw.map(|x| x / len),
                    offset: p[0] / len,
                });
            }
        }
        Ok(Polytope {
            facets,
            triangles: planes.len(),
        })
    }

    /// The facets (edge of the longitudes' polygon major, triangle minor).
    pub fn facets(&self) -> &[Facet4] {
        &self.facets
    }

    /// The triangles of the `(t, n)` grid (facets per edge of the longitudes' polygon).
    pub fn triangles(&self) -> usize {
        self.triangles
    }

    /// The largest `s` with `s u` inside the polytope (the load factor of a
    /// section whose normalised forces are `u = (m2, m3, t, n)` per unit load).
    pub fn load_factor(&self, u: [f64; 4]) -> f64 {
        self.facets
            .iter()
            .filter_map(|f| {
                let p = (0..4).map(|d| f.normal[d] * u[d]).sum::<f64>();
                (p > 0.0).then(|| f.offset / p)
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// The smooth surface's load factor along `u = (m2, m3, t, n)`: the largest
/// `s` with `s |(m2, m3)| <= g(s t, s n)` ([`pipe_surface`]), by bisection
/// to rounding (the set is convex and star-shaped about the origin).
pub fn pipe_load_factor(u: [f64; 4]) -> f64 {
    let m = u[0].hypot(u[1]);
    let inside = |s: f64| {
        let (t, n) = (s * u[2], s * u[3]);
        s * m <= pipe_surface(t, n) && t * t + n * n <= 1.0
    };
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    while inside(hi) {
        hi *= 2.0;
        if hi > 1e300 {
            return f64::INFINITY;
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if inside(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// The point of longitude `i` of `k` on the unit circle, exact on the axes.
fn lon_point(i: usize, k: usize) -> [f64; 2] {
    let i = i % k;
    let q = k / 4;
    if i % q == 0 {
        [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]][i / q]
    } else {
        let a = 2.0 * PI * i as f64 / k as f64;
        [a.cos(), a.sin()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inscribed_and_symmetric() {
        for curve in [Curve::BendingTorsion, Curve::BendingAxial] {
            for k in [4, 8, 16, 32, 64] {
                let p = Polygon::new(curve, k).unwrap();
                // the axis points are capacities exactly
                assert_eq!(p.load_factor(1.0, 0.0), 1.0, "{curve:?} {k}");
                assert!((p.load_factor(0.0, 1.0) - 1.0).abs() < 1e-15);
                assert!((p.load_factor(-1.0, 0.0) - 1.0).abs() < 1e-15);
                // inscribed: every point of the boundary lies inside the curve
                for i in 0..720 {
                    let a = i as f64 * PI / 360.0;
                    let r = p.radius(a);
                    let (m, f) = (r * a.cos(), r * a.sin());
                    let inside = match curve {
                        Curve::BendingTorsion => m * m + f * f <= 1.0 + 1e-12,
                        Curve::BendingAxial => m.abs() <= (0.5 * PI * f.abs()).cos() + 1e-12,
                    };
                    assert!(inside, "{curve:?} k = {k}, angle {a}: ({m}, {f})");
                    // symmetric about both axes
                    assert!((p.radius(-a) - r).abs() < 1e-12);
                    assert!((p.radius(PI - a) - r).abs() < 1e-12);
                }
                for f in p.facets() {
                    assert!((f.normal[0].hypot(f.normal[1]) - 1.0).abs() < 1e-15);
                    assert!(f.offset > 0.0 && f.offset <= 1.0);
                }
            }
        }
    }

    #[test]
    fn circle_offsets_and_convergence() {
        let mut last = 0.0;
        for k in [4, 8, 16, 32, 64, 128] {
            let p = Polygon::new(Curve::BendingTorsion, k).unwrap();
            for f in p.facets() {
                assert!((f.offset - (PI / k as f64).cos()).abs() < 1e-15);
            }
            // the worst radius is cos(pi / k): error 1 - cos(pi/k) ~ pi^2 / (2 k^2)
            let worst = (0..3600)
                .map(|i| p.radius(i as f64 * PI / 1800.0))
                .fold(f64::INFINITY, f64::min);
            assert!((worst - (PI / k as f64).cos()).abs() < 1e-6);
            assert!(worst > last);
            last = worst;
        }
        assert!(Polygon::new(Curve::BendingAxial, 0).is_err());
        assert!(Polygon::new(Curve::BendingAxial, 10).is_err());
    }

    #[test]
    fn polyhedron_is_inscribed_with_planar_facets_and_polygon_sections() {
        for k in [4, 8, 16, 32] {
            let p = Polyhedron::new(k).unwrap();
            assert_eq!(p.facets().len(), k * k / 2, "k = {k}");
            assert!(p.planarity() < 1e-15, "k = {k}: {}", p.planarity());
            // pure bending about the grid's axes, and pure torsion: capacities exactly
            for u in [
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.0, -1.0, 0.0],
            ] {
                assert!((p.load_factor(u) - 1.0).abs() < 1e-14, "k = {k}: {u:?}");
            }
            // the cross-section m2 = 0 is the polygon of k facets
            let poly = Polygon::new(Curve::BendingTorsion, k).unwrap();
            for a in 0..97 {
                let t = a as f64 * 0.0654;
                let (m, f) = (t.cos(), t.sin());
                let want = poly.load_factor(m, f);
                for u in [[0.0, m, f], [m, 0.0, f]] {
                    let got = p.load_factor(u);
                    assert!(
                        (got - want).abs() < 1e-12 * want,
                        "k = {k}, {u:?}: {got} vs {want}"
                    );
                }
            }
            // inscribed: never outside the sphere, and the gap closes as k doubles
            let mut worst = 0.0f64;
            for a in 0..40 {
                let (th, ph) = (a as f64 * 0.7137, (a as f64 * 0.3911).sin() * 1.5);
                let u = [ph.cos() * th.cos(), ph.cos() * th.sin(), ph.sin()];
                let s = p.load_factor(u);
                assert!(s <= 1.0 + 1e-14, "k = {k}: outside the sphere along {u:?}");
                worst = worst.max(1.0 - s);
            }
            // the facets' farthest point from the sphere: at most 1 - cos(2 pi / k)
            assert!(
                worst <= 1.0 - (2.0 * PI / k as f64).cos(),
                "k = {k}: {worst}"
            );
        }
    }

    #[test]
    fn polytope_is_inscribed_with_exact_cross_sections() {
        let mut last = 0.0f64;
        for k in [4, 8, 16, 32] {
            let p = Polytope::new(k).unwrap();
            let q = k / 4;
            assert_eq!(p.triangles(), 8 * q * q - 4 * q, "k = {k}");
            assert_eq!(p.facets().len(), k * p.triangles());
            for f in p.facets() {
                let len = f.normal.iter().map(|x| x * x).sum::<f64>().sqrt();
                assert!((len - 1.0).abs() < 1e-15 && f.offset > 0.0);
            }
            // the cross-section n = 0 is the bending-torsion polyhedron of k,
            // m2 = t = 0 the bending-axial polygon of k (the planar model's)
            let sphere = Polyhedron::new(k).unwrap();
            let axial = Polygon::new(Curve::BendingAxial, k).unwrap();
            for a in 0..61 {
                let (th, ph) = (a as f64 * 0.7137, (a as f64 * 0.3911).sin() * 1.5);
                let u = [ph.cos() * th.cos(), ph.cos() * th.sin(), ph.sin()];
                let (got, want) = (
                    p.load_factor([u[0], u[1], u[2], 0.0]),
                    sphere.load_factor(u),
                );
                assert!(
                    (got - want).abs() < 1e-12 * want,
                    "k = {k}, {u:?}: {got} vs {want}"
                );
                let (m, n) = (th.cos(), th.sin());
                let (got, want) = (p.load_factor([0.0, m, 0.0, n]), axial.load_factor(m, n));
                assert!(
                    (got - want).abs() < 1e-12 * want,
                    "k = {k}, ({m}, {n}): {got} vs {want}"
                );
            }
            // inscribed: never outside the smooth surface; the gap closes with k
            let mut worst = 0.0f64;
            for a in 0..200 {
                let x = a as f64;
                let u = [
                    (x * 0.37).sin(),
                    (x * 0.91).cos(),
                    (x * 0.53).sin() * 0.8,
                    (x * 1.31).cos() * 0.9,
                ];
                let (s, smooth) = (p.load_factor(u), pipe_load_factor(u));
                assert!(s <= smooth * (1.0 + 1e-12), "k = {k}: outside along {u:?}");
                worst = worst.max(1.0 - s / smooth);
            }
            assert!(last == 0.0 || worst < last, "k = {k}: {worst} vs {last}");
            last = worst;
        }
        assert!(last < 2e-2, "{last}");
        assert!(Polytope::new(128).is_err() && Polytope::new(6).is_err());
    }

    #[test]
    fn pipe_surface_sections() {
        // n = 0: the sphere; t = 0: the planar curve; zero on the rim
        for a in 0..50 {
            let x = a as f64 / 50.0;
            assert!((pipe_surface(x, 0.0) - (1.0 - x * x).sqrt()).abs() < 1e-15);
            assert!((pipe_surface(0.0, x) - (0.5 * PI * x).cos()).abs() < 1e-15);
            let (c, s) = (x.cos(), x.sin());
            assert!(pipe_surface(c, s).abs() < 1e-12);
        }
        let s = pipe_load_factor([0.0, 1.0, 0.0, 0.0]);
        assert!((s - 1.0).abs() < 1e-15, "{s}");
        let s = pipe_load_factor([0.0, 0.0, 0.0, 2.0]);
        assert!((s - 0.5).abs() < 1e-15, "{s}");
    }
}
