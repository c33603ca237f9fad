//! The time-stepping response against the PLCP path ([`compare`]).

use super::*;
/// Largest translation of any node, `max |q_j|` over translational coordinates
/// (x and y of a planar frame, z of a grillage; never a rotation).
pub fn largest_translation(system: &System, q: &[f64]) -> f64 {
    system
        .coordinates
        .iter()
        .zip(q)
        .filter(|(c, _)| !c.component.is_rotation())
        .fold(0.0, |a, (_, x)| a.max(x.abs()))
}

/// A time-stepping run against the PLCP response.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// Time of the comparison (the end time, or the PLCP path's first
    /// deactivation if earlier).
    pub t: f64,
    /// Largest difference of a nodal translation at `t`.
    pub displacement_error: f64,
    /// Largest nodal translation of the PLCP response at `t`.
    pub displacement_scale: f64,
    /// Largest difference of a hinge's start-of-flow time, over the PLCP
    /// hinges that form before `t` (`inf` if one of them never flows in the run).
    pub activation_error: f64,
    /// PLCP hinges (groups) compared.
    pub hinges_compared: usize,
    /// Groups that flow in the run before `t` but not in the PLCP path.
    pub extra_activations: usize,
}

/// Start-of-flow time of every hinge group in a run.
fn group_starts(analysis: &Analysis, run: &StepResponse) -> Vec<Option<f64>> {
    let mut first = vec![None; analysis.reading.groups.len()];
    for e in run.activations() {
        if let Some(Some(g)) = analysis.reading.group_of.get(e.section) {
            let f: &mut Option<f64> = &mut first[*g];
            if f.is_none() {
                *f = Some(e.t);
            }
        }
    }
    first
}

/// Compares a run from rest with the PLCP response at `min(run end, first
/// deactivation of the path)`.
pub fn compare(analysis: &Analysis, run: &StepResponse) -> Comparison {
    let history = &analysis.scene.history;
    let mut t = run.end.t;
    if let Some((_, td)) = plcp_valid_until(analysis) {
        t = t.min(td);
    }
    let exact = path_state(analysis, t);
    let ts = run
        .displacement_at(t)
        .unwrap_or_else(|| vec![f64::NAN; exact.q.len()]);
    let diff: Vec<f64> = exact.q.iter().zip(&ts).map(|(a, b)| a - b).collect();
    let displacement_error = largest_translation(&analysis.system, &diff);
    let starts = group_starts(analysis, run);
    let mut activation_error: f64 = 0.0;
    let mut compared = 0;
    let mut plcp_groups = vec![false; starts.len()];
    for hinge in &analysis.reading.hinges {
        let Some(tp) = history.time_at(hinge.lambda) else {
            continue;
        };
        if tp >= t {
            continue;
        }
        plcp_groups[hinge.group] = true;
        compared += 1;
        let e = starts[hinge.group].map_or(f64::INFINITY, |ts| (ts - tp).abs());
        activation_error = activation_error.max(e);
    }
    let extra = starts
        .iter()
        .zip(&plcp_groups)
        .filter(|(s, p)| !**p && s.is_some_and(|ts| ts < t))
        .count();
    Comparison {
        t,
        displacement_error,
        displacement_scale: largest_translation(&analysis.system, &exact.q),
        activation_error,
        hinges_compared: compared,
        extra_activations: extra,
    }
}
