//! Which moment distributions and node series the JSON report writes: all
//! for a small scene, an even sample of `n` out of `len` otherwise
//! ([`sample_indices`]: `round(k (len - 1) / (n - 1))`, `k = 0..n`).

use crate::analysis::Analysis;

/// Which Lambda values get moment distributions (and which intervals their
/// pieces) in the JSON report.
#[derive(Clone, Debug, PartialEq)]
pub enum MomentPick {
    /// Every breakpoint and interval.
    All,
    /// At most this many, sampled evenly over the breakpoints (first and last kept).
    Count(usize),
    /// The breakpoints nearest these Lambda values, and the intervals holding them.
    At(Vec<f64>),
}

/// Which nodes get accelerations and the time response in the JSON report.
#[derive(Clone, Debug, PartialEq)]
pub enum NodePick {
    /// Every node.
    All,
    /// At most this many, sampled evenly over the node list (first and last kept).
    Count(usize),
    /// These node ids.
    Ids(Vec<String>),
}

/// How the JSON report writes each interval's hinge sets (`accelerating`,
/// `constant_rate`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HingeSets {
    /// The full lists in every interval. For a hinge that travels, the groups
    /// behind the front rotate at a constant rate in every later interval, so
    /// the lists grow as `intervals x hinges` (585 of the 616 MB of JSON of
    /// the 10^4-element cantilever).
    Full,
    /// Per interval, what starts and stops against the interval before
    /// (`hinge_changes`: `accelerating` and `constant_rate`, each with
    /// `added` and `removed`; the first interval against empty sets). The
    /// output is linear in the hinge events; a reader rebuilds the lists by
    /// applying the changes in order.
    Changes,
}

/// What the JSON report writes beyond what it always writes (every
/// breakpoint's events, every interval's hinge sets): moment distributions
/// and node series grow with `breakpoints x sections` and `nodes x times`, so
/// large scenes get a bounded default ([`OutputSelection::default_for`]).
#[derive(Clone, Debug, PartialEq)]
pub struct OutputSelection {
    /// Moment distributions.
    pub moments: MomentPick,
    /// Node accelerations and displacement/velocity series.
    pub nodes: NodePick,
    /// Each interval's hinge sets in full, or as changes.
    pub hinge_sets: HingeSets,
}

/// Scenes up to this many nodes and breakpoints report everything by default.
pub const SMALL_SCENE: usize = 200;
/// The default number of Lambda values with moment distributions, and of
/// nodes with series, for larger scenes.
pub const DEFAULT_SAMPLES: usize = 20;

/// `count` indices of `0..len`, evenly spaced, the first and the last kept.
pub fn sample_indices(len: usize, count: usize) -> Vec<usize> {
    if count == 0 || len == 0 {
        return Vec::new();
    }
    if len <= count {
        return (0..len).collect();
    }
    if count == 1 {
        return vec![len - 1];
    }
    let mut v: Vec<usize> = (0..count)
        .map(|k| ((k as f64) * ((len - 1) as f64) / ((count - 1) as f64)).round() as usize)
        .collect();
    v.dedup();
    v
}

/// `count` values evenly spaced from `from` to `to`, both kept (`from`
/// alone where `to <= from`): the default sampled Lambda values of a large
/// scene ([`OutputSelection::default_for`]).
pub fn spread(from: f64, to: f64, count: usize) -> Vec<f64> {
    if count == 0 {
        return Vec::new();
    }
    if count == 1 || to <= from {
        return vec![from];
    }
    (0..count)
        .map(|k| from + (to - from) * (k as f64) / ((count - 1) as f64))
        .collect()
}

