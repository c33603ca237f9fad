//! A small log-log scatter plot written as SVG by hand (the root crate has no
//! plotting dependency): one colour and marker per series, a legend, decade
//! grid lines, and a short label beside every point.

#![allow(dead_code)]

use std::fmt::Write as _;

/// One marker.
pub struct Point {
    /// Abscissa (positive; drawn on a log scale).
    pub x: f64,
    /// Ordinate (drawn on a log scale; zero and below are clamped to the floor).
    pub y: f64,
    /// Series name (legend entry).
    pub series: String,
    /// Text beside the marker.
    pub label: String,
}

const COLOURS: [&str; 10] = [
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
    "#bcbd22", "#17becf",
];

/// The SVG text of a log-log scatter plot.
pub fn log_log(title: &str, xlabel: &str, ylabel: &str, points: &[Point]) -> String {
    let (w, h) = (900.0, 600.0);
    let (left, right, top, bottom) = (80.0, 230.0, 40.0, 60.0);
    let floor = 1e-17;
    let ly = |y: f64| if y.is_finite() { y.max(floor) } else { 1e3 }.log10();
    let lx = |x: f64| x.max(1e-7).log10();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in points {
        x0 = x0.min(lx(p.x));
        x1 = x1.max(lx(p.x));
        y0 = y0.min(ly(p.y));
        y1 = y1.max(ly(p.y));
    }
    if points.is_empty() {
        (x0, x1, y0, y1) = (-3.0, 0.0, -16.0, 0.0);
    }
    let (x0, x1, y0, y1) = (
        x0.floor(),
        x1.ceil().max(x0.floor() + 1.0),
        y0.floor(),
        y1.ceil().max(y0.floor() + 1.0),
    );
    let pw = w - left - right;
    let ph = h - top - bottom;
    let sx = |x: f64| left + (lx(x) - x0) / (x1 - x0) * pw;
    let sy = |y: f64| top + (y1 - ly(y)) / (y1 - y0) * ph;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="22" text-anchor="middle" font-size="15">{title}</text>"#,
        left + pw / 2.0
    );
    for e in (x0 as i32)..=(x1 as i32) {
        let x = left + (e as f64 - x0) / (x1 - x0) * pw;
        let _ = writeln!(
            s,
            r##"<line x1="{x}" y1="{top}" x2="{x}" y2="{}" stroke="#ddd"/><text x="{x}" y="{}" text-anchor="middle">1e{e}</text>"##,
            top + ph,
            top + ph + 16.0
        );
    }
    for e in (y0 as i32)..=(y1 as i32) {
        let y = top + (y1 - e as f64) / (y1 - y0) * ph;
        let _ = writeln!(
            s,
            r##"<line x1="{left}" y1="{y}" x2="{}" y2="{y}" stroke="#ddd"/><text x="{}" y="{}" text-anchor="end">1e{e}</text>"##,
            left + pw,
            left - 6.0,
            y + 4.0
        );
    }
    let _ = writeln!(
        s,
        r#"<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="black"/>"#
    );
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{xlabel}</text>"#,
        left + pw / 2.0,
        h - 15.0
    );
    let _ = writeln!(
        s,
        r#"<text x="18" y="{}" text-anchor="middle" transform="rotate(-90 18 {})">{ylabel}</text>"#,
        top + ph / 2.0,
        top + ph / 2.0
    );
    let mut series: Vec<&str> = Vec::new();
    for p in points {
        if !series.contains(&p.series.as_str()) {
            series.push(&p.series);
        }
    }
    let marker = |k: usize, x: f64, y: f64, c: &str| -> String {
        match (k / COLOURS.len()) % 3 {
            0 => format!(r#"<circle cx="{x:.1}" cy="{y:.1}" r="4" fill="{c}"/>"#),
            1 => format!(
                r#"<rect x="{:.1}" y="{:.1}" width="8" height="8" fill="{c}"/>"#,
                x - 4.0,
                y - 4.0
            ),
            _ => format!(
                r#"<path d="M{:.1},{:.1} l8,0 l-4,-8 z" fill="{c}"/>"#,
                x - 4.0,
                y + 4.0
            ),
        }
    };
    for p in points {
        let k = series.iter().position(|q| *q == p.series).unwrap_or(0);
        let c = COLOURS[k % COLOURS.len()];
        let (x, y) = (sx(p.x), sy(p.y));
        s.push_str(&marker(k, x, y, c));
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" font-size="9" fill="{c}">{}</text>"#,
            x + 5.0,
            y - 4.0,
            p.label
        );
    }
    for (k, name) in series.iter().enumerate() {
        let c = COLOURS[k % COLOURS.len()];
        let (x, y) = (w - right + 20.0, top + 10.0 + 18.0 * k as f64);
        s.push_str(&marker(k, x, y, c));
        let _ = writeln!(s, r#"<text x="{}" y="{}">{name}</text>"#, x + 10.0, y + 4.0);
    }
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" font-size="10">errors below 1e-17 drawn at 1e-17</text>"#,
        w - right + 10.0,
        top + ph
    );
    s.push_str("</svg>\n");
    s
}
