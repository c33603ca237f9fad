//! Pipe whip: the cases the paper's introduction cites, by system (9).
//!
//! ```sh
//! cargo run --release -q --example pipe_whip
//! ```
//!
//! - a circular-quadrant cantilever loaded radially at its tip in its plane
//!   (planar model; bending only, and with the bending-axial interaction);
//! - an L-shaped and a semicircular cantilever loaded normal to their plane at
//!   the tip (grillage model: bending and torsion, `(M/Mp)^2 + (T/Tp)^2 <= 1`
//!   approximated by an inscribed polygon);
//! - the straight cantilever of the paper turned out of plane (no torsion),
//!   which must reproduce the planar path.
//!
//! - an L-shaped run loaded along its broken leg by a thrust rising to a
//!   plateau, with a restraint at a gap from the break (`[[target]]`): when the
//!   pipe reaches it, how fast, and the kinetic energy the restraint must absorb;
//! - a space scene (`model = "space"`): a horizontal run, an elbow and a riser
//!   in a vertical plane, the thrust along the broken riser, alone (`riser`,
//!   in the tables and the time-stepping check) and with a restraint at the
//!   elbow (`riser-restraint`); both are reduced to the planar model in their
//!   plane automatically (the report says so);
//! - a run in three dimensions (`space-run`): an L-shaped horizontal run (two
//!   legs and a chorded elbow) and a second elbow turning it into a riser,
//!   the thrust along the broken riser rising to a plateau; no plane holds
//!   it, so it is the general space model (six components per node, the
//!   yield polyhedron); alone and with a restraint at the riser's foot
//!   (`space-restraint`).
//!
//! Units: radius or leg length 1, Mp = 1, Tp / Mp = pi / (2 sqrt 3) (thin-walled
//! pipe, von Mises), mass per length 1, lambda(t) = t.
//!
//! Prints, per scene: the sizes of system (9) before and after leaving out what
//! the scene does not need, the hinges in order of formation, and the events
//! where a flowing hinge leaves yield (deactivations: system (9) assumes none);
//! then convergence tables in the number of facets and of elements; then the
//! non-deactivation check by the library's time-stepping integrator
//! (`frames::timestep`, at two step sizes) against the PLCP path's first
//! unloading, and an independent cross-check by a Clarabel-based stepper. Writes the
//! reports and plots (geometry with the hinge order, activation diagram,
//! profiles, moments, displacements) to `out/pipe-whip/<scene>/`.

use frames::yield_surface::{Curve, Polygon};
use frames::{Analysis, AnalysisOptions, Scene, System};
use std::path::Path;

#[path = "../frames/tests/common/reference.rs"]
mod reference;

const TP: f64 = 0.906_899_682_117_108_9;

fn g(x: f64) -> String {
    frames::report::format_number(x)
}

fn analyse(scene: Scene) -> Result<Analysis, Box<dyn std::error::Error>> {
    let a = Analysis::run(scene, &AnalysisOptions::default())?;
    if !a.solution.status.is_success() {
        return Err(format!(
            "{}: {} ({})",
            a.scene.file,
            a.solution.status.as_str(),
            a.solution.message
        )
        .into());
    }
    Ok(a)
}

fn variant(file: &Path, from: &str, to: &str) -> Result<Scene, Box<dyn std::error::Error>> {
    // strict, as Scene::from_file: a byte that is not UTF-8 is named by position
    let bytes = std::fs::read(file)?;
    let src = plcp::io::utf8(&bytes).map_err(|e| format!("{}: {e}", file.display()))?;
    if !src.contains(from) {
        return Err(format!("{}: no \"{from}\" to vary", file.display()).into());
    }
    Ok(Scene::from_toml(
        &src.replace(from, to),
        &format!("{} [{to}]", file.display()),
    )?)
}

