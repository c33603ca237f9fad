//! Plots of what the paper's figures show, as SVG (plotters), with the numbers
//! beside them as CSV:
//!
//! | file | what | paper |
//! |---|---|---|
//! | `activation.svg/.csv` | hinges against `Lambda`: accelerating, rotating at constant rate, at yield | Fig. 1(c) |
//! | `profiles.svg/.csv` | the shape of the acceleration (velocity-increment) field in each interval | Fig. 1(b) |
//! | `moments.svg/.csv` | bending moment along the members at every critical `Lambda` | Fig. 2(a) |
//! | `displacements.svg/.csv` | nodal displacements (and velocities in the CSV) against time | Fig. 2(b) |
//! | `geometry.svg/.csv` | the frame in plan with the hinges numbered in their order of formation, with `Lambda` | |
//!
//! A grillage's acceleration field (out of the plane) is drawn in an oblique
//! view: plan coordinates `(x, y)` at `(x + 0.5 y, 0.5 y)` and `z` upward.
//!
//! **Space scenes** (the general model) are drawn in a projection ([`View`]):
//! chosen (`frames run --view xy|xz|yz|iso`) or automatic (the plane of the
//! nodes when they lie in a coordinate plane, else the isometric view from
//! `(1, 1, 1)`); the geometry and the profiles say which in their captions.
//! Their moment plot shows what a pipe engineer reads at each section: the
//! bending magnitude `sqrt(M2^2 + M3^2)` against `Mp` and the torque `T`
//! against `+-Tp` (the CSV adds `m2`, `bending` and `torque`).
//!
//! **Large scenes stay readable**: the moment plot draws at most
//! [`MAX_CURVES`] critical `Lambda` values (evenly sampled, the first and the
//! last among them; its CSV holds the same ones), the activation diagram at
//! most [`MAX_ROWS`] hinges (evenly sampled), the geometry's legend and
//! numbers the first [`MAX_LEGEND`] hinges, the profiles show 12 intervals;
//! each plot says so in its caption. Members are drawn as one polyline each,
//! the activation bars one per run of intervals in the same state. The CSVs
//! follow the plots where those sample: `moments.csv` and `profiles.csv` hold
//! the shown `Lambda` values and intervals, `displacements.csv` every node up
//! to [`MAX_CSV_NODES`], else the plotted ones.

use crate::analysis::Analysis;
use crate::error::FramesError;
use crate::hinge::section_name;
use crate::model::{Component, Model};
use crate::report::format_number as g;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// Most moment diagrams (critical `Lambda` values) in `moments.svg`.
pub const MAX_CURVES: usize = 12;
/// Most hinges (rows) in `activation.svg`.
pub const MAX_ROWS: usize = 60;
/// Most hinges in the legend (and numbered) in `geometry.svg`.
pub const MAX_LEGEND: usize = 20;
/// Most nodes in `displacements.csv` (beyond: the plotted ones only).
pub const MAX_CSV_NODES: usize = 200;

/// `count` indices of `0..n` evenly spread, the first and the last among
/// them (all of them when `n <= count`).
fn sample(n: usize, count: usize) -> Vec<usize> {
    if n <= count {
        return (0..n).collect();
    }
    let mut v: Vec<usize> = (0..count).map(|k| k * (n - 1) / (count - 1)).collect();
    v.dedup();
    v
}

/// How a space scene is projected on the page.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// The plane of the nodes when they lie in a coordinate plane (`x-y`,
    /// `x-z` or `y-z`), else [`View::Isometric`].
    #[default]
    Auto,
    /// Plan: `x` to the right, `y` up.
    Xy,
    /// Elevation: `x` to the right, `z` up.
    Xz,
    /// Elevation: `y` to the right, `z` up.
    Yz,
    /// Isometric from `(1, 1, 1)`: `z` up, `x` to the lower left, `y` to the lower right.
    Isometric,
}

impl View {
    /// Reads `auto`, `xy`, `xz`, `yz` or `iso`.
    pub fn parse(s: &str) -> Result<View, String> {
        match s {
            "auto" => Ok(View::Auto),
            "xy" => Ok(View::Xy),
            "xz" => Ok(View::Xz),
            "yz" => Ok(View::Yz),
            "iso" | "isometric" => Ok(View::Isometric),
            _ => Err(format!("unknown view \"{s}\" (auto, xy, xz, yz or iso)")),
        }
    }
}

/// A projection of space onto the page: `(right . p, up . p)`.
#[derive(Clone, Debug)]
struct Projection {
    right: [f64; 3],
    up: [f64; 3],
    name: &'static str,
}

