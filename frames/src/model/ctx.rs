//! Reading context: checked numbers with the file, line and key in the
//! message; member strengths; generated nodes and members.

use super::*;

/// 1-based line of a byte offset.
pub(super) fn line_of(src: &str, offset: usize) -> usize {
    let end = offset.min(src.len());
    src.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

pub(super) struct Ctx<'a> {
    pub(super) src: &'a str,
    pub(super) file: &'a str,
}

impl Ctx<'_> {
    pub(super) fn err<T>(
        &self,
        span: core::ops::Range<usize>,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> Result<T, FramesError> {
        Err(FramesError::Scene {
            file: self.file.to_string(),
            line: line_of(self.src, span.start),
            key: key.into(),
            message: message.into(),
        })
    }
    pub(super) fn finite(
        &self,
        v: &Spanned<f64>,
        key: impl Into<String>,
    ) -> Result<f64, FramesError> {
        let x = *v.get_ref();
        if !x.is_finite() {
            self.err(v.span(), key, format!("must be a finite number, got {x}"))
        } else if x.abs() > 1e100 {
            // products of such numbers overflow in the solver
            self.err(
                v.span(),
                key,
                format!("{x:e} is out of range (at most 1e100 in magnitude)"),
            )
        } else {
            Ok(x)
        }
    }
    pub(super) fn positive(
        &self,
        v: &Spanned<f64>,
        key: impl Into<String>,
    ) -> Result<f64, FramesError> {
        let key = key.into();
        let x = self.finite(v, key.clone())?;
        if x > 0.0 {
            Ok(x)
        } else {
            self.err(v.span(), key, format!("must be positive, got {x}"))
        }
    }
    pub(super) fn nonnegative(
        &self,
        v: &Spanned<f64>,
        key: impl Into<String>,
    ) -> Result<f64, FramesError> {
        let key = key.into();
        let x = self.finite(v, key.clone())?;
        if x >= 0.0 {
            Ok(x)
        } else {
            self.err(v.span(), key, format!("must not be negative, got {x}"))
        }
    }
}

/// The strength keys of a member or an arc.
pub(super) struct Keys<'a> {
    pub(super) plastic_moment: &'a Spanned<f64>,
    pub(super) plastic_torque: Option<&'a Spanned<f64>>,
    pub(super) plastic_axial: Option<&'a Spanned<f64>>,
    pub(super) facets: Option<&'a Spanned<i64>>,
    pub(super) mass_per_length: Option<&'a Spanned<f64>>,
}

impl Keys<'_> {
    /// The capacity given under `key` (`plastic_axial` or `plastic_torque`).
    pub(super) fn capacity(&self, key: &str) -> Option<&Spanned<f64>> {
        match key {
            "plastic_axial" => self.plastic_axial,
            "plastic_torque" => self.plastic_torque,
            _ => None,
        }
    }
}

