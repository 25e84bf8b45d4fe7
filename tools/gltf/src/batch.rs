//! Many files at once: a pool of threads, one summary line per file in the order the files were
//! given, a progress bar for large batches.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use indicatif::{ProgressBar, ProgressStyle};

use crate::args::Job;
use crate::convert::{convert, Outcome, Settings};

/// From this many files on, a progress bar shows (on a terminal only).
const LARGE_BATCH: usize = 8;

/// How a batch went.
pub struct Totals {
    /// Files that could not be converted (or, with `--check`, read and computed).
    pub failed: usize,
    /// Files that were, or with `--check` would be, changed.
    pub changed: usize,
}

/// Converts every job on `workers` threads.
pub fn run(jobs: &[Job], settings: &Settings, workers: usize, quiet: bool) -> Totals {
    let bar = if jobs.len() >= LARGE_BATCH && !quiet {
        let bar = ProgressBar::new(jobs.len() as u64);
        let style = ProgressStyle::with_template("{bar:40} {pos}/{len} files, {elapsed} elapsed, about {eta} left")
            .unwrap_or_else(|_| ProgressStyle::default_bar());
        bar.set_style(style);
        bar
    } else {
        ProgressBar::hidden()
    };
    let next = AtomicUsize::new(0);
    let failed = AtomicUsize::new(0);
    let changed = AtomicUsize::new(0);
    let report = Mutex::new(InOrder {
        next: 0,
        waiting: (0..jobs.len()).map(|_| None).collect(),
    });
    let work = || loop {
        let index = next.fetch_add(1, Ordering::Relaxed);
        let Some(job) = jobs.get(index) else {
            break;
        };
        let result = caught(|| convert(job, settings));
        let line = match &result {
            Ok(outcome) if !quiet => Some(Line::Out(summary(job, outcome))),
            Ok(_) => None,
            Err(message) => Some(Line::Err(format!("tbasis-gltf: {}: {message}", job.input.display()))),
        };
        // A poisoned lock only means another thread panicked while printing; the lines stand.
        let mut report = report.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        report.waiting[index] = Some(line);
        bar.suspend(|| report.print_ready());
        drop(report);
        match &result {
            Ok(outcome) if outcome.changes() => {
                changed.fetch_add(1, Ordering::Relaxed);
            }
            Ok(_) => {}
            Err(_) => {
                failed.fetch_add(1, Ordering::Relaxed);
            }
        }
        bar.inc(1);
    };
    std::thread::scope(|scope| {
        for _ in 1..workers.clamp(1, jobs.len().max(1)) {
            scope.spawn(work);
        }
        work();
    });
    bar.finish_and_clear();
    Totals {
        failed: failed.into_inner(),
        changed: changed.into_inner(),
    }
}

/// The summary lines of a batch, printed in the order of its files: a file's line waits until
/// every file before it has printed its own.
struct InOrder {
    /// The first file whose line is not printed yet.
    next: usize,
    /// Per file: `Some` once it is done, with its line if it has one.
    waiting: Vec<Option<Option<Line>>>,
}

/// A file's line, for stdout or stderr.
enum Line {
    Out(String),
    Err(String),
}

impl InOrder {
    /// Prints the lines of the done files that no unfinished file precedes.
    fn print_ready(&mut self) {
        while let Some(done) = self.waiting.get_mut(self.next).and_then(Option::take) {
            match done {
                Some(Line::Out(line)) => println!("{line}"),
                Some(Line::Err(line)) => eprintln!("{line}"),
                None => {}
            }
            self.next += 1;
        }
    }
}

/// `in.glb -> out.glb: 3 primitives done, 120 vertices added, 0.25 s`, or with `--check`
/// `in.glb: would change 3 primitives, 120 vertices added, 0 corners repaired` (or `in.glb:
/// nothing to change`), then one indented line per primitive left as it was.
fn summary(job: &Job, outcome: &Outcome) -> String {
    let plural = |n: usize, word: &str| format!("{n} {word}{}", if n == 1 { "" } else { "s" });
    let vertices = plural(outcome.vertices_added, "vertex").replace("vertexs", "vertices");
    let corners = plural(outcome.repaired_corners, "corner");
    let mut line = match &job.output {
        None if outcome.changes() => format!(
            "{}: would change {}, {vertices} added, {corners} repaired",
            job.input.display(),
            plural(outcome.done, "primitive"),
        ),
        None => format!("{}: nothing to change", job.input.display()),
        Some(output) => format!(
            "{} -> {}: {} done, {vertices} added, {:.2} s",
            job.input.display(),
            output.display(),
            plural(outcome.done, "primitive"),
            outcome.elapsed.as_secs_f64()
        ),
    };
    if job.output.is_some() && outcome.repaired_corners > 0 {
        line += &format!(", {corners} repaired");
    }
    if !outcome.left.is_empty() {
        line += &format!(", {} left as it was:", plural(outcome.left.len(), "primitive"));
        for left in &outcome.left {
            line += &format!("\n  {left}");
        }
    }
    line
}

/// What `work` returns, or an error with the message of its panic: a bug met in one file must
/// not end the batch.
fn caught<T>(work: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    // `panic.as_ref()`: the payload itself. `&panic` would coerce to a `dyn Any` holding the box,
    // in which no downcast finds the message.
    catch_unwind(AssertUnwindSafe(work))
        .map_err(|panic| format!("internal error: {}", panic_message(panic.as_ref())))?
}

/// What a panic said, from its payload.
fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_caught_panic_gives_its_message() {
        let quiet = std::panic::take_hook();
        std::panic::set_hook(Box::new(|_| {}));
        let literal = caught(|| -> Result<(), String> { panic!("a literal") });
        let formatted = caught(|| -> Result<(), String> { panic!("index {} out of range", 7) });
        std::panic::set_hook(quiet);
        assert_eq!(literal, Err("internal error: a literal".to_string()));
        assert_eq!(formatted, Err("internal error: index 7 out of range".to_string()));
        assert_eq!(caught(|| Ok(3)), Ok(3));
    }
}
