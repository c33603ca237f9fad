//! The dense basis: the explicit inverse of `B`, updated in product form
//! (`O((p+n)^2)` a pivot whatever the basis; the reference in tests).

use super::*;

/// Product-form update of an explicit inverse `inv` (top-left `k x k`) when
/// column `r` of the matrix is replaced and `y = inv * a_new`.
fn product_form_update<T: Scalar>(inv: &mut Mat<T>, k: usize, r: usize, y: &[T]) {
    let piv = y[r];
    for j in 0..k {
        let f = inv[(r, j)] / piv;
        if f != T::zero() {
            col_axpy(inv, j, &y[..k], -f);
        }
        inv[(r, j)] = f;
    }
}

/// Dense explicit inverse with product-form (rank-one) updates.
pub(crate) struct DenseInverse<T: Scalar> {
    inv: Mat<T>,
}

impl<T: Scalar> DenseInverse<T> {
    pub(crate) fn new(dim: usize) -> Self {
        Self {
            inv: Mat::identity(dim, dim),
        }
    }
}

impl<T: Scalar> BasisFactor<T> for DenseInverse<T> {
    fn refactor(
        &mut self,
        m: MatrixRef<'_, T>,
        d: &Col<T>,
        p: usize,
        basis: &[Var],
    ) -> Option<f64> {
        let dim = m.nrows();
        let mut b = Mat::<T>::zeros(dim, dim);
        for (r, v) in basis.iter().enumerate() {
            let a = var_column(m, d, p, *v);
            for i in 0..dim {
                b[(i, r)] = a[i];
            }
        }
        let (inv, cond) = invert(b.as_ref(), &col_norms1(b.as_ref()))?;
        self.inv = inv;
        Some(cond)
    }

    fn solve(&self, a: &Col<T>) -> Col<T> {
        matvec(self.inv.as_ref(), a.as_ref())
    }

    fn column(&self, m: MatrixRef<'_, T>, d: &Col<T>, p: usize, v: Var) -> Col<T> {
        match v {
            Var::W(_) | Var::Artificial(_) => {
                self.unit(identity_row(p, v).expect("identity column"))
            }
            Var::Z(j) => match m {
                MatrixRef::Dense(m) => -matvec(self.inv.as_ref(), m.col(p + j)),
                MatrixRef::Sparse(_) => self.solve(&var_column(m, d, p, v)),
            },
            Var::U(j) => match m {
                MatrixRef::Dense(m) => -matvec(self.inv.as_ref(), m.col(j)),
                MatrixRef::Sparse(_) => self.solve(&var_column(m, d, p, v)),
            },
            Var::Lambda => -matvec(self.inv.as_ref(), d.as_ref()),
        }
    }

    fn unit(&self, k: usize) -> Col<T> {
        self.inv.col(k).to_owned()
    }

    fn solve_transpose(&self, c: &Col<T>) -> Col<T> {
        matvec(self.inv.as_ref().transpose(), c.as_ref())
    }

    fn replace(
        &mut self,
        _m: MatrixRef<'_, T>,
        _d: &Col<T>,
        _p: usize,
        r: usize,
        _leaving: Var,
        _entering: Var,
        y: &Col<T>,
    ) -> bool {
        let dim = self.inv.nrows();
        let ys: Vec<T> = (0..dim).map(|i| y[i]).collect();
        product_form_update(&mut self.inv, dim, r, &ys);
        true
    }
}