impl Ctx<'_> {
    pub(super) fn facets(&self, v: &Spanned<i64>, key: &str) -> Result<usize, FramesError> {
        let k = *v.get_ref();
        let ku = usize::try_from(k).unwrap_or(0);
        match Polygon::new(Curve::BendingTorsion, ku) {
            Ok(_) => Ok(ku),
            Err(_) => self.err(
                v.span(),
                key,
                format!("must be a multiple of 4 from 4 to 256 (4, 8, 16, 32, ...), got {k}"),
            ),
        }
    }

    /// The strength keys of a space scene's member or arc (`what`: "a
    /// member", "an arc") for the model it is solved as: `plastic_torque`
    /// required (a pipe); a reduced model's other capacity is not an unknown
    /// (planar: no torque, and without `plastic_axial` the polyhedron's
    /// cross-section at `T = N = 0` is `+-Mp`, no facets; grillage: no axial force).
    pub(super) fn space_keys<'k>(
        &self,
        model: Model,
        table: &str,
        what: &str,
        id: &Spanned<String>,
        mut keys: Keys<'k>,
    ) -> Result<Keys<'k>, FramesError> {
        let Some(tp) = keys.plastic_torque else {
            return self.err(
                id.span(),
                format!("{table} plastic_torque"),
                format!("{what} of a space scene needs plastic_torque (the plastic torque Tp of the pipe)"),
            );
        };
        self.positive(tp, format!("{table} plastic_torque"))?;
        match model {
            Model::Planar => {
                keys.plastic_torque = None;
                if keys.plastic_axial.is_none() {
                    keys.facets = None;
                }
            }
            Model::Grillage => keys.plastic_axial = None,
            Model::Space => {}
        }
        Ok(keys)
    }

    pub(super) fn element_count(&self, v: &Spanned<i64>, key: &str) -> Result<usize, FramesError> {
        let n = *v.get_ref();
        if !(1..=100_000).contains(&n) {
            return self.err(
                v.span(),
                key,
                format!("must be an integer from 1 to 100000, got {n}"),
            );
        }
        Ok(n as usize)
    }

    /// `(Mp, interaction, mass per length)` of a member or arc, checked against the model.
    pub(super) fn strength(
        &self,
        model: Model,
        table: &str,
        id: &Spanned<String>,
        k: Keys<'_>,
        default_facets: usize,
    ) -> Result<(f64, Option<Interaction>, f64), FramesError> {
        let mp = self.positive(k.plastic_moment, format!("{table} plastic_moment"))?;
        let mu = match k.mass_per_length {
            Some(v) => self.nonnegative(v, format!("{table} mass_per_length"))?,
            None => 0.0,
        };
        let facets = match k.facets {
            Some(f) => Some(self.facets(f, &format!("{table} facets"))?),
            None => None,
        };
        let rule = model.second_force_rule();
        let (own, foreign) = (k.capacity(rule.key), k.capacity(rule.foreign_key));
        if let Some(v) = foreign {
            return self.err(
                v.span(),
                format!("{table} {}", rule.foreign_key),
                rule.foreign_message,
            );
        }
        let interaction = match own {
            Some(v) => Some(Interaction {
                curve: rule.curve,
                capacity: self.positive(v, format!("{table} {}", rule.key))?,
                facets: facets.unwrap_or(default_facets),
                axial: match rule.third_key.and_then(|key| k.capacity(key)) {
                    Some(np) => Some(self.positive(np, format!("{table} plastic_axial"))?),
                    None => None,
                },
            }),
            None if rule.required => {
                return self.err(
                    id.span(),
                    format!("{table} {}", rule.key),
                    rule.required_message,
                );
            }
            None => {
                if let Some(f) = k.facets {
                    return self.err(f.span(), format!("{table} facets"), rule.facets_message);
                }
                None
            }
        };
        if let Some(it) = interaction.filter(|it| it.axial.is_some() && it.facets > 64) {
            return self.err(
                k.facets.map_or(id.span(), |f| f.span()),
                format!("{table} facets"),
                format!(
                    "with plastic_axial the general space model's polytope takes at most 64 longitudes (about k^3 / 2 facets per section), got {}",
                    it.facets
                ),
            );
        }
        Ok((mp, interaction, mu))
    }

    /// Adds a generated node, refusing an id that is taken.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn generate_node(
        &self,
        frame: &mut Frame,
        ids: &mut HashMap<String, usize>,
        gid: String,
        (x, y, z): (f64, f64, f64),
        generated: bool,
        span: core::ops::Range<usize>,
        key: &str,
    ) -> Result<usize, FramesError> {
        if ids.contains_key(&gid) {
            return self.err(
                span,
                key,
                format!("generated node id \"{gid}\" is already taken"),
            );
        }
        let i = frame.nodes.len();
        ids.insert(gid.clone(), i);
        frame.nodes.push(Node {
            id: gid,
            x,
            y,
            z,
            fixed: [false; 6],
            mass: 0.0,
            inertia: 0.0,
            load: [0.0; 6],
            generated,
        });
        Ok(i)
    }
}

