//! `activation.svg/.csv`: hinges against `Lambda` (Fig. 1(c)).

use super::*;

pub(super) fn activation(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("activation.svg");
    let csv = dir.join("activation.csv");
    let end = lambda_end(a);
    // rows: groups in order of their first appearance
    let mut rows: Vec<usize> = Vec::new();
    for iv in &a.reading.intervals {
        for g in iv
            .accelerating
            .iter()
            .chain(iv.constant_rate.iter())
            .chain(iv.at_yield.iter())
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
    let labels: Vec<String> = shown_rows
        .iter()
        .map(|&r| group_label(a, rows[r]))
        .collect();
    let chart = Chart {
        height,
        caption,
        end,
        n,
    };
    draw(&svg, a, &chart, &labels, &bars).map_err(|e| io(&svg, e))?;
    Ok(vec![svg, write(&csv, &text)?])
}

/// The size and axes of the activation diagram.
struct Chart {
    height: u32,
    caption: String,
    /// The last `Lambda` drawn.
    end: f64,
    /// The number of rows drawn.
    n: usize,
}

/// Draws the diagram: one bar per run of intervals in a state,
/// `(row, from, to, state)` with the states 0 at yield, 1 rotating at a
/// constant rate, 2 accelerating.
fn draw(
    svg: &Path,
    a: &Analysis,
    chart: &Chart,
    labels: &[String],
    bars: &[(usize, f64, f64, u8)],
) -> Result<(), Box<dyn std::error::Error>> {
    let Chart {
        height,
        ref caption,
        end,
        n,
    } = *chart;
    let root: Area = SVGBackend::new(svg, (900, height)).into_drawing_area();
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
    for &(r, from, to, k) in bars {
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
            .legend(move |(x, y)| Rectangle::new([(x, y - 4), (x + 16, y + 4)], color.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
