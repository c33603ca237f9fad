//! `profiles.svg/.csv`: the shape of the acceleration field in each interval (Fig. 1(b)).

use super::*;

pub(super) fn profiles(
    a: &Analysis,
    dir: &Path,
    view_choice: View,
) -> Result<Vec<PathBuf>, FramesError> {
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
    let shapes = shapes(a, listed, &mut text);
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
                    for gi in set.iter() {
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

/// `(interval, Lambda, per node the shape's components)`.
type Shape = (usize, f64, Vec<Vec<f64>>);

/// The normalised acceleration field of each listed interval at a
/// representative `Lambda`: `(interval, Lambda, per node the model's
/// components)`, largest nodal magnitude 1; their CSV rows appended to `text`.
fn shapes(a: &Analysis, listed: &[usize], text: &mut String) -> Vec<Shape> {
    let fr = &a.scene.frame;
    let grillage = fr.model == Model::Grillage;
    let space = fr.model == Model::Space;
    let comps = fr.model.components();
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
    shapes
}