impl Projection {
    fn of(view: View, fr: &crate::model::Frame) -> Projection {
        let view = match view {
            View::Auto => {
                let span = |f: fn(&crate::model::Node) -> f64| {
                    let (lo, hi) = fr.nodes.iter().fold((f64::MAX, f64::MIN), |(lo, hi), n| {
                        (lo.min(f(n)), hi.max(f(n)))
                    });
                    (hi - lo).max(0.0)
                };
                let (sx, sy, sz) = (span(|n| n.x), span(|n| n.y), span(|n| n.z));
                let tiny = 1e-12 * sx.max(sy).max(sz);
                if sz <= tiny {
                    View::Xy
                } else if sy <= tiny {
                    View::Xz
                } else if sx <= tiny {
                    View::Yz
                } else {
                    View::Isometric
                }
            }
            v => v,
        };
        let r = std::f64::consts::FRAC_1_SQRT_2;
        let u = 1.0 / 6f64.sqrt();
        match view {
            View::Xz => Projection {
                right: [1.0, 0.0, 0.0],
                up: [0.0, 0.0, 1.0],
                name: "elevation x-z (x right, z up)",
            },
            View::Yz => Projection {
                right: [0.0, 1.0, 0.0],
                up: [0.0, 0.0, 1.0],
                name: "elevation y-z (y right, z up)",
            },
            View::Isometric => Projection {
                right: [-r, r, 0.0],
                up: [-u, -u, 2.0 * u],
                name: "isometric view from (1, 1, 1) (z up, x lower left, y lower right)",
            },
            _ => Projection {
                right: [1.0, 0.0, 0.0],
                up: [0.0, 1.0, 0.0],
                name: "plan x-y (x right, y up)",
            },
        }
    }
    fn at(&self, p: [f64; 3]) -> (f64, f64) {
        let d = |v: [f64; 3]| v[0] * p[0] + v[1] * p[1] + v[2] * p[2];
        (d(self.right), d(self.up))
    }
    fn node(&self, n: &crate::model::Node) -> (f64, f64) {
        self.at([n.x, n.y, n.z])
    }
}

fn io(file: &Path, e: impl std::fmt::Display) -> FramesError {
    FramesError::Io {
        file: file.display().to_string(),
        message: format!("cannot write: {e}"),
    }
}

fn write(file: &Path, text: &str) -> Result<PathBuf, FramesError> {
    std::fs::write(file, text).map_err(|e| io(file, e))?;
    Ok(file.to_path_buf())
}

/// Writes every plot and its CSV into `dir` (created if needed); returns the files.
pub fn write_all(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    write_all_with(a, dir, View::Auto)
}

/// [`write_all`] with a chosen projection of a space scene (planar and
/// grillage scenes are drawn as always).
pub fn write_all_with(a: &Analysis, dir: &Path, view: View) -> Result<Vec<PathBuf>, FramesError> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut files = Vec::new();
    files.extend(activation(a, dir)?);
    files.extend(profiles(a, dir, view)?);
    files.extend(moments(a, dir)?);
    files.extend(displacements(a, dir)?);
    files.extend(geometry(a, dir, view)?);
    Ok(files)
}

fn lambda_end(a: &Analysis) -> f64 {
    let last = a
        .reading
        .breakpoints
        .last()
        .map(|b| b.lambda)
        .unwrap_or(1.0);
    let reached = a.solution.lambda_reached;
    let mut end = 1.25 * last.max(f64::MIN_POSITIVE);
    if a.solution.status != plcp::Status::UnboundedRay && reached.is_finite() && reached > 0.0 {
        end = end.min(reached);
    }
    end.max(last)
}

fn group_label(a: &Analysis, g: usize) -> String {
    let grp = &a.reading.groups[g];
    if grp.sections.len() > 1 {
        a.scene.frame.nodes[grp.node].id.clone()
    } else {
        let n = section_name(&a.scene.frame, &a.system, grp.sections[0]);
        format!("{} ({} {})", n.node, n.member, n.end.as_str())
    }
}

