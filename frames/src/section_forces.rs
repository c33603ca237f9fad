//! The forces a section of a general space frame carries besides `M3`.
//!
//! In the general space model ([`crate::model::Model::Space`]) each section
//! carries two bending moments, `M3` about the element's `e3` axis (the
//! [`MemberForce::Moment`] that every model reports, and that
//! [`crate::response`] tabulates) and `M2` about `e2`
//! ([`MemberForce::Moment2`]), and each element a torque `T` about `e1` and
//! an axial force `N` along it. A pipe's bending is isotropic, so what meets
//! the yield surface
//!
//! ```text
//! (M2^2 + M3^2) / Mp^2 + (T / Tp)^2 <= 1      (with N: its interaction)
//! ```
//!
//! is the bending magnitude `sqrt(M2^2 + M3^2)`, not the components in the
//! element's (arbitrary) axes. [`SpaceForces`] finds where `M2`, `T` and `N`
//! sit among the free variables `(q_dd, X)` of system (9), so that the report
//! can give them at a breakpoint, or as affine functions of `Lambda` on a
//! piece of the path.

use crate::assemble::{MemberForce, System};
use crate::model::Model;

/// Where each section's `M2` and each element's torque and axial force sit in
/// the free variables `u = (q_dd, X)` of system (9) of a general space scene.
#[derive(Clone, Debug)]
pub struct SpaceForces {
    /// Per critical section, the index in `u` of its `M2`.
    m2: Vec<Option<usize>>,
    /// Per element, the index in `u` of its torque.
    torque: Vec<Option<usize>>,
    /// Per element, the index in `u` of its axial force.
    axial: Vec<Option<usize>>,
}

impl SpaceForces {
    /// The positions for `system`, or `None` unless it is the general space
    /// model (planar and grillage systems, and space scenes reduced to them,
    /// have no `M2`).
    pub fn new(system: &System, elements: usize) -> Option<Self> {
        if system.model != Model::Space {
            return None;
        }
        let nb = system.coordinates.len();
        let mut out = SpaceForces {
            m2: vec![None; system.sections.len()],
            torque: vec![None; elements],
            axial: vec![None; elements],
        };
        for (r, f) in system.forces.iter().enumerate() {
            match *f {
                MemberForce::Moment2(k) if k < out.m2.len() => out.m2[k] = Some(nb + r),
                MemberForce::Torque(e) if e < elements => out.torque[e] = Some(nb + r),
                MemberForce::Axial(e) if e < elements => out.axial[e] = Some(nb + r),
                _ => {}
            }
        }
        Some(out)
    }

    /// `M2` of section `k` in `u` (zero where the system does not keep it:
    /// a section left out of the system carries none).
    pub fn m2(&self, u: &[f64], k: usize) -> f64 {
        self.m2.get(k).copied().flatten().map_or(0.0, |r| u[r])
    }

    /// The torque of element `e` in `u` (zero where it is not kept).
    pub fn torque(&self, u: &[f64], e: usize) -> f64 {
        self.torque.get(e).copied().flatten().map_or(0.0, |r| u[r])
    }

    /// The axial force (tension positive) of element `e` in `u` (zero where
    /// it is not kept).
    pub fn axial(&self, u: &[f64], e: usize) -> f64 {
        self.axial.get(e).copied().flatten().map_or(0.0, |r| u[r])
    }

    /// The bending magnitude `sqrt(M2^2 + M3^2)` of section `k`, given its
    /// `M3` (the moment every model reports).
    pub fn bending(&self, u: &[f64], k: usize, m3: f64) -> f64 {
        self.m2(u, k).hypot(m3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Scene;

    fn system_of(file: &str) -> (System, usize) {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../scenes")
            .join(file);
        let scene = Scene::from_file(&path).unwrap();
        let elements = scene.frame.elements.len();
        let system = System::assemble(&scene.frame);
        (system, elements)
    }

    /// Every section of the general 3D run has an `M2`, every element a
    /// torque and an axial force, each at a distinct member-force row;
    /// the reduced (planar) riser has none.
    #[test]
    fn positions_cover_the_general_model_only() {
        let (sys, elements) = system_of("pipe-whip/space-run.toml");
        let f = SpaceForces::new(&sys, elements).expect("general space model");
        assert!(f.m2.iter().all(Option::is_some));
        assert!(f.torque.iter().all(Option::is_some));
        assert!(f.axial.iter().all(Option::is_some));
        let mut rows: Vec<usize> =
            f.m2.iter()
                .chain(&f.torque)
                .chain(&f.axial)
                .map(|r| r.unwrap())
                .collect();
        let n = rows.len();
        rows.sort_unstable();
        rows.dedup();
        assert_eq!(rows.len(), n);
        let (planar, elements) = system_of("pipe-whip/riser.toml");
        assert!(SpaceForces::new(&planar, elements).is_none());
    }
}