/// Adds a member over a chain of nodes, one element per link with its
/// `(length, cos, sin)` (and its axes: none given for the planar axes of
/// `(cos, sin)`), lumping `mu h / 2` to each element end.
#[allow(clippy::too_many_arguments)]
pub(super) fn push_member(
    frame: &mut Frame,
    id: String,
    chain: Vec<usize>,
    dirs: &[(f64, f64, f64)],
    axes: &[[[f64; 3]; 3]],
    mp: f64,
    interaction: Option<Interaction>,
    mu: f64,
) {
    let mi = frame.members.len();
    let first = frame.elements.len();
    for (k, (w, &(h, c, s))) in chain.windows(2).zip(dirs).enumerate() {
        frame.elements.push(Element {
            member: mi,
            from: w[0],
            to: w[1],
            length: h,
            cos: c,
            sin: s,
            plastic_moment: mp,
            interaction,
            axes: axes
                .get(k)
                .copied()
                .unwrap_or([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]),
        });
        let lump = 0.5 * mu * h;
        frame.nodes[w[0]].mass += lump;
        frame.nodes[w[1]].mass += lump;
    }
    frame.members.push(Member {
        id,
        from: chain[0],
        to: chain[chain.len() - 1],
        plastic_moment: mp,
        interaction,
        mass_per_length: mu,
        nodes: chain,
        elements: first..frame.elements.len(),
    });
}

/// 1-based column, in characters, of a byte offset on its line.
pub(super) fn column_of(src: &str, offset: usize) -> usize {
    let mut end = offset.min(src.len());
    while !src.is_char_boundary(end) {
        end -= 1;
    }
    let start = src[..end].rfind('\n').map_or(0, |i| i + 1);
    src[start..end].chars().count() + 1
}

/// Turns a toml syntax or type error into one line with file, line, column
/// and key; an unknown key's message lists the keys its table accepts.
pub(super) fn toml_error(src: &str, file: &str, e: toml::de::Error) -> FramesError {
    let first = e.message().lines().next().unwrap_or("invalid TOML").trim();
    if let (Some(span), Some(rest)) = (e.span(), first.strip_prefix("unknown field `")) {
        let key = rest.split('`').next().unwrap_or("").to_string();
        // serde lists them as "expected one of `a`, `b`" or "expected `a` or `b`"
        let accepted = rest
            .split_once(", expected one of ")
            .or_else(|| rest.split_once(", expected "))
            .map_or("none", |(_, list)| list);
        return FramesError::Syntax {
            file: file.to_string(),
            line: line_of(src, span.start),
            column: column_of(src, span.start),
            message: format!(
                "unknown key \"{key}\": the accepted keys are {accepted} (a typo would change the scene silently; annotate with # or a comment key)"
            ),
            key,
        };
    }
    let Some(span) = e.span() else {
        return FramesError::Scene {
            file: file.to_string(),
            line: 0,
            key: "(syntax)".to_string(),
            message: first.to_string(),
        };
    };
    let text = src.get(span.clone()).unwrap_or("").trim();
    let key = if !text.is_empty()
        && text.len() <= 40
        && text
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.')
    {
        text.to_string()
    } else {
        // the key is the word before '=' on that line, if any
        let l = line_of(src, span.start);
        src.lines()
            .nth(l - 1)
            .and_then(|s| s.split_once('='))
            .map(|(k, _)| k.trim().to_string())
            .filter(|k| !k.is_empty())
            .unwrap_or_else(|| "(syntax)".to_string())
    };
    FramesError::Syntax {
        file: file.to_string(),
        line: line_of(src, span.start),
        column: column_of(src, span.start),
        key,
        message: first.to_string(),
    }
}