fn activation(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("activation.svg");
    let csv = dir.join("activation.csv");
    let end = lambda_end(a);
    // rows: groups in order of their first appearance
    let mut rows: Vec<usize> = Vec::new();
    for iv in &a.reading.intervals {
        for &g in iv
            .accelerating
            .iter()
            .chain(&iv.constant_rate)
            .chain(&iv.at_yield)
        {
            if !rows.contains(&g) {
                rows.push(g);
            }
        }
    }
    let mut text = String::from("lambda_from,lambda_to,hinge,state\n");
    let mut bars: Vec<(usize, f64, f64, u8)> = Vec::new();
    // the rows drawn: at most MAX_ROWS, evenly sampled (the CSV holds all)
    let total_rows = rows.len();
    let shown_rows = sample(total_rows, MAX_ROWS);
    let row_of: std::collections::HashMap<usize, usize> = shown_rows
        .iter()
        .enumerate()
        .map(|(k, &r)| (r, k))
        .collect();
    let mut last_bar: std::collections::HashMap<usize, usize> = Default::default();
    for iv in a.reading.intervals.iter().filter(|i| !i.rigid) {
        let to = iv.lambda_to.min(end);
        for (r, &grp) in rows.iter().enumerate() {
            let state = if iv.accelerating.contains(&grp) {
                Some((2, "accelerating"))
            } else if iv.constant_rate.contains(&grp) {
                Some((1, "constant_rate"))
            } else if iv.at_yield.contains(&grp) {
                Some((0, "at_yield"))
            } else {
                None
            };
            if let Some((k, name)) = state {
                if let Some(&shown) = row_of.get(&r) {
                    // one bar per run of intervals in the same state
                    match last_bar.get(&shown).map(|&b| &mut bars[b]) {
                        Some(b) if b.3 == k && b.2 == iv.lambda_from => b.2 = to,
                        _ => {
                            last_bar.insert(shown, bars.len());
                            bars.push((shown, iv.lambda_from, to, k));
                        }
                    }
                }
                let lt = if iv.lambda_to.is_finite() {
                    g(iv.lambda_to)
                } else {
                    "inf".into()
                };
                let _ = writeln!(
                    text,
                    "{},{},{},{}",
                    g(iv.lambda_from),
                    lt,
                    group_label(a, grp),
                    name
                );
            }
        }
    }
    let n = shown_rows.len().max(1);
    let height = (160 + 40 * n).min(1400) as u32;
    let caption = if total_rows > shown_rows.len() {
        format!(
            "Activation diagram: {} of {total_rows} hinges (sampled evenly; all in the CSV)",
            shown_rows.len()
        )
    } else {
        "Activation diagram: hinges against the load parameter".to_string()
    };
    {
        let root: Area = SVGBackend::new(&svg, (900, height)).into_drawing_area();
        let labels: Vec<String> = shown_rows
            .iter()
            .map(|&r| group_label(a, rows[r]))
            .collect();
        let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(caption, ("sans-serif", 20))
                .margin(15)
                .x_label_area_size(40)
                .y_label_area_size(150)
                .build_cartesian_2d(0.0..end, -0.5..(n as f64 - 0.5))?;
            chart
                .configure_mesh()
                .disable_y_mesh()
                .x_desc("Lambda")
                .y_labels(n)
                .y_label_formatter(&|y| {
                    let k = y.round();
                    if (y - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < labels.len() {
                        labels[k as usize].clone()
                    } else {
                        String::new()
                    }
                })
                .draw()?;
            let bps = &a.reading.breakpoints;
            for k in sample(bps.len(), 400) {
                let l = bps[k].lambda;
                chart.draw_series(LineSeries::new(
                    vec![(l, -0.5), (l, n as f64 - 0.5)],
                    BLACK.mix(0.3),
                ))?;
            }
            let styles = [
                (0.06, RGBColor(150, 150, 150)),
                (0.22, RGBColor(40, 90, 200)),
                (0.3, RGBColor(210, 40, 40)),
            ];
            for &(r, from, to, k) in &bars {
                let (hw, color) = styles[k as usize];
                let y = r as f64;
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(from, y - hw), (to, y + hw)],
                    color.filled(),
                )))?;
            }
            for (k, name) in [
                "at yield",
                "rotating at constant rate (x*_dd = 0)",
                "accelerating (x*_dd > 0)",
            ]
            .iter()
            .enumerate()
            {
                let (_, color) = styles[k];
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(0.0, -10.0), (0.0, -10.0)],
                        color.filled(),
                    )))?
                    .label(*name)
                    .legend(move |(x, y)| {
                        Rectangle::new([(x, y - 4), (x + 16, y + 4)], color.filled())
                    });
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()?;
            root.present()?;
            Ok(())
        };
        draw().map_err(|e| io(&svg, e))?;
    }
    Ok(vec![svg, write(&csv, &text)?])
}

