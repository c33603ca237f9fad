//! `displacements.svg/.csv`: nodal displacements and velocities against time (Fig. 2(b)).

use super::*;

pub(super) fn displacements(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
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
