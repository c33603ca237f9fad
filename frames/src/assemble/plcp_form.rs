//! System (9) as plcp's mixed PLCP: dense, sparse and as JSON input.

use super::System;
use faer::{Col, Mat};
use plcp::{Plcp, PlcpError, Scalar};

impl System {
    /// The mixed PLCP of system (9), in plcp's form
    /// `0 = (M x + q + L d)[..free]`, `w = (M x + q + L d)[free..]`, with
    /// `x = (q_dd, X, x*_dd)`, `w = y*` and `L = Lambda`:
    ///
    /// ```text
    /// M = [ -M_q  -A^T     0  ]   q = [ 0  ]   d = [ a_o ]
    ///     [ -A     0      T N ]       [ 0  ]       [ 0   ]
    ///     [  0   -(T N)^T  0  ]       [ X* ]       [ 0   ]
    /// ```
    pub fn blocks(&self) -> (Mat<f64>, Col<f64>, Col<f64>) {
        let (nb, ns, np) = (self.coordinates.len(), self.forces.len(), self.modes.len());
        let dim = nb + ns + np;
        let mut m = Mat::<f64>::zeros(dim, dim);
        for j in 0..nb {
            m[(j, j)] = -self.mass[j];
        }
        for j in 0..nb {
            let (rows, vals) = self.a.col(j);
            for (&r, &v) in rows.iter().zip(vals) {
                m[(j, nb + r)] = -v;
                m[(nb + r, j)] = -v;
            }
        }
        for k in 0..np {
            let (rows, vals) = self.tn.col(k);
            for (&r, &v) in rows.iter().zip(vals) {
                m[(nb + r, nb + ns + k)] = v;
                m[(nb + ns + k, nb + r)] = -v;
            }
        }
        let q = Col::from_fn(dim, |i| {
            if i >= nb + ns {
                self.capacities[i - nb - ns]
            } else {
                0.0
            }
        });
        let d = Col::from_fn(dim, |i| if i < nb { self.load[i] } else { 0.0 });
        (m, q, d)
    }

    /// The mixed PLCP in precision `T`, for `Lambda` from 0 to `lambda_max` (`None`: infinity).
    pub fn plcp<T: Scalar>(&self, lambda_max: Option<f64>) -> Result<Plcp<T>, PlcpError> {
        let (m, q, d) = self.blocks();
        let mt = Mat::from_fn(m.nrows(), m.ncols(), |i, j| T::from_f64(m[(i, j)]));
        let qt = Col::from_fn(q.nrows(), |i| T::from_f64(q[i]));
        let dt = Col::from_fn(d.nrows(), |i| T::from_f64(d[i]));
        Plcp::mixed(mt.as_ref(), qt.as_ref(), dt.as_ref(), self.sizes().free())?
            .with_range(T::zero(), lambda_max.map(T::from_f64))
    }

    /// The mixed PLCP of [`System::blocks`] with `M` in sparse form (the
    /// stored entries of the mass diagonal, `A` and `T N` only; `O(nnz)`,
    /// no dense `M`), for plcp's sparse basis.
    ///
    /// ```
    /// let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml")).unwrap();
    /// let scene = frames::Scene::from_toml(&src, "cantilever.toml").unwrap();
    /// let sys = frames::System::assemble(&scene.frame);
    /// let sparse = sys.plcp_sparse::<f64>(None).unwrap();
    /// assert!(sparse.is_sparse());
    /// assert_eq!(sparse.m(), sys.plcp::<f64>(None).unwrap().m());
    /// ```
    pub fn plcp_sparse<T: Scalar>(&self, lambda_max: Option<f64>) -> Result<Plcp<T>, PlcpError> {
        let (nb, ns, np) = (self.coordinates.len(), self.forces.len(), self.modes.len());
        let dim = nb + ns + np;
        let mut triplets: Vec<(usize, usize, T)> = Vec::new();
        for j in 0..nb {
            triplets.push((j, j, T::from_f64(-self.mass[j])));
        }
        // the stored entries only: O(nnz), in any order (the triplets are
        // sorted into columns, each position given once)
        for j in 0..nb {
            let (rows, vals) = self.a.col(j);
            for (&r, &v) in rows.iter().zip(vals) {
                triplets.push((j, nb + r, T::from_f64(-v)));
                triplets.push((nb + r, j, T::from_f64(-v)));
            }
        }
        for k in 0..np {
            let (rows, vals) = self.tn.col(k);
            for (&r, &v) in rows.iter().zip(vals) {
                triplets.push((nb + r, nb + ns + k, T::from_f64(v)));
                triplets.push((nb + ns + k, nb + r, T::from_f64(-v)));
            }
        }
        let m = plcp::matrix::Csc::try_from_triplets(dim, dim, &triplets)?;
        let qt = Col::from_fn(dim, |i| {
            T::from_f64(if i >= nb + ns {
                self.capacities[i - nb - ns]
            } else {
                0.0
            })
        });
        let dt = Col::from_fn(dim, |i| {
            T::from_f64(if i < nb { self.load[i] } else { 0.0 })
        });
        Plcp::mixed_sparse(m, qt.as_ref(), dt.as_ref(), self.sizes().free())?
            .with_range(T::zero(), lambda_max.map(T::from_f64))
    }

    /// The mixed PLCP as plcp's JSON input: `{"M": rows, "q", "d", "lambda_max", "free"}`.
    #[cfg(feature = "json")]
    pub fn plcp_json(&self, lambda_max: Option<f64>) -> serde_json::Value {
        let (m, q, d) = self.blocks();
        let rows: Vec<Vec<f64>> = (0..m.nrows())
            .map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect())
            .collect();
        serde_json::json!({
            "M": rows,
            "q": (0..q.nrows()).map(|i| q[i]).collect::<Vec<_>>(),
            "d": (0..d.nrows()).map(|i| d[i]).collect::<Vec<_>>(),
            "lambda_max": lambda_max,
            "free": self.sizes().free(),
        })
    }
}