fn profiles(a: &Analysis, dir: &Path, view_choice: View) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("profiles.svg");
    let csv = dir.join("profiles.csv");
    let fr = &a.scene.frame;
    let ivs: Vec<usize> = (0..a.reading.intervals.len())
        .filter(|&i| !a.reading.intervals[i].rigid)
        .collect();
    // at most 12 panels, evenly chosen
    let shown: Vec<usize> = if ivs.len() <= 12 {
        ivs.clone()
    } else {
        (0..12).map(|k| ivs[k * (ivs.len() - 1) / 11]).collect()
    };
    let grillage = fr.model == Model::Grillage;
    let space = fr.model == Model::Space;
    let proj = Projection::of(view_choice, fr);
    // a node to the drawing: as is (planar), oblique (grillage), projected (space)
    let view = |n: &crate::model::Node| -> (f64, f64) {
        if grillage {
            (n.x + 0.5 * n.y, 0.5 * n.y)
        } else if space {
            proj.node(n)
        } else {
            (n.x, n.y)
        }
    };
    let (xmin, xmax, ymin, ymax) =
        fr.nodes
            .iter()
            .fold((f64::MAX, f64::MIN, f64::MAX, f64::MIN), |b, n| {
                let (x, y) = view(n);
                (b.0.min(x), b.1.max(x), b.2.min(y), b.3.max(y))
            });
    let extent = (xmax - xmin).max(ymax - ymin).max(1e-12);
    let amp = 0.2 * extent;
    let (cx, cy) = (0.5 * (xmin + xmax), 0.5 * (ymin + ymax));
    let half = 0.5 * extent + 1.6 * amp;
    let comps = fr.model.components();
    let mut text = String::from("interval,lambda_from,lambda_to,lambda_shown,node,x,y");
    for c in comps {
        let _ = write!(text, ",shape_{}", c.as_str());
    }
    text.push('\n');
    // the CSV holds every interval for small scenes, the shown ones when sampled
    let listed: &[usize] = if ivs.len() <= 12 { &ivs } else { &shown };
    let mut shapes = Vec::new();
    for &i in listed {
        let iv = &a.reading.intervals[i];
        let r = &a.response.intervals[i];
        let l = a.solution.pieces[iv.piece]
            .representative()
            .max(iv.lambda_from);
        // the model's components in its order
        let acc: Vec<Vec<f64>> = r
            .accelerations
            .iter()
            .map(|a| {
                comps
                    .iter()
                    .map(|c| a[c.index()][0] + a[c.index()][1] * l)
                    .collect()
            })
            .collect();
        let norm = acc.iter().fold(0.0f64, |m, v| {
            m.max(if grillage {
                v[0].abs()
            } else if space {
                (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
            } else {
                v[0].hypot(v[1])
            })
        });
        let s = if norm > 0.0 { 1.0 / norm } else { 0.0 };
        let shape: Vec<Vec<f64>> = acc
            .iter()
            .map(|v| v.iter().map(|x| x * s).collect())
            .collect();
        for (k, n) in fr.nodes.iter().enumerate() {
            let lt = if iv.lambda_to.is_finite() {
                g(iv.lambda_to)
            } else {
                "inf".into()
            };
            let _ = write!(
                text,
                "{},{},{},{},{},{},{}",
                i,
                g(iv.lambda_from),
                lt,
                g(l),
                n.id,
                n.x,
                n.y
            );
            for v in &shape[k] {
                let _ = write!(text, ",{v}");
            }
            text.push('\n');
        }
        shapes.push((i, l, shape));
    }
    let panels = shown.len().max(1);
    let cols = panels.min(3);
    let rows_n = panels.div_ceil(cols);
    {
        let root: Area = SVGBackend::new(&svg, (320 * cols as u32 + 20, 300 * rows_n as u32 + 50))
            .into_drawing_area();
        let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let mut title = if space {
                format!(
                    "Shape of the acceleration field in each interval; {}",
                    proj.name
                )
            } else {
                "Shape of the acceleration field in each interval (velocity profiles grow in this shape)".to_string()
            };
            if ivs.len() > shown.len() {
                let _ = write!(
                    title,
                    " ({} of {} intervals, sampled evenly)",
                    shown.len(),
                    ivs.len()
                );
            }
            let root = root.titled(&title, ("sans-serif", 18))?;
            let areas = root.split_evenly((rows_n, cols));
            for (area, &i) in areas.iter().zip(&shown) {
                let Some((_, l, shape)) = shapes.iter().find(|s| s.0 == i) else {
                    continue;
                };
                let iv = &a.reading.intervals[i];
                let range = if iv.lambda_to.is_finite() {
                    format!("{} <= Lambda <= {}", g(iv.lambda_from), g(iv.lambda_to))
                } else {
                    format!("Lambda >= {}", g(iv.lambda_from))
                };
                let mut chart = ChartBuilder::on(area)
                    .caption(range, ("sans-serif", 14))
                    .margin(8)
                    .build_cartesian_2d((cx - half)..(cx + half), (cy - half)..(cy + half))?;
                // displaced position of a node in the drawing
                let moved = |i: usize| -> (f64, f64) {
                    let (n, s) = (&fr.nodes[i], &shape[i]);
                    let (x, y) = view(n);
                    if grillage {
                        (x, y + amp * s[0])
                    } else if space {
                        proj.at([n.x + amp * s[0], n.y + amp * s[1], n.z + amp * s[2]])
                    } else {
                        (x + amp * s[0], y + amp * s[1])
                    }
                };
                // one polyline per member (its node chain)
                for m in &fr.members {
                    chart.draw_series(LineSeries::new(
                        m.nodes.iter().map(|&i| view(&fr.nodes[i])),
                        RGBColor(170, 170, 170).stroke_width(2),
                    ))?;
                    chart.draw_series(LineSeries::new(
                        m.nodes.iter().map(|&i| moved(i)),
                        RGBColor(20, 20, 20).stroke_width(2),
                    ))?;
                }
                for n in &fr.nodes {
                    if n.fixed.iter().any(|&f| f) {
                        chart.draw_series(std::iter::once(TriangleMarker::new(
                            view(n),
                            7,
                            BLACK.filled(),
                        )))?;
                    }
                }
                for (set, color) in [
                    (&iv.accelerating, RGBColor(210, 40, 40)),
                    (&iv.constant_rate, RGBColor(40, 90, 200)),
                ] {
                    for &gi in set.iter() {
                        let node = a.reading.groups[gi].node;
                        chart.draw_series(std::iter::once(Circle::new(
                            moved(node),
                            5,
                            color.filled(),
                        )))?;
                    }
                }
                let _ = l;
            }
            root.present()?;
            Ok(())
        };
        draw().map_err(|e| io(&svg, e))?;
    }
    Ok(vec![svg, write(&csv, &text)?])
}

