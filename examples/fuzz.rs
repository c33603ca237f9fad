//! Fuzz harness over plcp's JSON and Siconos `.dat` readers, the frames scene
//! reader, and the solvers on arbitrary small problems (see
//! `examples/common/fuzz_core.rs` for what each input is).
//!
//! ```text
//! cargo run --release --example fuzz -- N [--seed S] [--threads T] [--only I] [--quiet]
//! ```
//!
//! Runs inputs `0..N` (or only input `I`), every call under `catch_unwind`.
//! Prints a summary table; each distinct panic is printed with the input that
//! caused it and saved to `out/fuzz-panic-K.txt`. Inputs over 1 s are listed
//! (a watchdog prints any input still running after 10 s). Exit code 1 if
//! anything panicked.

#[path = "common/fuzz_core.rs"]
mod fuzz_core;

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut n: u64 = 10_000;
    let mut seed: u64 = 20261121;
    let mut threads: u64 = 1;
    let mut only: Option<u64> = None;
    let mut quiet = false;
    let mut i = 0;
    while i < args.len() {
        let next = |i: usize| -> u64 {
            args.get(i + 1)
                .and_then(|s| s.replace('_', "").parse::<f64>().ok())
                .map(|v| v as u64)
                .unwrap_or_else(|| {
                    eprintln!("error: {} needs a number", args[i]);
                    std::process::exit(2)
                })
        };
        match args[i].as_str() {
            "--seed" => {
                seed = next(i);
                i += 1;
            }
            "--threads" => {
                threads = next(i).max(1);
                i += 1;
            }
            "--quiet" | "-q" => quiet = true,
            "--only" => {
                only = Some(next(i));
                i += 1;
            }
            s => {
                n = s
                    .replace('_', "")
                    .parse::<f64>()
                    .map(|v| v as u64)
                    .unwrap_or_else(|_| {
                        eprintln!("usage: fuzz N [--seed S] [--threads T] [--only I] [--quiet]");
                        std::process::exit(2)
                    })
            }
        }
        i += 1;
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let scenes = Arc::new(fuzz_core::read_scenes(&root.join("scenes")));
    fuzz_core::install_hook();
    let t0 = Instant::now();

    if let Some(idx) = only {
        let mut sum = fuzz_core::Summary::default();
        fuzz_core::run_one(&mut sum, seed, idx, &scenes);
        sum.inputs = 1;
        sum.seconds = t0.elapsed().as_secs_f64();
        print!("{}", sum.table());
        println!("input #{idx}: {}", sum.last_desc);
        for (_, msg, _, desc) in sum.distinct.values() {
            println!("\npanic: {msg}\ninput: {desc}");
        }
        return;
    }

    println!(
        "fuzz: {n} inputs, seed {seed}, {threads} thread(s), {} scenes",
        scenes.len()
    );
    // watchdog: one slot per thread holding (index, start in ms since t0)
    let slots: Arc<Vec<(AtomicU64, AtomicU64)>> = Arc::new(
        (0..threads)
            .map(|_| (AtomicU64::new(u64::MAX), AtomicU64::new(0)))
            .collect(),
    );
    let done = Arc::new(AtomicU64::new(0));
    // a bar on a terminal (not with --quiet), fed by the watchdog from the slots
    let bar = Arc::new(plcp::progress::Progress::bar(n, "inputs", quiet));
    let chunk = n.div_ceil(threads);
    {
        let (slots, done, bar) = (slots.clone(), done.clone(), bar.clone());
        std::thread::spawn(move || {
            let mut last = vec![u64::MAX; slots.len()];
            let mut since = vec![Instant::now(); slots.len()];
            let mut warned = vec![u64::MAX; slots.len()];
            let mut finished = vec![false; slots.len()];
            while done.load(Ordering::Relaxed) == 0 {
                std::thread::sleep(Duration::from_millis(500));
                let mut pos = 0;
                for (k, (idx, _)) in slots.iter().enumerate() {
                    let cur = idx.load(Ordering::Relaxed);
                    let lo = (k as u64 * chunk).min(n);
                    if cur == u64::MAX {
                        // not started, or done with its range
                        finished[k] |= last[k] != u64::MAX;
                        if finished[k] {
                            pos += ((k as u64 + 1) * chunk).min(n) - lo;
                        }
                        continue;
                    }
                    pos += cur.saturating_sub(lo);
                    if cur != last[k] {
                        last[k] = cur;
                        since[k] = Instant::now();
                    } else if since[k].elapsed() > Duration::from_secs(10) && warned[k] != cur {
                        warned[k] = cur;
                        bar.println(&format!("WATCHDOG: input #{cur} has run for over 10 s (possible hang; reproduce with --only {cur})"));
                    }
                }
                bar.set_position(pos);
            }
        });
    }
    let handles: Vec<_> = (0..threads)
        .map(|k| {
            let (scenes, slots, bar) = (scenes.clone(), slots.clone(), bar.clone());
            std::thread::spawn(move || {
                let lo = (k * chunk).min(n);
                let hi = ((k + 1) * chunk).min(n);
                let sum = fuzz_core::run_range(
                    seed,
                    lo..hi,
                    &scenes,
                    1.0,
                    Some(&slots[k as usize].0),
                    |s| {
                        if k == 0 {
                            bar.println(&format!(
                                "  thread 0: {} inputs, {:.0} inputs/s, {} panics",
                                s.inputs,
                                s.inputs as f64 / s.seconds.max(1e-9),
                                s.panics
                            ));
                        }
                    },
                );
                slots[k as usize].0.store(u64::MAX, Ordering::Relaxed);
                sum
            })
        })
        .collect();
    let mut sum = fuzz_core::Summary::default();
    for h in handles {
        sum.merge(h.join().expect("fuzz threads catch every panic"));
    }
    done.store(1, Ordering::Relaxed);
    bar.finish();
    sum.seconds = t0.elapsed().as_secs_f64();
    println!("{}", sum.table());
    println!(
        "rate: {:.0} inputs/s ({threads} thread(s))",
        sum.inputs as f64 / sum.seconds.max(1e-9)
    );
    if !sum.distinct.is_empty() {
        let out = root.join("out");
        let _ = std::fs::create_dir_all(&out);
        for (k, (count, msg, idx, desc)) in sum.distinct.values().enumerate() {
            let file = out.join(format!("fuzz-panic-{k}.txt"));
            let text = format!(
                "panic ({count} times): {msg}\nfirst input: #{idx} (seed {seed}; reproduce: cargo run --release --example fuzz -- 1 --seed {seed} --only {idx})\n\n{desc}\n"
            );
            let _ = std::fs::write(&file, &text);
            println!("\n=== distinct panic {k} -> {}\n{text}", file.display());
        }
        std::process::exit(1);
    }
}