fn hinge_list(a: &Analysis, max: usize) -> String {
    let mut v: Vec<String> = a
        .reading
        .hinges
        .iter()
        .take(max)
        .map(|h| format!("{} {}", a.scene.frame.nodes[h.node].id, g(h.lambda)))
        .collect();
    if a.reading.hinges.len() > max {
        v.push("...".into());
    }
    v.join(", ")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scenes = root.join("scenes").join("pipe-whip");
    let out = root.join("out").join("pipe-whip");
    let names = [
        "quadrant",
        "quadrant-axial",
        "l-shaped",
        "semicircle",
        "straight",
        "riser",
        "space-run",
    ];
    println!("==== the scenes ====");
    println!(
        "{:<16} {:>9} {:>22} {:>22} {:>10} {:>10} {:>15}",
        "scene",
        "model",
        "full (beta, s, p)",
        "solved (beta, s, p)",
        "collapse",
        "hinges",
        "deactivations"
    );
    let mut analyses = Vec::new();
    for name in names {
        let file = scenes.join(format!("{name}.toml"));
        let a = analyse(Scene::from_file(&file)?)?;
        let dir = out.join(name);
        std::fs::create_dir_all(&dir)?;
        std::fs::write(dir.join("report.txt"), a.to_text())?;
        std::fs::write(
            dir.join("report.json"),
            serde_json::to_string_pretty(&a.to_json())?,
        )?;
        frames::plot::write_all(&a, &dir)?;
        let (f, s) = (a.system.full, a.system.sizes());
        println!(
            "{:<16} {:>9} {:>22} {:>22} {:>10} {:>10} {:>15}",
            name,
            match &a.scene.frame.reduction {
                Some(r) => format!("space:{}", r.kind.as_str()),
                None => a.scene.frame.model.as_str().to_string(),
            },
            format!("({}, {}, {})", f.coordinates, f.forces, f.modes),
            format!("({}, {}, {})", s.coordinates, s.forces, s.modes),
            g(a.reading.collapse_load().unwrap_or(f64::NAN)),
            a.reading.hinges.len(),
            a.reading.deactivations().len()
        );
        analyses.push((name, a));
    }
    println!("(beta coordinates, s member forces, p yield modes; full: every coordinate and mode of the model, no ties, no decoupled parts left out)");
    println!();
    println!("==== hinge order (node, Lambda at which it starts to flow) ====");
    for (name, a) in &analyses {
        println!("{name:<16} {}", hinge_list(a, 10));
        if let Some((l, e)) = a.reading.deactivations().first() {
            println!(
                "{:<16} first deactivation at Lambda = {}: {} leaves yield after flowing",
                "",
                g(*l),
                a.scene.frame.nodes[a.reading.groups[e.group].node].id
            );
        }
    }
    println!();

    // the straight cantilever out of plane against the planar one
    let planar = analyse(Scene::from_file(
        root.join("scenes").join("cantilever.toml"),
    )?)?;
    let straight = &analyses.iter().find(|(n, _)| *n == "straight").unwrap().1;
    let crit =
        |a: &Analysis| -> Vec<f64> { a.reading.breakpoints.iter().map(|b| b.lambda).collect() };
    let (cp, cs) = (crit(&planar), crit(straight));
    let same = cp.len() == cs.len() && cp.iter().zip(&cs).all(|(a, b)| (a - b).abs() < 1e-9);
    println!(
        "straight out-of-plane cantilever: breakpoints {:?}; planar cantilever {:?}: {}",
        cs.iter().map(|&x| g(x)).collect::<Vec<_>>(),
        cp.iter().map(|&x| g(x)).collect::<Vec<_>>(),
        if same { "the same" } else { "DIFFERENT" }
    );
    if !same {
        return Err("the straight grillage cantilever does not reproduce the planar path".into());
    }
    println!();

    // convergence in facets: the L-shaped cantilever, 4 elements per leg
    let circle = 1.0 / (1.0f64 + 1.0 / (TP * TP)).sqrt();
    println!("==== convergence in facets: L-shaped cantilever (4 + 4 elements) ====");
    println!(
        "static collapse, circle (closed form, root section): P = 1 / sqrt(1/Mp^2 + 1/Tp^2) = {}",
        g(circle)
    );
    println!(
        "{:>7} {:>12} {:>12} {:>12} {:>14}   hinges (node Lambda)",
        "facets", "collapse", "polygon*", "circle-coll.", "1-cos(pi/k)"
    );
    let l_file = scenes.join("l-shaped.toml");
    for k in [4, 8, 16, 32, 64] {
        let a = analyse(variant(&l_file, "facets = 16", &format!("facets = {k}"))?)?;
        let poly = Polygon::new(Curve::BendingTorsion, k)?;
        let closed = poly.load_factor(1.0, 1.0 / TP);
        let c = a.reading.collapse_load().unwrap_or(f64::NAN);
        println!(
            "{:>7} {:>12} {:>12} {:>12} {:>14}   {}",
            k,
            g(c),
            g(closed),
            format!("{:.2e}", circle - c),
            format!("{:.2e}", 1.0 - (std::f64::consts::PI / k as f64).cos()),
            hinge_list(&a, 6)
        );
    }
    println!("(* the root section's load factor on the polygon, (M, T) = (L1, L2) P: an independent closed form)");
    println!();

    println!("==== convergence in elements: semicircular cantilever (16 facets) ====");
    println!(
        "continuum, root in pure torsion (a vertex of the polygon): Tp / 2R = {}",
        g(TP / 2.0)
    );
    // the continuum with the same polygon: (M, T) = R P (sin t, 1 + cos t) at the angle t
    let poly16 = Polygon::new(Curve::BendingTorsion, 16)?;
    let continuum = (0..=20_000)
        .map(|i| {
            let t = std::f64::consts::PI * i as f64 / 20_000.0;
            poly16.load_factor(t.sin(), (1.0 + t.cos()) / TP)
        })
        .fold(f64::INFINITY, f64::min);
    println!(
        "continuum with the 16-facet polygon (its cut corners weaken the sections next to the root): {}",
        g(continuum)
    );
    println!(
        "{:>9} {:>12} {:>8}   hinges (node Lambda)",
        "elements", "collapse", "modes"
    );
    let s_file = scenes.join("semicircle.toml");
    for n in [4, 8, 16, 32] {
        let a = analyse(variant(
            &s_file,
            "elements = 8",
            &format!("elements = {n}"),
        )?)?;
        println!(
            "{:>9} {:>12} {:>8}   {}",
            n,
            g(a.reading.collapse_load().unwrap_or(f64::NAN)),
            a.system.modes.len(),
            hinge_list(&a, 6)
        );
    }
    println!();
    println!("==== convergence in elements: L-shaped cantilever (16 facets) ====");
    println!("{:>9} {:>12}   hinges (node Lambda)", "per leg", "collapse");
    for n in [1, 2, 4, 8, 16] {
        let a = analyse(variant(
            &l_file,
            "elements = 4",
            &format!("elements = {n}"),
        )?)?;
        println!(
            "{:>9} {:>12}   {}",
            n,
            g(a.reading.collapse_load().unwrap_or(f64::NAN)),
            hinge_list(&a, 6)
        );
    }
    println!();
    println!("==== convergence in elements: circular quadrant in plane (bending only) ====");
    println!(
        "{:>9} {:>12}   hinges (node Lambda)",
        "elements", "collapse"
    );
    let q_file = scenes.join("quadrant.toml");
    for n in [4, 8, 16, 32] {
        let a = analyse(variant(
            &q_file,
            "elements = 8",
            &format!("elements = {n}"),
        )?)?;
        println!(
            "{:>9} {:>12}   {}",
            n,
            g(a.reading.collapse_load().unwrap_or(f64::NAN)),
            hinge_list(&a, 6)
        );
    }
    println!();

    // reduced against full assembly (same path)
    println!("==== leave-outs: reduced against full assembly ====");
    for (name, a) in &analyses {
        let full = System::assemble_full(&a.scene.frame);
        let sol = frames::solve::solve(&full, &frames::SolveOptions::default())?;
        let reading = frames::hinge::read(&a.scene.frame, &full, &sol.pieces, sol.tolerance);
        let first = |hs: &[frames::hinge::Hinge]| {
            let mut m = std::collections::BTreeMap::new();
            for h in hs {
                m.entry(h.node).or_insert(h.lambda);
            }
            m
        };
        let (r, f) = (first(&a.reading.hinges), first(&reading.hinges));
        let agree = r.len() == f.len()
            && r.iter()
                .zip(&f)
                .all(|((n1, l1), (n2, l2))| n1 == n2 && (l1 - l2).abs() < 1e-9);
        println!(
            "{name:<16} free + complementary: {} + {} solved, {} + {} full; {} pivots vs {}; first hinge at every node: {}",
            a.system.sizes().free(),
            a.system.sizes().modes,
            full.sizes().free(),
            full.sizes().modes,
            a.solution.info.pivots,
            sol.info.pivots,
            if agree { "the same" } else { "DIFFERENT" }
        );
    }
    println!();
    println!("==== time stepping: does a flowing hinge slow down? ====");
    println!("System (9) assumes that a flowing hinge keeps accelerating or rotates on at a");
    println!("constant rate; where its path shows a flowing section leaving yield, the path");
    println!("beyond is not the response (the hinge would decelerate, x*_dd < 0, which (9)");
    println!("excludes). The non-deactivation check is the library integrator frames::timestep");
    println!("(backward Euler at velocity level, one mixed LCP per step solved by plcp, warm-");
    println!("started; hinges may unload), from rest, at two step sizes h and h/2:");
    println!("  M (v - v_old) / h + A' X = a_o lambda_n,  A v = T N r,  y* = X* - (T N)' X >= 0,  r >= 0,  y*' r = 0");
    println!("Columns: PLCP = first unloading on the path of (9) (its reading, Lambda = t);");
    println!("decel = first flow_decelerated event (a flowing yield mode's rate below its running");
    println!(
        "peak by more than {DECEL_TOL:.0e} relative: x*_dd < 0); stop = first flow_stopped event"
    );
    println!("(a mode's rate back to zero); hinge stop = first section whose every mode stopped.");
    println!(
        "{:<16} {:>9} {:>10} {:>9} {:>22} {:>22} {:>22} {:>9} {:>8}",
        "scene",
        "PLCP",
        "h",
        "path bp",
        "decel Lambda (node)",
        "stop Lambda (node)",
        "hinge stop",
        "disp err",
        "seconds"
    );
    for (name, a) in &analyses {
        let plcp_first = a.reading.deactivations().first().map(|(l, e)| {
            (
                *l,
                a.scene.frame.nodes[a.reading.groups[e.group].node]
                    .id
                    .clone(),
            )
        });
        let t_end = horizon(a);
        for (i, h) in [t_end / STEPS, 0.5 * t_end / STEPS].into_iter().enumerate() {
            let r = library_run(a, h, t_end)?;
            let node = |section: usize| {
                a.scene.frame.nodes[a.system.sections[section].node]
                    .id
                    .clone()
            };
            let fmt = |e: Option<&frames::timestep::ModeEvent>| match e {
                Some(e) => format!("{} ({})", g6(e.lambda), node(e.section)),
                None => "none".into(),
            };
            let c = frames::timestep::compare(a, &r);
            let decel = r.decelerations().first().copied();
            // the last breakpoint of the PLCP path at or before the deceleration
            let bp = decel.and_then(|e| {
                a.reading
                    .breakpoints
                    .iter()
                    .map(|b| b.lambda)
                    .rfind(|&l| l <= e.lambda)
            });
            println!(
                "{:<16} {:>9} {:>10} {:>9} {:>22} {:>22} {:>22} {:>9} {:>8}",
                if i == 0 { *name } else { "" },
                if i == 0 {
                    plcp_first.as_ref().map_or("none".into(), |(l, _)| g6(*l))
                } else {
                    String::new()
                },
                format!("{h:.2e}"),
                bp.map_or("-".into(), g6),
                fmt(decel),
                fmt(r.deactivations().first().copied()),
                fmt(first_hinge_stop(a, &r)),
                format!("{:.1e}", c.displacement_error / c.displacement_scale),
                format!("{:.2}", r.seconds)
            );
            if !r.outcome.is_completed() {
                return Err(format!("{name}: time stepping stopped: {:?}", r.outcome).into());
            }
        }
    }
    println!(
        "(Lambda = lambda(t) = t. Stepped to t = 1.3 x the PLCP first unloading, or 1.3 x the"
    );
    println!("last breakpoint; {STEPS} and {} steps. disp err: largest nodal translation against the exact", 2.0 * STEPS);
    println!(
        "PLCP response at its first unloading (or the end), relative to the largest translation."
    );
    println!(
        "An event is seen at the end of its step: resolution h. path bp: the PLCP path's last"
    );
    println!(
        "breakpoint at or before the first deceleration. On the L-shaped cantilever the root's"
    );
    println!(
        "flow runs on two facets of its bending-torsion polygon from Lambda 1.28; one facet's"
    );
    println!(
        "x*_dd falls to zero at the path's breakpoint 1.4782 and in the stepped response its rate"
    );
    println!(
        "then decreases (and stops, leaving yield, at 1.88) while the root keeps flowing on the"
    );
    println!(
        "other facet: a deactivation of a yield mode that (9) cannot follow, not flagged by the"
    );
    println!("PLCP reading, which reads unloading per section (its first is at B, Lambda 3.18).)");
    println!();
    println!("==== cross-check: an independent stepper (Clarabel interior-point QP) ====");
    println!("The same implicit-Euler velocity-level problem, each step solved as a convex QP by");
    println!("Clarabel (no plcp, no warm start, lambda at the step end instead of its mean).");
    println!("Reported: the first time a section's plastic rate (of one yield mode) falls below");
    println!("97 % of its peak (a slowing hinge), against the first unloading on the PLCP path.");
    println!(
        "{:<16} {:>8} {:>10} {:>24} {:>26} {:>12}",
        "scene", "dt", "steps", "PLCP first unloading", "Clarabel: first slowing", "|dv| before"
    );
    for (name, a) in &analyses {
        let plcp_first = a.reading.deactivations().first().map(|(l, e)| {
            (
                *l,
                a.scene.frame.nodes[a.reading.groups[e.group].node]
                    .id
                    .clone(),
            )
        });
        let t_end = match &plcp_first {
            Some((l, _)) => 1.3 * l,
            None => {
                1.3 * a
                    .reading
                    .breakpoints
                    .last()
                    .map(|b| b.lambda)
                    .unwrap_or(1.0)
            }
        };
        let dt = t_end / 2000.0;
        let t_collapse = a
            .reading
            .collapse_load()
            .and_then(|l| a.scene.history.time_at(l))
            .unwrap_or(0.0);
        let t_compare = plcp_first
            .as_ref()
            .and_then(|(l, _)| a.scene.history.time_at(*l))
            .unwrap_or(t_end);
        let stepped = first_slowing(a, dt, t_end, t_collapse, t_compare)
            .ok_or_else(|| format!("{name}: the time-stepping QP failed"))?;
        let fmt = |x: &Option<(f64, String)>| match x {
            Some((l, n)) => format!("{} at {n}", g(*l)),
            None => "none".into(),
        };
        let slow = stepped.slowing.map(|(t, sec)| {
            (
                a.scene.history.lambda(t),
                a.scene.frame.nodes[a.system.sections[sec].node].id.clone(),
            )
        });
        println!(
            "{:<16} {:>8} {:>10} {:>24} {:>26} {:>12}",
            name,
            format!("{:.1e}", dt),
            2000,
            fmt(&plcp_first),
            fmt(&slow),
            format!("{:.1e}", stepped.deviation)
        );
    }
    println!("(Lambda = lambda(t) = t; |dv| before: the difference between the stepped and the");
    println!("PLCP velocities of the masses at the first of the two events (or the end), relative");
    println!("to the largest velocity: the stepper's O(dt) error where both models hold. A mode");
    println!(
        "whose rate falls is a deactivation of that mode: (9) is the response only up to it.)"
    );
    restraint(&scenes, &out, "restraint", "C along the broken leg (-y)")?;
    restraint(
        &scenes,
        &out,
        "riser-restraint",
        "D along the broken riser (-z), target at the elbow's end C along -z",
    )?;
    restraint(
        &scenes,
        &out,
        "space-restraint",
        "G along the broken riser (-z) of the 3D run, target at the riser's foot F along -z",
    )?;
    println!("reports and plots in {}", out.display());
    Ok(())
}

