//! The facets of yield polygons that start or stop accelerating at a
//! breakpoint while their section keeps flowing (the text report's
//! `facets:`).

use crate::analysis::Analysis;

impl Analysis {
    /// At a breakpoint, the facets of yield polygons of flowing sections that
    /// start or stop accelerating while their section keeps flowing (the flow
    /// moving across the polygon; no event of the hinge itself), e.g.
    /// `A (AB from) @124 stops, @101 starts`. A facet that stops keeps its rate
    /// in system (9), whose path cannot let a rate decrease.
    pub(super) fn facet_changes(&self, lambda: f64) -> Vec<String> {
        if self.system.modes.iter().all(|m| m.facet.is_none()) {
            return Vec::new(); // no yield polygon
        }
        let pieces = &self.solution.pieces;
        let ivs = &self.reading.intervals;
        let Some(k) = ivs.iter().position(|i| i.lambda_from == lambda && !i.rigid) else {
            return Vec::new();
        };
        if k == 0 || ivs[k - 1].rigid {
            return Vec::new();
        }
        // the pieces of the path just before and just after the breakpoint,
        // read inside their spans (an interval may hold several pieces)
        let acc = |span: Option<&crate::hinge::Span>| -> Vec<bool> {
            let Some(span) = span else {
                return Vec::new();
            };
            let p = &pieces[span.piece];
            let l = if span.lambda_to.is_finite() {
                0.5 * (span.lambda_from + span.lambda_to)
            } else {
                span.lambda_from + span.lambda_from.abs().max(1.0)
            };
            let z = p.z(l);
            let scale = z.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
            z.iter()
                .map(|&v| v > self.solution.tolerance * scale)
                .collect()
        };
        let (before, after) = (acc(ivs[k - 1].pieces.last()), acc(ivs[k].pieces.first()));
        if before.is_empty() || after.is_empty() {
            return Vec::new();
        }
        let modes = &self.system.modes;
        // the facet modes of each section, in mode order (one pass over the
        // modes: a scan of all modes per section was quadratic, 4 s of a
        // 1000-element cantilever's report)
        let mut by_section: Vec<Vec<usize>> = vec![Vec::new(); self.system.sections.len()];
        for (m, mode) in modes.iter().enumerate() {
            if mode.facet.is_some() {
                by_section[mode.section].push(m);
            }
        }
        let mut out = Vec::new();
        for (sec, ks) in by_section.iter().enumerate() {
            let was = ks.iter().any(|&m| before[m]);
            let is = ks.iter().any(|&m| after[m]);
            if !(was && is) {
                continue;
            }
            let stops: Vec<String> = ks
                .iter()
                .filter(|&&m| before[m] && !after[m])
                .map(|&m| self.mode_tag(m, modes[m].sign))
                .collect();
            let starts: Vec<String> = ks
                .iter()
                .filter(|&&m| !before[m] && after[m])
                .map(|&m| self.mode_tag(m, modes[m].sign))
                .collect();
            if stops.is_empty() && starts.is_empty() {
                continue;
            }
            let Some(g) = self.reading.group_of[sec] else {
                continue;
            };
            let mut what = Vec::new();
            if !stops.is_empty() {
                what.push(format!("{} stops", stops.join(" ")));
            }
            if !starts.is_empty() {
                what.push(format!("{} starts", starts.join(" ")));
            }
            out.push(format!("{} {}", self.group_label(g), what.join(", ")));
        }
        out
    }
}