/// One curve per shown `Lambda`, one polyline per member: `(Lambda, polylines)`.
type Curves = Vec<(f64, Vec<Vec<(f64, f64)>>)>;

/// A chart of curves along the members (arc length) with horizontal levels.
#[allow(clippy::too_many_arguments)]
fn member_panel(
    area: &Area,
    caption: &str,
    y_desc: &str,
    x_desc: &str,
    (total, lo, hi): (f64, f64, f64),
    levels: &[f64],
    offsets: &[f64],
    curves: &Curves,
) -> Result<(), Box<dyn std::error::Error>> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..total.max(1e-12), lo..hi)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()?;
    for &y in levels {
        chart.draw_series(LineSeries::new(vec![(0.0, y), (total, y)], BLACK.mix(0.4)))?;
    }
    for &o in offsets.iter().skip(1) {
        chart.draw_series(LineSeries::new(vec![(o, lo), (o, hi)], BLACK.mix(0.15)))?;
    }
    for (k, (l, per_member)) in curves.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        for (mi, pts) in per_member.iter().enumerate() {
            let s = chart.draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?;
            if mi == 0 {
                s.label(format!("Lambda = {}", g(*l)))
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                    });
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

/// The bending moment diagrams at the critical `Lambda` values (at most
/// [`MAX_CURVES`], evenly sampled); a space scene's as the bending magnitude
/// `sqrt(M2^2 + M3^2)` and the torque of each section.
fn moments(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("moments.svg");
    let csv = dir.join("moments.csv");
    let fr = &a.scene.frame;
    let sys = &a.system;
    let space = fr.model == Model::Space;
    let mut text = String::from(if space {
        "lambda,member,node,end,s,moment,m2,bending,torque\n"
    } else {
        "lambda,member,node,end,s,moment\n"
    });
    // abscissa: arc length, member after member
    let mut offsets = Vec::new();
    let mut total = 0.0;
    for m in &fr.members {
        offsets.push(total);
        total += m
            .elements
            .clone()
            .map(|e| fr.elements[e].length)
            .sum::<f64>();
    }
    let mp = fr
        .elements
        .iter()
        .fold(0.0f64, |m, e| m.max(e.plastic_moment));
    let tp = fr.elements.iter().fold(0.0f64, |m, e| {
        m.max(e.interaction.map_or(0.0, |i| i.capacity))
    });
    let diagrams = &a.response.moments_at_breakpoints;
    let shown = sample(diagrams.len(), MAX_CURVES);
    // space: the positions in u of each section's M2 and each element's torque
    let nb = sys.coordinates.len();
    let (mut pos2, mut post) = (
        vec![None; sys.sections.len()],
        vec![None; fr.elements.len()],
    );
    if space {
        for (r, f) in sys.forces.iter().enumerate() {
            match *f {
                crate::assemble::MemberForce::Moment2(k) => pos2[k] = Some(nb + r),
                crate::assemble::MemberForce::Torque(e) => post[e] = Some(nb + r),
                _ => {}
            }
        }
    }
    let intervals: Vec<&crate::hinge::Interval> =
        a.reading.intervals.iter().filter(|i| !i.rigid).collect();
    let (mut bending, mut torque): (Curves, Curves) = (Vec::new(), Vec::new());
    let (mut blo, mut bhi) = (-1.15 * mp, 1.15 * mp);
    for &j in &shown {
        let d = &diagrams[j];
        // space: u at the breakpoint, on the piece that starts there
        let u = match (space, intervals.get(j)) {
            (true, Some(iv)) => Some(a.solution.pieces[iv.piece_at(d.lambda)].u(d.lambda)),
            _ => None,
        };
        let (mut per_b, mut per_t) = (Vec::new(), Vec::new());
        for (mi, m) in fr.members.iter().enumerate() {
            let (mut pb, mut pt) = (Vec::new(), Vec::new());
            let mut s = 0.0;
            for e in m.elements.clone() {
                let el = &fr.elements[e];
                for (k, node, ds) in [(2 * e, el.from, 0.0), (2 * e + 1, el.to, el.length)] {
                    let end = if k % 2 == 0 { "from" } else { "to" };
                    let _ = write!(
                        text,
                        "{},{},{},{},{},{}",
                        g(d.lambda),
                        m.id,
                        fr.nodes[node].id,
                        end,
                        s + ds,
                        d.moments[k]
                    );
                    match &u {
                        Some(u) => {
                            let m2 = pos2[k].map_or(0.0, |r| u[r]);
                            let t = post[e].map_or(0.0, |r| u[r]);
                            let b = m2.hypot(d.moments[k]);
                            let _ = write!(text, ",{m2},{b},{t}");
                            pb.push((offsets[mi] + s + ds, b));
                            pt.push((offsets[mi] + s + ds, t));
                        }
                        None => pb.push((offsets[mi] + s + ds, d.moments[k])),
                    }
                    text.push('\n');
                }
                s += el.length;
            }
            per_b.push(pb);
            per_t.push(pt);
        }
        bending.push((d.lambda, per_b));
        torque.push((d.lambda, per_t));
    }
    if space {
        blo = 0.0;
        bhi = 1.15 * mp;
    }
    let sampled = if diagrams.len() > shown.len() {
        format!(
            " ({} of {} critical Lambda values, sampled evenly)",
            shown.len(),
            diagrams.len()
        )
    } else {
        String::new()
    };
    let x_desc = if fr.members.len() > 1 {
        "arc length along the members, in scene order"
    } else {
        "distance from the member's start"
    };
    {
        let height = if space { 900 } else { 520 };
        let root: Area = SVGBackend::new(&svg, (900, height)).into_drawing_area();
        let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            if space {
                let (top, bottom) = root.split_vertically(height / 2);
                member_panel(
                    &top,
                    &format!("Bending moment sqrt(M2^2 + M3^2) at each critical Lambda{sampled}"),
                    "bending moment",
                    x_desc,
                    (total, blo, bhi),
                    &[mp],
                    &offsets,
                    &bending,
                )
                .map_err(|e| e.to_string())?;
                let th = 1.15 * tp.max(1e-300);
                member_panel(
                    &bottom,
                    "Torque T of each section (right-handed about the member)",
                    "torque",
                    x_desc,
                    (total, -th, th),
                    &[tp, -tp],
                    &offsets,
                    &torque,
                )
                .map_err(|e| e.to_string())?;
            } else {
                member_panel(
                    &root,
                    &format!("Bending moment at each critical Lambda (sagging positive){sampled}"),
                    "bending moment",
                    x_desc,
                    (total, blo, bhi),
                    &[mp, -mp],
                    &offsets,
                    &bending,
                )
                .map_err(|e| e.to_string())?;
            }
            root.present()?;
            Ok(())
        };
        draw().map_err(|e| io(&svg, e))?;
    }
    Ok(vec![svg, write(&csv, &text)?])
}