/// The restraint scene: when the whipping pipe closes the gap to its
/// restraint, how fast, and with what kinetic energy, for a few gaps; exact
/// from the PLCP response, and by the time-stepping integrator at two steps.
fn restraint(
    scenes: &Path,
    out: &Path,
    name: &str,
    thrust: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    use frames::timestep::{StepOptions, StepState, TimeStepping};
    let file = scenes.join(format!("{name}.toml"));
    let a = analyse(Scene::from_file(&file)?)?;
    let dir = out.join(name);
    std::fs::create_dir_all(&dir)?;
    std::fs::write(dir.join("report.txt"), a.to_text())?;
    std::fs::write(
        dir.join("report.json"),
        serde_json::to_string_pretty(&a.to_json())?,
    )?;
    frames::plot::write_all(&a, &dir)?;
    println!();
    println!("==== {name}: when the whipping pipe reaches the restraint ====");
    println!("{}: {}", name, a.scene.frame.title);
    println!(
        "thrust at {thrust}, {}; collapse load {}",
        a.scene.history.describe(),
        g(a.reading.collapse_load().unwrap_or(f64::NAN))
    );
    println!(
        "{:>6} {:>10} {:>8} {:>10} {:>10}   {:>10} {:>10}   {:>10} {:>10}",
        "gap", "t", "lambda", "velocity", "energy", "t (h)", "v (h)", "t (h/2)", "v (h/2)"
    );
    let t_end = 4.0;
    // the scene's target, and more gaps at the same node and direction
    let mut targets = a.scene.targets.clone();
    for gap in [0.01, 0.2, 0.5] {
        targets.push(frames::target::Target {
            gap,
            ..targets[0].clone()
        });
    }
    let mut scene = a.scene.clone();
    scene.targets = targets;
    let a = Analysis::run(
        scene,
        &AnalysisOptions {
            t_end: Some(t_end),
            ..AnalysisOptions::default()
        },
    )?;
    let mut stepped = Vec::new();
    for steps in [2000.0, 4000.0] {
        let options = StepOptions {
            h: t_end / steps,
            t_end,
            ..StepOptions::default()
        };
        let ts = TimeStepping::new(&a.system, &a.scene.history, &options)?;
        stepped.push(ts.run(&StepState::rest(&a.system))?);
    }
    let along = |q: &[f64]| a.scene.targets[0].project(&a.system, q);
    for arr in &a.targets {
        let gap = arr.target.gap;
        let exact = match (arr.time, arr.lambda, arr.velocity, arr.kinetic_energy) {
            (Some(t), Some(l), Some(v), Some(e)) => {
                format!("{:>10} {:>8} {:>10} {:>10}", g(t), g(l), g(v), g(e))
            }
            _ => format!("{:>10} {:>8} {:>10} {:>10}", "never", "-", "-", "-"),
        };
        let by_steps: Vec<String> = stepped
            .iter()
            .map(
                |r| match r.displacement.iter().position(|q| along(q) >= gap) {
                    Some(k) => format!("{:>10} {:>10}", g(r.times[k]), g(along(&r.velocity[k]))),
                    None => format!("{:>10} {:>10}", "never", "-"),
                },
            )
            .collect();
        println!("{:>6} {exact}   {}", g(gap), by_steps.join("   "));
    }
    println!("(exact: the first root of the piecewise polynomial displacement along the target;");
    println!("energy: kinetic energy of the whole run then. (h), (h/2): the first step of the");
    println!(
        "time-stepping integrator, h = {} and {}, whose displacement reaches the gap.)",
        g(t_end / 2000.0),
        g(t_end / 4000.0)
    );
    Ok(())
}

