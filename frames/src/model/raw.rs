//! The scene file's tables as serde reads them (spans kept for the messages).

use super::*;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub(super) title: Option<String>,
    pub(super) model: Option<Spanned<String>>,
    #[serde(rename = "yield")]
    pub(super) yield_table: Option<Spanned<RawYield>>,
    #[serde(default)]
    pub(super) arc: Vec<Spanned<RawArc>>,
    #[serde(default)]
    pub(super) node: Vec<Spanned<RawNode>>,
    #[serde(default)]
    pub(super) member: Vec<Spanned<RawMember>>,
    #[serde(default)]
    pub(super) support: Vec<Spanned<RawSupport>>,
    #[serde(default)]
    pub(super) mass: Vec<Spanned<RawMass>>,
    #[serde(default)]
    pub(super) load: Vec<Spanned<RawLoad>>,
    pub(super) history: Option<Spanned<RawHistory>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
    #[serde(default)]
    pub(super) target: Vec<Spanned<RawTarget>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTarget {
    pub(super) node: Spanned<String>,
    pub(super) direction: Spanned<Vec<f64>>,
    pub(super) gap: Spanned<f64>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNode {
    pub(super) id: Spanned<String>,
    pub(super) x: Spanned<f64>,
    pub(super) y: Spanned<f64>,
    pub(super) z: Option<Spanned<f64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMember {
    pub(super) id: Spanned<String>,
    pub(super) from: Spanned<String>,
    pub(super) to: Spanned<String>,
    pub(super) plastic_moment: Spanned<f64>,
    pub(super) plastic_torque: Option<Spanned<f64>>,
    pub(super) plastic_axial: Option<Spanned<f64>>,
    pub(super) facets: Option<Spanned<i64>>,
    pub(super) elements: Option<Spanned<i64>>,
    pub(super) mass_per_length: Option<Spanned<f64>>,
    pub(super) orientation: Option<Spanned<Vec<f64>>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawYield {
    pub(super) facets: Option<Spanned<i64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawArc {
    pub(super) id: Spanned<String>,
    pub(super) centre: Spanned<Vec<f64>>,
    pub(super) radius: Spanned<f64>,
    pub(super) start_angle: Spanned<f64>,
    pub(super) end_angle: Spanned<f64>,
    pub(super) elements: Spanned<i64>,
    pub(super) from: Option<Spanned<String>>,
    pub(super) to: Option<Spanned<String>>,
    pub(super) plastic_moment: Spanned<f64>,
    pub(super) plastic_torque: Option<Spanned<f64>>,
    pub(super) plastic_axial: Option<Spanned<f64>>,
    pub(super) facets: Option<Spanned<i64>>,
    pub(super) mass_per_length: Option<Spanned<f64>>,
    pub(super) normal: Option<Spanned<Vec<f64>>>,
    pub(super) reference: Option<Spanned<Vec<f64>>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

impl RawArc {
    /// A space arc's centre, unit normal, in-plane axes and points, if its
    /// keys are valid (else the arc's own checks report them).
    pub(super) fn space_points(&self) -> Option<Vec<[f64; 3]>> {
        let c = self.centre.get_ref();
        if c.len() != 3 || c.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let n = match &self.normal {
            Some(n) => crate::space::unit_of(n.get_ref())?,
            None => [0.0, 0.0, 1.0],
        };
        let (r, a0, a1) = (
            *self.radius.get_ref(),
            *self.start_angle.get_ref(),
            *self.end_angle.get_ref(),
        );
        let k = usize::try_from(*self.elements.get_ref()).ok()?;
        if !(r > 0.0 && r.is_finite() && a0.is_finite() && a1.is_finite()) || k == 0 || k > 100_000
        {
            return None;
        }
        let reference = match &self.reference {
            Some(g) => Some(crate::space::unit_of(g.get_ref())?),
            None => None,
        };
        let axes = crate::space::arc_axes(n, reference)?;
        Some(
            (0..=k)
                .map(|i| {
                    crate::space::arc_point(
                        [c[0], c[1], c[2]],
                        r,
                        axes,
                        a0 + (a1 - a0) * i as f64 / k as f64,
                    )
                })
                .collect(),
        )
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSupport {
    pub(super) node: Spanned<String>,
    pub(super) fix: Spanned<Vec<Spanned<String>>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMass {
    pub(super) node: Spanned<String>,
    pub(super) m: Option<Spanned<f64>>,
    pub(super) j: Option<Spanned<f64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLoad {
    pub(super) node: Spanned<String>,
    pub(super) fx: Option<Spanned<f64>>,
    pub(super) fy: Option<Spanned<f64>>,
    pub(super) mz: Option<Spanned<f64>>,
    pub(super) fz: Option<Spanned<f64>>,
    pub(super) mx: Option<Spanned<f64>>,
    pub(super) my: Option<Spanned<f64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawHistory {
    pub(super) kind: Option<Spanned<String>>,
    pub(super) rate: Option<Spanned<f64>>,
    pub(super) points: Option<Spanned<Vec<Spanned<Vec<f64>>>>>,
    pub(super) peak: Option<Spanned<f64>>,
    pub(super) tau: Option<Spanned<f64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    pub(super) _comment: Option<IgnoredAny>,
}

impl RawLoad {
    /// The value given under a load key (`fx`, `fy`, `fz`, `mx`, `my`, `mz`).
    pub(super) fn key(&self, name: &str) -> Option<&Spanned<f64>> {
        match name {
            "fx" => self.fx.as_ref(),
            "fy" => self.fy.as_ref(),
            "fz" => self.fz.as_ref(),
            "mx" => self.mx.as_ref(),
            "my" => self.my.as_ref(),
            "mz" => self.mz.as_ref(),
            _ => None,
        }
    }
}
