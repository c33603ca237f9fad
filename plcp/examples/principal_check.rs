//! Compares the principal-pivoting fast path with the general engine on
//! instance files (`plcp solve`'s JSON): statuses, events, segment bases,
//! the largest relative breakpoint difference, the end `z` difference and
//! both paths' largest residual.
//!
//! ```sh
//! cargo run --release -p plcp --example principal_check -- /tmp/qpoases-bench/inst_n*_s1.json
//! ```

use plcp::Settings;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for file in std::env::args().skip(1) {
        let problem = plcp::io::json::read_plcp::<f64>(std::path::Path::new(&file))?;
        let fast = plcp::solve(&problem, &Settings::<f64>::default())?;
        let engine = plcp::solve(
            &problem,
            &Settings::<f64> {
                principal: false,
                ..Settings::default()
            },
        )?;
        let same_events = fast.breakpoints.len() == engine.breakpoints.len()
            && fast
                .breakpoints
                .iter()
                .zip(&engine.breakpoints)
                .all(|(a, b)| a.entering == b.entering && a.leaving == b.leaving);
        let same_bases = fast.segments.len() == engine.segments.len()
            && fast
                .segments
                .iter()
                .zip(&engine.segments)
                .all(|(a, b)| a.basis == b.basis);
        let bp = fast
            .breakpoints
            .iter()
            .zip(&engine.breakpoints)
            .fold(0.0f64, |m, (a, b)| {
                m.max((a.lambda - b.lambda).abs() / a.lambda.abs().max(1.0))
            });
        let zmax = (0..problem.n()).fold(1.0f64, |m, i| m.max(engine.end.z[i].abs()));
        let dz = (0..problem.n()).fold(0.0f64, |m, i| {
            m.max((fast.end.z[i] - engine.end.z[i]).abs() / zmax)
        });
        println!(
            "{file}: {} / {}, status {:?} / {:?}, events same {same_events}, bases same {same_bases}, breakpoints {bp:.1e}, end z {dz:.1e}, residual {:.1e} / {:.1e}, max_condition {:.3e}",
            fast.info.method,
            engine.info.method,
            fast.status,
            engine.status,
            fast.info.residual.worst(),
            engine.info.residual.worst(),
            fast.info.max_condition,
        );
    }
    Ok(())
}