/// Steps the velocity-level rigid-plastic problem from rest and returns the
/// first time and section at which the plastic rate of a yield mode falls
/// below 97 % of its peak (once the peak is above 1 % of the largest rate
/// seen), after the collapse time (before it the rates are zero up to
/// round-off).
fn first_slowing(
    an: &Analysis,
    dt: f64,
    t_end: f64,
    t_collapse: f64,
    t_compare: f64,
) -> Option<Stepped> {
    let (sys, history) = (&an.system, &an.scene.history);
    use clarabel::algebra::CscMatrix;
    use clarabel::solver::{
        DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
        SupportedConeT, ZeroConeT,
    };
    let (nb, ns, np) = (sys.coordinates.len(), sys.forces.len(), sys.modes.len());
    let n = nb + np;
    // the blocks of the tests' reference QP, the mass divided by the step
    let (p, (ii, jj, vv), b) = reference::qp_blocks(sys, dt);
    let a = CscMatrix::new_from_triplets(ns + np, n, ii, jj, vv);
    let cones: Vec<SupportedConeT<f64>> = vec![ZeroConeT(ns), NonnegativeConeT(np)];
    let mut v = vec![0.0; nb];
    let mut v_plcp = vec![0.0; nb];
    let mut deviation = 0.0f64;
    let mut slowing = None;
    let mut peak = vec![0.0f64; np];
    let mut global = 0.0f64;
    let steps = (t_end / dt).ceil() as usize;
    for step in 1..=steps {
        let t = step as f64 * dt;
        let lambda = history.lambda(t);
        let mut q: Vec<f64> = (0..nb)
            .map(|j| -sys.mass[j] * v[j] / dt - lambda * sys.load[j])
            .collect();
        q.extend(sys.capacities.iter().cloned());
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_gap_abs(1e-12)
            .tol_gap_rel(1e-12)
            .tol_feas(1e-12)
            .build()
            .ok()?;
        let mut solver = DefaultSolver::new(&p, &q, &a, &b, &cones, settings).ok()?;
        solver.solve();
        if !matches!(
            solver.solution.status,
            SolverStatus::Solved | SolverStatus::AlmostSolved
        ) {
            return None;
        }
        let x = &solver.solution.x;
        v.copy_from_slice(&x[..nb]);
        // the PLCP path's velocities, by the midpoint rule on its accelerations
        let acc = plcp_accelerations(an, history.lambda(t - 0.5 * dt));
        for j in 0..nb {
            v_plcp[j] += dt * acc[j];
        }
        if t > t_collapse + 10.0 * dt && t <= t_compare && slowing.is_none() {
            let scale = v_plcp.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
            let d = (0..nb)
                .filter(|&j| sys.mass[j] > 0.0)
                .fold(0.0f64, |m, j| m.max((v[j] - v_plcp[j]).abs()));
            deviation = d / scale;
        }
        // the plastic multiplier rate of every yield mode (system (9) assumes
        // that none ever decreases: x*_dd >= 0)
        let rate: Vec<f64> = x[nb..nb + np].iter().map(|r| r.max(0.0)).collect();
        if t <= t_collapse {
            // rigid: the rates are the interior-point solver's round-off
            continue;
        }
        global = rate.iter().fold(global, |g, &r| g.max(r));
        for k in 0..np {
            // modes with 1 % of the largest rate and more: below, the scheme's
            // O(dt) smearing of the breakpoints shows as small spurious rates
            if slowing.is_none() && peak[k] > 1e-2 * global && rate[k] < 0.97 * peak[k] {
                slowing = Some((t, sys.modes[k].section));
            }
            peak[k] = peak[k].max(rate[k]);
        }
    }
    Some(Stepped { slowing, deviation })
}

