//! Progress bars for the long-running command lines (the `cli` feature).
//!
//! A bar is drawn on stderr only when stderr is a terminal and the caller did
//! not ask for quiet (`--quiet`): piped or redirected output, CI logs and the
//! test suite see nothing, and stdout (the report) is never touched. Drawing is
//! by `indicatif`. The hook per breakpoint of a trace comes with the path
//! observer; until then the command lines tick where their loops already are
//! (cases of a report, inputs of the fuzz run, phases of a frame analysis).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::time::Duration;

/// A progress bar or spinner on stderr, or nothing (not a terminal, or quiet).
///
/// ```
/// // in a test or a pipe stderr is no terminal: the bar draws nothing
/// let bar = plcp::progress::Progress::bar(3, "cases", false);
/// for _ in 0..3 {
///     bar.inc(1);
/// }
/// bar.finish();
/// ```
#[derive(Clone)]
pub struct Progress {
    bar: Option<ProgressBar>,
}

/// Whether a bar may be drawn: stderr is a terminal and `quiet` is off.
pub fn enabled(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

impl Progress {
    /// A bar of `len` steps labelled `what` (`cases`, `inputs`), with the
    /// elapsed time and an estimate of the time left.
    pub fn bar(len: u64, what: &str, quiet: bool) -> Self {
        if !enabled(quiet) {
            return Self::hidden();
        }
        let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
        let style = ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] {pos}/{len} {prefix} (eta {eta}) {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
        bar.set_style(style);
        bar.set_prefix(what.to_string());
        Self { bar: Some(bar) }
    }

    /// A spinner for work of unknown length, showing `message` (the phase).
    pub fn spinner(message: &str, quiet: bool) -> Self {
        if !enabled(quiet) {
            return Self::hidden();
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
        let style = ProgressStyle::with_template("{spinner} {elapsed_precise} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner());
        bar.set_style(style);
        bar.set_message(message.to_string());
        bar.enable_steady_tick(Duration::from_millis(120));
        Self { bar: Some(bar) }
    }

    /// Draws nothing (for `--quiet`, or where no bar is wanted).
    pub fn hidden() -> Self {
        Self { bar: None }
    }

    /// Advances the bar by `n` steps.
    pub fn inc(&self, n: u64) {
        if let Some(b) = &self.bar {
            b.inc(n);
        }
    }

    /// Sets the bar's position (for loops that count themselves, in threads).
    pub fn set_position(&self, pos: u64) {
        if let Some(b) = &self.bar {
            b.set_position(pos);
        }
    }

    /// Replaces the message after the bar (the current case or phase).
    pub fn message(&self, message: &str) {
        if let Some(b) = &self.bar {
            b.set_message(message.to_string());
        }
    }

    /// Prints a line above the bar (a plain `eprintln!` would be overdrawn).
    pub fn println(&self, line: &str) {
        match &self.bar {
            Some(b) => b.println(line),
            None => eprintln!("{line}"),
        }
    }

    /// Runs `f` with the bar hidden, for printing to stdout while a bar is on
    /// the same terminal (the bar is redrawn after).
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        match &self.bar {
            Some(b) => b.suspend(f),
            None => f(),
        }
    }

    /// Removes the bar from the terminal.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}
