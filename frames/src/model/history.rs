//! The load history `lambda(t)`: reading and evaluating it.

use super::*;

pub(super) fn parse_history(cx: &Ctx<'_>, h: &Spanned<RawHistory>) -> Result<History, FramesError> {
    let r = h.get_ref();
    let kind = r
        .kind
        .as_ref()
        .map(|k| k.get_ref().as_str())
        .unwrap_or("ramp");
    let unexpected =
        |present: bool, key: &str, span: core::ops::Range<usize>| -> Result<(), FramesError> {
            if present {
                cx.err(
                    span,
                    format!("history {key}"),
                    format!("not a key of kind = \"{kind}\""),
                )
            } else {
                Ok(())
            }
        };
    let span_of = |v: &Option<Spanned<f64>>| v.as_ref().map(|s| s.span()).unwrap_or(0..0);
    match kind {
        "ramp" => {
            unexpected(
                r.points.is_some(),
                "points",
                r.points.as_ref().map(|s| s.span()).unwrap_or(0..0),
            )?;
            unexpected(r.peak.is_some(), "peak", span_of(&r.peak))?;
            unexpected(r.tau.is_some(), "tau", span_of(&r.tau))?;
            let rate = match &r.rate {
                Some(v) => cx.positive(v, "history rate")?,
                None => 1.0,
            };
            Ok(History::Ramp { rate })
        }
        "table" => {
            unexpected(r.rate.is_some(), "rate", span_of(&r.rate))?;
            unexpected(r.peak.is_some(), "peak", span_of(&r.peak))?;
            unexpected(r.tau.is_some(), "tau", span_of(&r.tau))?;
            let Some(pts) = &r.points else {
                return cx.err(
                    h.span(),
                    "history points",
                    "kind = \"table\" needs points = [[t, lambda], ...]",
                );
            };
            let mut points: Vec<(f64, f64)> = Vec::new();
            for p in pts.get_ref() {
                let v = p.get_ref();
                if v.len() != 2 {
                    return cx.err(
                        p.span(),
                        "history points",
                        format!("each point is [t, lambda], got {} numbers", v.len()),
                    );
                }
                let (t, l) = (v[0], v[1]);
                if !t.is_finite() || !l.is_finite() {
                    return cx.err(
                        p.span(),
                        "history points",
                        format!("non-finite number in [{t}, {l}]"),
                    );
                }
                if let Some(&(t0, l0)) = points.last() {
                    if t <= t0 {
                        return cx.err(
                            p.span(),
                            "history points",
                            format!("times must increase: {t} after {t0}"),
                        );
                    }
                    if l < l0 {
                        return cx.err(p.span(), "history points", format!("decreasing history: lambda = {l} at t = {t} after {l0} at t = {t0} (the loading class is monotone nondecreasing)"));
                    }
                } else if t != 0.0 || l != 0.0 {
                    return cx.err(p.span(), "history points", format!("the history starts from rest: the first point must be [0.0, 0.0], got [{t}, {l}]"));
                }
                points.push((t, l));
            }
            if points.len() < 2 {
                return cx.err(
                    pts.span(),
                    "history points",
                    "at least two points are needed",
                );
            }
            Ok(History::Table { points })
        }
        "saturating" => {
            unexpected(r.rate.is_some(), "rate", span_of(&r.rate))?;
            unexpected(
                r.points.is_some(),
                "points",
                r.points.as_ref().map(|s| s.span()).unwrap_or(0..0),
            )?;
            let (Some(peak), Some(tau)) = (&r.peak, &r.tau) else {
                return cx.err(
                    h.span(),
                    "history",
                    "kind = \"saturating\" needs peak and tau (lambda = peak (1 - exp(-t/tau)))",
                );
            };
            Ok(History::Saturating {
                peak: cx.positive(peak, "history peak")?,
                tau: cx.positive(tau, "history tau")?,
            })
        }
        other => {
            let span = r.kind.as_ref().map(|k| k.span()).unwrap_or(0..0);
            cx.err(
                span,
                "history kind",
                format!("unknown kind \"{other}\": expected \"ramp\", \"table\" or \"saturating\""),
            )
        }
    }
}

impl History {
    /// `lambda(t)` for `t >= 0`.
    pub fn lambda(&self, t: f64) -> f64 {
        match self {
            History::Ramp { rate } => rate * t,
            History::Table { points } => {
                let last = points[points.len() - 1];
                if t >= last.0 {
                    return last.1;
                }
                let k = points.partition_point(|p| p.0 <= t).max(1);
                let (a, b) = (points[k - 1], points[k]);
                a.1 + (b.1 - a.1) * (t - a.0) / (b.0 - a.0)
            }
            History::Saturating { peak, tau } => -peak * (-t / tau).exp_m1(),
        }
    }

    /// The first time at which `lambda(t) >= lambda`, if it is ever reached.
    pub fn time_at(&self, lambda: f64) -> Option<f64> {
        if lambda <= 0.0 {
            return Some(0.0);
        }
        match self {
            History::Ramp { rate } => Some(lambda / rate),
            History::Table { points } => {
                let k = points.iter().position(|p| p.1 >= lambda)?;
                let (a, b) = (points[k - 1], points[k]);
                Some(a.0 + (b.0 - a.0) * (lambda - a.1) / (b.1 - a.1))
            }
            History::Saturating { peak, tau } => {
                if lambda >= *peak {
                    None
                } else {
                    Some(-tau * (-lambda / peak).ln_1p())
                }
            }
        }
    }

    /// The largest value the history ever reaches (`inf` for a ramp).
    pub fn sup(&self) -> f64 {
        match self {
            History::Ramp { .. } => f64::INFINITY,
            History::Table { points } => points[points.len() - 1].1,
            History::Saturating { peak, .. } => *peak,
        }
    }

    /// Times in `(0, t_end)` where the history's formula changes (table knots).
    pub fn knots(&self, t_end: f64) -> Vec<f64> {
        match self {
            History::Table { points } => points
                .iter()
                .map(|p| p.0)
                .filter(|&t| t > 0.0 && t < t_end)
                .collect(),
            _ => Vec::new(),
        }
    }

    /// A one-line description, e.g. `ramp lambda = 1 t`.
    pub fn describe(&self) -> String {
        match self {
            History::Ramp { rate } => format!("ramp: lambda(t) = {rate} t"),
            History::Table { points } => format!(
                "table: piecewise linear through {} points, held at {} after t = {}",
                points.len(),
                points[points.len() - 1].1,
                points[points.len() - 1].0
            ),
            History::Saturating { peak, tau } => {
                format!("saturating: lambda(t) = {peak} (1 - exp(-t / {tau}))")
            }
        }
    }
}