/// What the time stepping found.
struct Stepped {
    /// The first time a mode's rate fell below 97 % of its peak, and its section.
    slowing: Option<(f64, usize)>,
    /// The velocity difference to the PLCP path at the comparison time,
    /// relative to the largest PLCP velocity.
    deviation: f64,
}

/// The accelerations of the PLCP path at `lambda`, per coordinate of the system.
fn plcp_accelerations(a: &Analysis, lambda: f64) -> Vec<f64> {
    let Some(r) = a
        .reading
        .intervals
        .iter()
        .zip(&a.response.intervals)
        .find(|(i, _)| lambda >= i.lambda_from && lambda <= i.lambda_to)
        .map(|(_, r)| r)
    else {
        return vec![0.0; a.system.coordinates.len()];
    };
    a.system
        .coordinates
        .iter()
        .map(|c| {
            let [b, s] = r.accelerations[c.node][c.component.index()];
            b + s * lambda
        })
        .collect()
}

/// Steps per run at the coarser step size (the finer has twice as many).
const STEPS: f64 = 1000.0;
/// Relative drop of a flowing mode's rate below its peak reported as a deceleration.
const DECEL_TOL: f64 = 1e-6;

fn g6(x: f64) -> String {
    format!("{x:.4}")
}

/// End time of the runs: 1.3 times the PLCP path's first unloading, or its last breakpoint.
fn horizon(a: &Analysis) -> f64 {
    match a.reading.deactivations().first() {
        Some((l, _)) => 1.3 * a.scene.history.time_at(*l).unwrap_or(*l),
        None => {
            1.3 * a
                .reading
                .breakpoints
                .last()
                .map(|b| b.lambda)
                .unwrap_or(1.0)
        }
    }
}

