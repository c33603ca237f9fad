//! A massless mechanism: a coordinate that the load accelerates without limit.

use super::full::full_blocks;
use crate::kernel::null_space;
use crate::model::{Component, Frame};
use faer::Mat;

/// A coordinate that the load can accelerate without limit: it moves in a
/// mechanism that carries no mass (rotations of a lumped model carry none
/// unless `j` is given). `None` if there is none.
pub fn massless_mechanism(frame: &Frame) -> Option<(usize, Component)> {
    let f = full_blocks(frame);
    let massless: Vec<usize> = (0..f.coords.len()).filter(|&j| f.mass[j] == 0.0).collect();
    if massless.is_empty() {
        return None;
    }
    let scale = massless.iter().fold(0.0f64, |s, &j| s.max(f.load[j].abs()));
    if scale == 0.0 {
        return None;
    }
    // A massless motion moves only massless coordinates; every deformation with
    // a yield mode is free at the hinges, so only the rows without one (the
    // inextensibility of planar members) restrict it: the null space of `C`,
    // those rows on the massless columns. Columns of `C` that are zero (the
    // rotations of a planar frame: inextensibility involves translations only)
    // are unit null vectors; the rest is the null space of the small block `C'`
    // of the rows and columns that touch, found densely.
    let ne = frame.elements.len();
    let rigid_rows: Vec<usize> = (0..ne)
        .filter_map(|e| frame.model.rigid_rows(&frame.elements[e], e, ne))
        .collect();
    let mut position = vec![None; f.coords.len()];
    for (k, &j) in massless.iter().enumerate() {
        position[j] = Some(k);
    }
    let mut touched_col = vec![None; massless.len()];
    let mut touched: Vec<usize> = Vec::new();
    let mut rows: Vec<usize> = Vec::new();
    for &r in &rigid_rows {
        let mut any = false;
        for &(j, _) in &f.a[r] {
            if let Some(k) = position[j] {
                any = true;
                if touched_col[k].is_none() {
                    touched_col[k] = Some(touched.len());
                    touched.push(k);
                }
            }
        }
        if any {
            rows.push(r);
        }
    }
    let tol = 1e-9 * scale * (massless.len() as f64);
    // a unit null vector: the work is the load on its coordinate
    if let Some(k) =
        (0..massless.len()).find(|&k| touched_col[k].is_none() && f.load[massless[k]].abs() > tol)
    {
        let co = f.coords[massless[k]];
        return Some((co.node, co.component));
    }
    if touched.is_empty() {
        return None;
    }
    let mut c = Mat::<f64>::zeros(rows.len(), touched.len());
    for (i, &r) in rows.iter().enumerate() {
        for &(j, v) in &f.a[r] {
            if let Some(col) = position[j].and_then(|k| touched_col[k]) {
                c[(i, col)] = v;
            }
        }
    }
    let (_, basis) = null_space(&c);
    for v in &basis {
        let vn = v.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        let load = |t: usize| f.load[massless[touched[t]]];
        let work: f64 = v.iter().enumerate().map(|(t, x)| x * load(t)).sum();
        if work.abs() > tol * vn {
            // point at a loaded coordinate that moves in this mechanism
            let t = (0..touched.len())
                .filter(|&t| v[t] != 0.0 && load(t) != 0.0)
                .max_by(|&x, &y| (v[x] * load(x)).abs().total_cmp(&(v[y] * load(y)).abs()))?;
            let co = f.coords[massless[touched[t]]];
            return Some((co.node, co.component));
        }
    }
    None
}
