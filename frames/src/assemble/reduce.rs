//! What is left out: supported coordinates, the unloaded decoupled parts
//! (connected components of the sparsity graph) and the tied sections; and
//! the rank of `A`.

use super::full::{full_blocks, rigid_sections};
use super::{LeftOut, Sizes, SparseBlock, System, YieldMode};
use crate::kernel::null_space;
use crate::model::Frame;

struct Dsu(Vec<usize>);
impl Dsu {
    fn find(&mut self, i: usize) -> usize {
        let mut r = i;
        while self.0[r] != r {
            r = self.0[r];
        }
        let mut i = i;
        while self.0[i] != r {
            let n = self.0[i];
            self.0[i] = r;
            i = n;
        }
        r
    }
    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.0[a] = b;
        }
    }
}

/// The rank of a square `A` that its sparse LU shows nonsingular: full, when
/// the condition estimate says `A` is farther than the kernel's relative
/// tolerance `1e-10` from a singular matrix (`cond_1(A) * 1e-10 < 1`, a
/// backward-stable LU and Hager's estimator standing in for the size factor
/// the dense elimination of [`null_space`] adds for its own rounding); `None`
/// otherwise (then the dense elimination decides). `O(nnz(L + U))` instead of
/// `O(n^3)`: the cantilever's `A` has `cond_1 = 6 n^2` for `n` elements, and
/// at 1000 elements the dense elimination took 30 s.
fn full_rank_sparse(a: &SparseBlock) -> Option<usize> {
    let n = a.nrows();
    if n != a.ncols() || n == 0 {
        return None;
    }
    let cond = a.csc().lu_condition()?;
    (cond * 1e-10 < 1.0).then_some(n)
}

impl System {
    /// Assembles system (9) for a frame, leaving out supported coordinates and
    /// unloaded decoupled parts.
    ///
    /// ```
    /// let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml")).unwrap();
    /// let scene = frames::Scene::from_toml(&src, "cantilever.toml").unwrap();
    /// let sys = frames::System::assemble(&scene.frame);
    /// // four elements: y and rz at four free nodes, two end moments each;
    /// // the axial motion (x, N) is unloaded and decoupled, so it is left out
    /// assert_eq!((sys.full.coordinates, sys.full.forces, sys.full.modes), (12, 12, 16));
    /// // the tied sections at the three inner nodes keep one pair of yield modes each
    /// assert_eq!((sys.coordinates.len(), sys.forces.len(), sys.modes.len()), (8, 8, 10));
    /// assert!(sys.is_determinate());
    /// ```
    pub fn assemble(frame: &Frame) -> System {
        Self::assemble_with(frame, true)
    }

    /// System (9) with nothing left out but the supported coordinates: every
    /// coordinate, member force and yield mode of the model, no ties. The same
    /// path as [`System::assemble`] (a check of the leave-outs), larger.
    pub fn assemble_full(frame: &Frame) -> System {
        Self::assemble_with(frame, false)
    }

    pub(super) fn assemble_with(frame: &Frame, leave_out: bool) -> System {
        let f = full_blocks(frame);
        let (nb, ns, np) = (f.coords.len(), f.forces.len(), f.modes.len());
        // variables: coordinates [0, nb), forces [nb, nb + ns), modes [nb + ns, ...)
        let mut dsu = Dsu((0..nb + ns + np).collect());
        for (r, row) in f.a.iter().enumerate() {
            for &(j, _) in row {
                dsu.union(nb + r, j);
            }
        }
        for (k, m) in f.modes.iter().enumerate() {
            for &(r, _) in &m.column {
                dsu.union(nb + r, nb + ns + k);
            }
        }
        let mut loaded = vec![false; nb + ns + np];
        for j in 0..nb {
            if f.load[j] != 0.0 {
                let r = dsu.find(j);
                loaded[r] = true;
            }
        }
        let keep: Vec<bool> = (0..nb + ns + np)
            .map(|v| !leave_out || loaded[dsu.find(v)])
            .collect();
        let kc: Vec<usize> = (0..nb).filter(|&j| keep[j]).collect();
        let kf: Vec<usize> = (0..ns).filter(|&r| keep[nb + r]).collect();
        let ties: Vec<[usize; 2]> = if leave_out {
            rigid_sections(frame, &f.sections)
                .into_iter()
                .filter(|t| keep[nb + t[0]] && keep[nb + t[1]])
                .collect()
        } else {
            Vec::new()
        };
        let mut rigid = vec![false; f.sections.len()];
        for t in &ties {
            rigid[t[1]] = true;
        }
        let km: Vec<usize> = (0..np)
            .filter(|&k| keep[nb + ns + k] && !rigid[f.modes[k].mode.section])
            .collect();
        let mut left_out = LeftOut {
            supported: f.supported.clone(),
            loads_on_supports: f.loads_on_supports.clone(),
            full_assembly: !leave_out,
            ..LeftOut::default()
        };
        for (co, _) in f.coords.iter().zip(&keep).filter(|(_, k)| !**k) {
            left_out.decoupled_coordinates.push((co.node, co.component));
        }
        for r in 0..ns {
            if !keep[nb + r] {
                left_out.decoupled_forces.push(f.forces[r]);
            }
        }
        left_out.tied_sections = ties.iter().map(|t| t[1]).collect();
        let tied_modes = (0..np)
            .filter(|&k| keep[nb + ns + k] && rigid[f.modes[k].mode.section])
            .count();
        left_out.decoupled_modes = np - km.len() - tied_modes;
        let mut col_of = vec![None; nb];
        for (k, &j) in kc.iter().enumerate() {
            col_of[j] = Some(k);
        }
        let mut entries = Vec::new();
        for (i, &r) in kf.iter().enumerate() {
            for &(j, v) in &f.a[r] {
                if let Some(k) = col_of[j] {
                    entries.push((i, k, v));
                }
            }
        }
        let a = SparseBlock::from_entries(kf.len(), kc.len(), entries);
        let mut row_of = vec![None; ns];
        for (i, &r) in kf.iter().enumerate() {
            row_of[r] = Some(i);
        }
        let mut entries = Vec::new();
        for (col, &k) in km.iter().enumerate() {
            for &(r, v) in &f.modes[k].column {
                if let Some(row) = row_of[r] {
                    entries.push((row, col, v));
                }
            }
        }
        let tn = SparseBlock::from_entries(kf.len(), km.len(), entries);
        let modes: Vec<YieldMode> = km.iter().map(|&k| f.modes[k].mode).collect();
        let capacities = km.iter().map(|&k| f.modes[k].capacity).collect();
        let rank_a = full_rank_sparse(&a).unwrap_or_else(|| null_space(&a.to_dense()).0);
        System {
            model: frame.model,
            coordinates: kc.iter().map(|&j| f.coords[j]).collect(),
            forces: kf.iter().map(|&r| f.forces[r]).collect(),
            modes,
            sections: f.sections,
            ties,
            mass: kc.iter().map(|&j| f.mass[j]).collect(),
            a,
            tn,
            capacities,
            load: kc.iter().map(|&j| f.load[j]).collect(),
            full: Sizes {
                coordinates: nb,
                forces: ns,
                modes: np,
            },
            left_out,
            rank_a,
        }
    }
}