/// The library integrator from rest to `t_end` with step `h`.
fn library_run(
    a: &Analysis,
    h: f64,
    t_end: f64,
) -> Result<frames::timestep::StepResponse, Box<dyn std::error::Error>> {
    use frames::timestep::{StepOptions, StepState, TimeStepping};
    let options = StepOptions {
        h,
        t_end,
        decel_tol: DECEL_TOL,
        ..StepOptions::default()
    };
    Ok(TimeStepping::new(&a.system, &a.scene.history, &options)?
        .run(&StepState::rest(&a.system))?)
}

/// The first `flow_stopped` event after which no mode of its section flows: the
/// hinge (not just one facet of its polygon) stops.
fn first_hinge_stop<'a>(
    a: &Analysis,
    r: &'a frames::timestep::StepResponse,
) -> Option<&'a frames::timestep::ModeEvent> {
    use frames::timestep::ModeEventKind;
    let mut flowing = vec![false; a.system.modes.len()];
    let mut i = 0;
    while i < r.events.len() {
        // the events of one step: starts first, then the stops
        let t = r.events[i].t;
        let j = i + r.events[i..].iter().take_while(|e| e.t == t).count();
        for e in &r.events[i..j] {
            if e.kind == ModeEventKind::FlowStarted {
                flowing[e.mode] = true;
            }
        }
        for e in &r.events[i..j] {
            if e.kind == ModeEventKind::FlowStopped {
                flowing[e.mode] = false;
            }
        }
        for e in &r.events[i..j] {
            if e.kind == ModeEventKind::FlowStopped
                && !a
                    .system
                    .modes
                    .iter()
                    .enumerate()
                    .any(|(k, m)| m.section == e.section && flowing[k])
            {
                return Some(e);
            }
        }
        i = j;
    }
    None
}
