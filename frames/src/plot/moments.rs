//! `moments.svg/.csv`: the bending moment along the members at the
//! critical `Lambda` values (Fig. 2(a)).

use super::*;

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
pub(super) fn moments(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    let svg = dir.join("moments.svg");
    let csv = dir.join("moments.csv");
    let fr = &a.scene.frame;
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
    let (bending, torque) = curves(a, &shown, &offsets, &mut text);
    let (mut blo, mut bhi) = (-1.15 * mp, 1.15 * mp);
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

/// The curves of the shown diagrams (bending, and the torque of a space
/// scene), each member a polyline along the arc length from its offset; their
/// CSV rows appended to `text`.
fn curves(a: &Analysis, shown: &[usize], offsets: &[f64], text: &mut String) -> (Curves, Curves) {
    let fr = &a.scene.frame;
    let sys = &a.system;
    let diagrams = &a.response.moments_at_breakpoints;
    // space: where each section's M2 and each element's torque sit in u
    let sf = crate::section_forces::SpaceForces::new(sys, fr.elements.len());
    let intervals: Vec<&crate::hinge::Interval> =
        a.reading.intervals.iter().filter(|i| !i.rigid).collect();
    let (mut bending, mut torque): (Curves, Curves) = (Vec::new(), Vec::new());
    for &j in shown {
        let d = &diagrams[j];
        // space: u at the breakpoint, on the piece that starts there
        let u = match (&sf, intervals.get(j)) {
            (Some(sf), Some(iv)) => {
                Some((sf, a.solution.pieces[iv.piece_at(d.lambda)].u(d.lambda)))
            }
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
                        Some((sf, u)) => {
                            let m2 = sf.m2(u, k);
                            let t = sf.torque(u, e);
                            let b = sf.bending(u, k, d.moments[k]);
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
    (bending, torque)
}