fn displacements(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("displacements.svg");
    let csv = dir.join("displacements.csv");
    let fr = &a.scene.frame;
    let t = &a.response.time;
    let nt = t.times.len();
    // curves: (node, component) that move, largest first, at most 10
    let mut cand: Vec<(usize, Component, f64)> = Vec::new();
    let translations: &[Component] = match fr.model {
        Model::Planar => &[Component::X, Component::Y],
        Model::Grillage => &[Component::Z],
        Model::Space => &[Component::X, Component::Y, Component::Z],
    };
    for (i, n) in fr.nodes.iter().enumerate() {
        for &c in translations {
            let m = t
                .displacement
                .iter()
                .fold(0.0f64, |m, row| m.max(row[i][c.index()].abs()));
            if m > 0.0 && (n.mass > 0.0 || !n.generated) {
                cand.push((i, c, m));
            }
        }
    }
    let gmax = cand.iter().fold(0.0f64, |m, c| m.max(c.2));
    cand.retain(|c| c.2 > 1e-9 * gmax);
    cand.sort_by(|x, y| y.2.total_cmp(&x.2));
    cand.truncate(10);
    cand.sort_by_key(|c| (c.0, c.1));
    // the CSV's nodes: all of them up to MAX_CSV_NODES, else the plotted ones
    let csv_nodes: Vec<usize> = if fr.nodes.len() <= MAX_CSV_NODES {
        (0..fr.nodes.len()).collect()
    } else {
        let mut v: Vec<usize> = cand.iter().map(|c| c.0).collect();
        v.dedup();
        v
    };
    let mut header = String::from("t,lambda");
    for prefix in ["u", "v"] {
        for &i in &csv_nodes {
            for c in fr.model.components() {
                let _ = write!(header, ",{prefix}_{}.{}", fr.nodes[i].id, c.as_str());
            }
        }
    }
    let mut text = header + "\n";
    for k in 0..nt {
        let _ = write!(text, "{},{}", t.times[k], t.lambda[k]);
        for row in [&t.displacement[k], &t.velocity[k]] {
            for &i in &csv_nodes {
                for c in fr.model.components() {
                    let _ = write!(text, ",{}", row[i][c.index()]);
                }
            }
        }
        text.push('\n');
    }
    let t_end = t.times.last().copied().unwrap_or(1.0).max(1e-12);
    let (lo, hi) = cand.iter().fold((0.0f64, 0.0f64), |(lo, hi), &(i, c, _)| {
        t.displacement.iter().fold((lo, hi), |(lo, hi), row| {
            (lo.min(row[i][c.index()]), hi.max(row[i][c.index()]))
        })
    });
    let pad = 0.05 * (hi - lo).max(1e-12);
    {
        let root: Area = SVGBackend::new(&svg, (900, 520)).into_drawing_area();
        let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(
                    format!(
                        "Nodal displacements against time ({})",
                        t.history.describe()
                    ),
                    ("sans-serif", 18),
                )
                .margin(15)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..t_end, (lo - pad)..(hi + pad))?;
            chart
                .configure_mesh()
                .x_desc("t")
                .y_desc("displacement")
                .draw()?;
            for b in &a.reading.breakpoints {
                if let Some(tb) = t.history.time_at(b.lambda) {
                    if tb <= t_end {
                        chart.draw_series(LineSeries::new(
                            vec![(tb, lo - pad), (tb, hi + pad)],
                            BLACK.mix(0.2),
                        ))?;
                    }
                }
            }
            for (k, &(i, c, _)) in cand.iter().enumerate() {
                let color = Palette99::pick(k).to_rgba();
                let pts: Vec<(f64, f64)> = (0..nt)
                    .map(|j| (t.times[j], t.displacement[j][i][c.index()]))
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)))?
                    .label(format!("{} {}", fr.nodes[i].id, c.as_str()))
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                    });
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()?;
            root.present()?;
            Ok(())
        };
        draw().map_err(|e| io(&svg, e))?;
    }
    Ok(vec![svg, write(&csv, &text)?])
}