impl OutputSelection {
    /// Everything (the hinge sets in full).
    pub fn all() -> Self {
        Self {
            moments: MomentPick::All,
            nodes: NodePick::All,
            hinge_sets: HingeSets::Full,
        }
    }
    /// Everything for a small scene (at most [`SMALL_SCENE`] nodes and
    /// breakpoints); otherwise [`DEFAULT_SAMPLES`] Lambda values and nodes.
    /// The hinge sets in full up to [`SMALL_SCENE`] nodes, as changes above.
    ///
    /// The sampled Lambda values are decided before the path is known where
    /// they can be: with `lambda_max` set, the breakpoints nearest
    /// [`DEFAULT_SAMPLES`] values evenly spaced from the first breakpoint to
    /// `lambda_max` ([`MomentPick::At`], [`spread`]); without it, an even
    /// sample over the breakpoints ([`MomentPick::Count`]). A selection
    /// known once the first breakpoint is lets `frames run` analyse a large
    /// scene in one trace ([`crate::stream`]); a count needs the number of
    /// breakpoints, known only at the end.
    pub fn default_for(a: &Analysis) -> Self {
        Self::default_for_path(
            a.scene.frame.nodes.len(),
            a.reading.breakpoints.len(),
            a.reading.breakpoints.first().map(|b| b.lambda),
            a.options.solve.lambda_max,
        )
    }
    /// [`OutputSelection::default_for`] a scene of `nodes` nodes whose path
    /// has `bps` breakpoints, the first at `first`, traced up to `lambda_max`.
    pub fn default_for_path(
        nodes: usize,
        bps: usize,
        first: Option<f64>,
        lambda_max: Option<f64>,
    ) -> Self {
        let mut sel = Self::default_for_counts(nodes, bps);
        if let (MomentPick::Count(c), Some(first), Some(to)) = (&sel.moments, first, lambda_max) {
            if first.is_finite() && to.is_finite() {
                sel.moments = MomentPick::At(spread(first, to, *c));
            }
        }
        sel
    }
    /// [`OutputSelection::default_for`] a scene of `nodes` nodes whose path
    /// has `bps` breakpoints.
    pub fn default_for_counts(nodes: usize, bps: usize) -> Self {
        Self {
            moments: if bps <= SMALL_SCENE && nodes <= SMALL_SCENE {
                MomentPick::All
            } else {
                MomentPick::Count(DEFAULT_SAMPLES)
            },
            nodes: if nodes <= SMALL_SCENE {
                NodePick::All
            } else {
                NodePick::Count(DEFAULT_SAMPLES)
            },
            hinge_sets: if nodes <= SMALL_SCENE {
                HingeSets::Full
            } else {
                HingeSets::Changes
            },
        }
    }
    /// The node indices selected out of `ids`; `Err` names an unknown id.
    pub fn node_indices(&self, ids: &[&str]) -> Result<Vec<usize>, String> {
        match &self.nodes {
            NodePick::All => Ok((0..ids.len()).collect()),
            NodePick::Count(c) => Ok(sample_indices(ids.len(), *c)),
            NodePick::Ids(want) => want
                .iter()
                .map(|w| {
                    ids.iter()
                        .position(|i| i == w)
                        .ok_or_else(|| format!("--nodes: no node \"{w}\" in the scene"))
                })
                .collect(),
        }
    }
    /// Which of `lambdas` (in order) get moment distributions.
    pub fn moment_indices(&self, lambdas: &[f64]) -> Vec<usize> {
        match &self.moments {
            MomentPick::All => (0..lambdas.len()).collect(),
            MomentPick::Count(c) => sample_indices(lambdas.len(), *c),
            MomentPick::At(ls) => {
                let mut v: Vec<usize> = ls
                    .iter()
                    .filter_map(|l| {
                        (0..lambdas.len()).min_by(|&a, &b| {
                            (lambdas[a] - l).abs().total_cmp(&(lambdas[b] - l).abs())
                        })
                    })
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            }
        }
    }
    /// One line for the report: what was selected out of how many.
    #[cfg(feature = "json")]
    pub(super) fn describe(&self, what: &str, kept: usize, of: usize, flag: &str) -> String {
        if kept == of {
            format!("{what}: all {of}")
        } else {
            format!("{what}: {kept} of {of} (sampled; {flag} all, a count, or a list)")
        }
    }
}
