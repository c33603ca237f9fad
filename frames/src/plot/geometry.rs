//! `geometry.svg/.csv`: the frame with its hinges numbered in their order of formation.

use super::*;

/// The frame in plan, supports as triangles, the hinges as circles numbered
/// in their order of formation (ties at a node share a number), with the
/// `Lambda` at which each formed in the legend and the CSV.
pub(super) fn geometry(a: &Analysis, dir: &Path, view: View) -> Result<Vec<PathBuf>, FramesError> {
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
    let text = hinge_table(a);
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

/// `geometry.csv`: the hinges in order of formation, with their `Lambda`,
/// node and place.
fn hinge_table(a: &Analysis) -> String {
    let fr = &a.scene.frame;
    let space = fr.model == Model::Space;
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
    text
}
