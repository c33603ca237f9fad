//! Convergence of the lumped cantilever to the continuum (system9-notes, fact 7).
//!
//! ```sh
//! cargo run --release -q --example cantilever_convergence
//! ```
//!
//! A uniform cantilever (L = 1, Mp = 1, mu = 1, lumped mu h / 2 to each element
//! end) with a tip force P = Lambda from rest. Continuum (derived in the notes
//! and checked here): rigid for P < Mp / L, a root hinge for Mp/L <= P <= 3 Mp/L,
//! then a fully plastic zone from the root out to a distance xi = 3 Mp / P from
//! the tip, so the hinge front reaches x (from the root) at P = 3 Mp / (L - x).
//! Derivation: the outer rigid part of length xi rotates about its inner end,
//! which does not accelerate (zero acceleration inside the zone); with zero
//! shear there, P = mu xi^2 alpha / 2 and P xi / 2 - Mp = mu xi^3 alpha / 12,
//! so P xi / 3 = Mp. For each n the table gives the Lambda at which a hinge
//! forms at x = 1/4, 1/2, 3/4 beside the continuum value.

use frames::{Analysis, AnalysisOptions, Scene, SolveOptions};
use plcp::{Method, Precision};

fn options(precision: Precision) -> AnalysisOptions {
    AnalysisOptions {
        solve: SolveOptions {
            method: Method::Wolfe,
            precision,
            lambda_max: None,
        },
        samples: 11,
        // this example escalates itself, to say which precision each row used
        escalate: false,
        ..AnalysisOptions::default()
    }
}

fn scene(n: usize) -> Result<Scene, frames::FramesError> {
    let src = format!(
        "[[node]]\nid = \"A\"\nx = 0.0\ny = 0.0\n[[node]]\nid = \"B\"\nx = 1.0\ny = 0.0\n\
         [[member]]\nid = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nmass_per_length = 1.0\nelements = {n}\n\
         [[support]]\nnode = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n[[load]]\nnode = \"B\"\nfy = -1.0\n"
    );
    Scene::from_toml(&src, &format!("cantilever-{n}.toml"))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let fronts = [0.25, 0.5, 0.75];
    println!("hinge front of the lumped cantilever against the continuum xi = 3 Mp / P");
    println!(
        "{:>5} {:>10} | {:>22} {:>22} {:>22} | {:>9}",
        "n", "root", "x = 1/4 (cont. 4)", "x = 1/2 (cont. 6)", "x = 3/4 (cont. 12)", "max error"
    );
    for n in [4usize, 8, 16, 32, 64, 128, 256] {
        let t = std::time::Instant::now();
        // f64 first; where plcp's path does not satisfy system (9) well enough,
        // the same path in double-double (fx128)
        let mut a = Analysis::run(scene(n)?, &options(Precision::F64))?;
        let mut precision = "f64";
        if !a.solution.status.is_success() || a.solution.info.residual.worst() > 1e-6 {
            // (at n = 256 this takes about 8 minutes on 2 cores)
            a = Analysis::run(scene(n)?, &options(Precision::F128))?;
            precision = "f128";
        }
        let fr = &a.scene.frame;
        let at = |x: f64| {
            a.reading
                .hinges
                .iter()
                .find(|h| (fr.nodes[h.node].x - x).abs() < 1e-9)
                .map(|h| h.lambda)
        };
        let mut err = 0.0f64;
        let mut cells = Vec::new();
        for &x in &fronts {
            let exact = 3.0 / (1.0 - x);
            match at(x) {
                Some(l) => {
                    err = err.max((l - exact).abs() / exact);
                    cells.push(format!("{l:>10.5} ({:+.2e})", (l - exact) / exact));
                }
                None => cells.push(format!("{:>22}", "-")),
            }
        }
        let residual = a.solution.info.residual.worst();
        if !a.solution.status.is_success() || residual > 1e-6 {
            println!(
                "{n:>5}   plcp's path is not a solution (status {}, residual {residual:.1e}): row withheld",
                a.solution.status.as_str()
            );
            continue;
        }
        println!(
            "{n:>5} {:>10.6} | {:>22} {:>22} {:>22} | {err:>9.2e}   ({precision}, {:.1} s, {} pivots)",
            a.reading.collapse_load().unwrap_or(f64::NAN),
            cells[0],
            cells[1],
            cells[2],
            t.elapsed().as_secs_f64(),
            a.solution.info.pivots
        );
    }
    println!("(relative errors in brackets; the root hinge forms at Mp / L = 1 for every n)");
    Ok(())
}