/// The frame in plan, supports as triangles, the hinges as circles numbered
/// in their order of formation (ties at a node share a number), with the
/// `Lambda` at which each formed in the legend and the CSV.
fn geometry(a: &Analysis, dir: &Path, view: View) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("geometry.svg");
    let csv = dir.join("geometry.csv");
    let fr = &a.scene.frame;
    let space = fr.model == Model::Space;
    let proj = Projection::of(view, fr);
    // a node on the page: plan (planar, grillage), projected (space)
    let at = |n: &crate::model::Node| -> (f64, f64) {
        if space {
            proj.node(n)
        } else {
            (n.x, n.y)
        }
    };
    let mut text = String::from(if space {
        "order,lambda,node,x,y,z,hinge\n"
    } else {
        "order,lambda,node,x,y,hinge\n"
    });
    for (k, h) in a.reading.hinges.iter().enumerate() {
        let n = &fr.nodes[h.node];
        let z = if space {
            format!("{},", n.z)
        } else {
            String::new()
        };
        let _ = writeln!(
            text,
            "{},{},{},{},{},{}{}",
            k + 1,
            g(h.lambda),
            n.id,
            n.x,
            n.y,
            z,
            group_label(a, h.group)
        );
    }
    let (xmin, xmax, ymin, ymax) =
        fr.nodes
            .iter()
            .fold((f64::MAX, f64::MIN, f64::MAX, f64::MIN), |b, n| {
                let (x, y) = at(n);
                (b.0.min(x), b.1.max(x), b.2.min(y), b.3.max(y))
            });
    let extent = (xmax - xmin).max(ymax - ymin).max(1e-12);
    let (cx, cy) = (0.5 * (xmin + xmax), 0.5 * (ymin + ymax));
    let half = 0.62 * extent;
    let hinges = a.reading.hinges.len();
    let legend = hinges.min(MAX_LEGEND);
    let mut caption = format!(
        "{} ({}): hinges in order of formation",
        if fr.title.is_empty() {
            "frame"
        } else {
            &fr.title
        },
        fr.model.as_str()
    );
    if hinges > legend {
        let _ = write!(caption, " (numbered: the first {legend} of {hinges})");
    }
    {
        let root: Area = SVGBackend::new(&svg, (760, 640)).into_drawing_area();
        let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(caption, ("sans-serif", 16))
                .margin(15)
                .x_label_area_size(30)
                .y_label_area_size(40)
                .build_cartesian_2d((cx - half)..(cx + half), (cy - half)..(cy + half))?;
            if space {
                chart
                    .configure_mesh()
                    .disable_mesh()
                    .x_labels(0)
                    .y_labels(0)
                    .x_desc(proj.name)
                    .draw()?;
                // the global axes at the lower left corner
                let o = (cx - 0.85 * half, cy - 0.85 * half);
                for (v, name) in [
                    ([1.0, 0.0, 0.0], "x"),
                    ([0.0, 1.0, 0.0], "y"),
                    ([0.0, 0.0, 1.0], "z"),
                ] {
                    let (dx, dy) = proj.at(v);
                    if dx.hypot(dy) < 1e-9 {
                        continue; // along the line of sight
                    }
                    let tip = (o.0 + 0.12 * half * dx, o.1 + 0.12 * half * dy);
                    chart.draw_series(LineSeries::new(vec![o, tip], BLUE.stroke_width(2)))?;
                    chart.draw_series(std::iter::once(Text::new(
                        name,
                        tip,
                        ("sans-serif", 14).into_font().color(&BLUE),
                    )))?;
                }
            } else {
                chart.configure_mesh().x_desc("x").y_desc("y").draw()?;
            }
            // one polyline per member (its node chain)
            for m in &fr.members {
                chart.draw_series(LineSeries::new(
                    m.nodes.iter().map(|&i| at(&fr.nodes[i])),
                    RGBColor(60, 60, 60).stroke_width(3),
                ))?;
            }
            for n in &fr.nodes {
                if n.fixed.iter().any(|&f| f) {
                    chart.draw_series(std::iter::once(TriangleMarker::new(
                        at(n),
                        9,
                        BLACK.filled(),
                    )))?;
                }
                if n.load.iter().any(|&l| l != 0.0) {
                    chart.draw_series(std::iter::once(Cross::new(
                        at(n),
                        8,
                        RGBColor(40, 140, 40).stroke_width(3),
                    )))?;
                }
            }
            // several hinges at one node: offset the labels
            let mut at_node: std::collections::HashMap<usize, usize> = Default::default();
            for (k, h) in a.reading.hinges.iter().enumerate() {
                let n = &fr.nodes[h.node];
                let (x, y) = at(n);
                let color = Palette99::pick(k).to_rgba();
                let series =
                    chart.draw_series(std::iter::once(Circle::new((x, y), 7, color.filled())))?;
                if k >= legend {
                    continue;
                }
                let dup = at_node.entry(h.node).or_insert(0);
                let off = 0.035 * extent * *dup as f64;
                *dup += 1;
                series
                    .label(format!(
                        "{}: {} at Lambda = {}",
                        k + 1,
                        group_label(a, h.group),
                        g(h.lambda)
                    ))
                    .legend(move |(x, y)| Circle::new((x + 8, y), 5, color.filled()));
                chart.draw_series(std::iter::once(Text::new(
                    format!("{}", k + 1),
                    (x + 0.02 * extent, y + 0.02 * extent + off),
                    ("sans-serif", 16).into_font().color(&BLACK),
                )))?;
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 11))
                .draw()?;
            root.present()?;
            Ok(())
        };
        draw().map_err(|e| io(&svg, e))?;
    }
    Ok(vec![svg, write(&csv, &text)?])
}
