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
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut files = Vec::new();
    files.extend(activation(a, dir)?);
    files.extend(profiles(a, dir)?);
    files.extend(moments(a, dir)?);
    files.extend(displacements(a, dir)?);
    files.extend(geometry(a, dir)?);
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
                bars.push((r, iv.lambda_from, to, k));
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
    let n = rows.len().max(1);
    let height = (160 + 40 * n).min(1400) as u32;
    {
        let root: Area = SVGBackend::new(&svg, (900, height)).into_drawing_area();
        let labels: Vec<String> = rows.iter().map(|&g| group_label(a, g)).collect();
        let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(
                    "Activation diagram: hinges against the load parameter",
                    ("sans-serif", 20),
                )
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
            for b in &a.reading.breakpoints {
                chart.draw_series(LineSeries::new(
                    vec![(b.lambda, -0.5), (b.lambda, n as f64 - 0.5)],
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

fn profiles(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
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
    // plan (x, y) to the drawing: as is (planar), oblique (grillage)
    let view = |x: f64, y: f64| -> (f64, f64) {
        if grillage {
            (x + 0.5 * y, 0.5 * y)
        } else {
            (x, y)
        }
    };
    let (xmin, xmax, ymin, ymax) =
        fr.nodes
            .iter()
            .fold((f64::MAX, f64::MIN, f64::MAX, f64::MIN), |b, n| {
                let (x, y) = view(n.x, n.y);
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
    let mut shapes = Vec::new();
    for &i in &ivs {
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
            let root = root.titled("Shape of the acceleration field in each interval (velocity profiles grow in this shape)", ("sans-serif", 18))?;
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
                    let (x, y) = view(n.x, n.y);
                    if grillage {
                        (x, y + amp * s[0])
                    } else {
                        (x + amp * s[0], y + amp * s[1])
                    }
                };
                for e in &fr.elements {
                    let (p, q) = (&fr.nodes[e.from], &fr.nodes[e.to]);
                    chart.draw_series(LineSeries::new(
                        vec![view(p.x, p.y), view(q.x, q.y)],
                        RGBColor(170, 170, 170).stroke_width(2),
                    ))?;
                    chart.draw_series(LineSeries::new(
                        vec![moved(e.from), moved(e.to)],
                        RGBColor(20, 20, 20).stroke_width(2),
                    ))?;
                }
                for n in &fr.nodes {
                    if n.fixed.iter().any(|&f| f) {
                        chart.draw_series(std::iter::once(TriangleMarker::new(
                            view(n.x, n.y),
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

fn moments(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("moments.svg");
    let csv = dir.join("moments.csv");
    let fr = &a.scene.frame;
    let mut text = String::from("lambda,member,node,end,s,moment\n");
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
    let diagrams = &a.response.moments_at_breakpoints;
    type Polyline = Vec<(f64, f64)>;
    let mut curves: Vec<(f64, Vec<Polyline>)> = Vec::new();
    for d in diagrams {
        let mut per_member = Vec::new();
        for (mi, m) in fr.members.iter().enumerate() {
            let mut pts = Vec::new();
            let mut s = 0.0;
            for e in m.elements.clone() {
                let el = &fr.elements[e];
                for (k, node, ds) in [(2 * e, el.from, 0.0), (2 * e + 1, el.to, el.length)] {
                    pts.push((offsets[mi] + s + ds, d.moments[k]));
                    let end = if k % 2 == 0 { "from" } else { "to" };
                    let _ = writeln!(
                        text,
                        "{},{},{},{},{},{}",
                        g(d.lambda),
                        m.id,
                        fr.nodes[node].id,
                        end,
                        s + ds,
                        d.moments[k]
                    );
                }
                s += el.length;
            }
            per_member.push(pts);
        }
        curves.push((d.lambda, per_member));
    }
    {
        let root: Area = SVGBackend::new(&svg, (900, 520)).into_drawing_area();
        let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(
                    "Bending moment at each critical Lambda (sagging positive)",
                    ("sans-serif", 20),
                )
                .margin(15)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(0.0..total.max(1e-12), (-1.15 * mp)..(1.15 * mp))?;
            chart
                .configure_mesh()
                .x_desc(if fr.members.len() > 1 {
                    "arc length along the members, in scene order"
                } else {
                    "distance from the member's start"
                })
                .y_desc("bending moment")
                .draw()?;
            for y in [mp, -mp] {
                chart.draw_series(LineSeries::new(vec![(0.0, y), (total, y)], BLACK.mix(0.4)))?;
            }
            for &o in offsets.iter().skip(1) {
                chart.draw_series(LineSeries::new(
                    vec![(o, -1.15 * mp), (o, 1.15 * mp)],
                    BLACK.mix(0.15),
                ))?;
            }
            for (k, (l, per_member)) in curves.iter().enumerate() {
                let color = Palette99::pick(k).to_rgba();
                for (mi, pts) in per_member.iter().enumerate() {
                    let s =
                        chart.draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?;
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
    let mut header = String::from("t,lambda");
    for n in &fr.nodes {
        for c in fr.model.components() {
            let _ = write!(header, ",u_{}.{}", n.id, c.as_str());
        }
    }
    for n in &fr.nodes {
        for c in fr.model.components() {
            let _ = write!(header, ",v_{}.{}", n.id, c.as_str());
        }
    }
    let mut text = header + "\n";
    for k in 0..nt {
        let _ = write!(text, "{},{}", t.times[k], t.lambda[k]);
        for row in [&t.displacement[k], &t.velocity[k]] {
            for v in row.iter() {
                for c in fr.model.components() {
                    let _ = write!(text, ",{}", v[c.index()]);
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
fn geometry(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("geometry.svg");
    let csv = dir.join("geometry.csv");
    let fr = &a.scene.frame;
    let mut text = String::from("order,lambda,node,x,y,hinge\n");
    for (k, h) in a.reading.hinges.iter().enumerate() {
        let n = &fr.nodes[h.node];
        let _ = writeln!(
            text,
            "{},{},{},{},{},{}",
            k + 1,
            g(h.lambda),
            n.id,
            n.x,
            n.y,
            group_label(a, h.group)
        );
    }
    let (xmin, xmax, ymin, ymax) = fr
        .nodes
        .iter()
        .fold((f64::MAX, f64::MIN, f64::MAX, f64::MIN), |b, n| {
            (b.0.min(n.x), b.1.max(n.x), b.2.min(n.y), b.3.max(n.y))
        });
    let extent = (xmax - xmin).max(ymax - ymin).max(1e-12);
    let (cx, cy) = (0.5 * (xmin + xmax), 0.5 * (ymin + ymax));
    let half = 0.62 * extent;
    {
        let root: Area = SVGBackend::new(&svg, (760, 640)).into_drawing_area();
        let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(
                    format!(
                        "{} ({}): hinges in order of formation",
                        if fr.title.is_empty() {
                            "frame"
                        } else {
                            &fr.title
                        },
                        fr.model.as_str()
                    ),
                    ("sans-serif", 16),
                )
                .margin(15)
                .x_label_area_size(30)
                .y_label_area_size(40)
                .build_cartesian_2d((cx - half)..(cx + half), (cy - half)..(cy + half))?;
            chart.configure_mesh().x_desc("x").y_desc("y").draw()?;
            for e in &fr.elements {
                let (p, q) = (&fr.nodes[e.from], &fr.nodes[e.to]);
                chart.draw_series(LineSeries::new(
                    vec![(p.x, p.y), (q.x, q.y)],
                    RGBColor(60, 60, 60).stroke_width(3),
                ))?;
            }
            for n in &fr.nodes {
                if n.fixed.iter().any(|&f| f) {
                    chart.draw_series(std::iter::once(TriangleMarker::new(
                        (n.x, n.y),
                        9,
                        BLACK.filled(),
                    )))?;
                }
                if n.load.iter().any(|&l| l != 0.0) {
                    chart.draw_series(std::iter::once(Cross::new(
                        (n.x, n.y),
                        8,
                        RGBColor(40, 140, 40).stroke_width(3),
                    )))?;
                }
            }
            // several hinges at one node: offset the labels
            let mut at_node: std::collections::HashMap<usize, usize> = Default::default();
            for (k, h) in a.reading.hinges.iter().enumerate() {
                let n = &fr.nodes[h.node];
                let dup = at_node.entry(h.node).or_insert(0);
                let off = 0.035 * extent * *dup as f64;
                *dup += 1;
                let color = Palette99::pick(k).to_rgba();
                chart
                    .draw_series(std::iter::once(Circle::new((n.x, n.y), 7, color.filled())))?
                    .label(format!(
                        "{}: {} at Lambda = {}",
                        k + 1,
                        group_label(a, h.group),
                        g(h.lambda)
                    ))
                    .legend(move |(x, y)| Circle::new((x + 8, y), 5, color.filled()));
                chart.draw_series(std::iter::once(Text::new(
                    format!("{}", k + 1),
                    (n.x + 0.02 * extent, n.y + 0.02 * extent + off),
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
