//! Many files at once: a pool of threads (by default one per core), one summary line per file in
//! the order the files were given, a progress bar for large batches.

use std::io::Write;
use std::num::NonZeroUsize;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

use indicatif::{ProgressBar, ProgressStyle};

use crate::args::Job;
use crate::convert::{convert, Outcome, Settings};

/// From this many files on, a progress bar shows (on a terminal only).
pub const LARGE_BATCH: usize = 8;

/// How a batch shares the cores: files at once, and threads for each file's primitives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parallelism {
    /// Files converted at once: the threads of [`run`].
    pub workers: usize,
    /// Threads for the primitives of each file ([`Settings::threads`]).
    pub threads: usize,
}

impl Parallelism {
    /// `jobs` files at once (`--jobs`), by default one per core, never more than there are
    /// `files` nor fewer than one. Cores the file workers leave idle go to the primitives of each
    /// file.
    pub fn new(jobs: Option<NonZeroUsize>, cores: usize, files: usize) -> Self {
        let workers = jobs.map_or(cores, usize::from).min(files).max(1);
        Parallelism {
            workers,
            threads: (cores / workers).max(1),
        }
    }

    /// [`Parallelism::new`] with the cores this process may use, as the standard library counts
    /// them (`available_parallelism`: CPU affinity and cgroup quotas included), or 1 when that is
    /// not known.
    pub fn on_this_machine(jobs: Option<NonZeroUsize>, files: usize) -> Self {
        let cores = std::thread::available_parallelism().map_or(1, usize::from);
        Self::new(jobs, cores, files)
    }
}

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
    let report = Mutex::new(InOrder::new(jobs.len()));
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
        // Nothing panics while holding the lock (writes that fail are dropped), so a poisoned
        // one cannot hold a half-made state.
        let mut report = report.lock().unwrap_or_else(PoisonError::into_inner);
        report.slots[index] = Slot::Done(line);
        if report.ready() {
            bar.suspend(|| report.print_ready(print));
        }
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
    slots: Vec<Slot>,
}

/// A file of the batch, as far as its line goes.
enum Slot {
    /// Not done yet.
    Pending,
    /// Done, with its line if it has one.
    Done(Option<Line>),
    /// Its line was printed (or it had none).
    Printed,
}

/// A file's line, for stdout or stderr.
#[derive(Debug, PartialEq)]
enum Line {
    Out(String),
    Err(String),
}

impl InOrder {
    fn new(files: usize) -> Self {
        InOrder {
            next: 0,
            slots: (0..files).map(|_| Slot::Pending).collect(),
        }
    }

    /// Whether the next file to print is done.
    fn ready(&self) -> bool {
        matches!(self.slots.get(self.next), Some(Slot::Done(_)))
    }

    /// Hands `emit` the lines of the done files that no unfinished file precedes, in order.
    fn print_ready(&mut self, mut emit: impl FnMut(Line)) {
        while self.ready() {
            if let Slot::Done(Some(line)) = std::mem::replace(&mut self.slots[self.next], Slot::Printed) {
                emit(line);
            }
            self.next += 1;
        }
    }
}

/// Writes a line where it belongs. A closed stdout (`tbasis-gltf ... | head`) loses the lines
/// after it, not the errors, and stops nothing.
fn print(line: Line) {
    let _ = match line {
        Line::Out(text) => writeln!(std::io::stdout().lock(), "{text}"),
        Line::Err(text) => writeln!(std::io::stderr().lock(), "{text}"),
    };
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
    fn lines_come_out_in_the_order_of_the_files_whatever_the_order_they_end_in() {
        let mut lines = InOrder::new(4);
        let mut printed = Vec::new();
        for (file, line) in [(2, Some("c")), (1, None), (3, Some("d")), (0, Some("a"))] {
            lines.slots[file] = Slot::Done(line.map(|text: &str| Line::Out(text.to_string())));
            lines.print_ready(|line| printed.push(line));
            // Nothing before file 0 ends; then all of it, file 1 without a line.
            let expected: &[&str] = if file == 0 { &["a", "c", "d"] } else { &[] };
            let expected: Vec<Line> = expected.iter().map(|text| Line::Out(text.to_string())).collect();
            assert_eq!(printed, expected, "after file {file}");
        }
        assert!(!lines.ready());
    }

    /// `--jobs N`, given as a number.
    fn jobs(n: usize) -> Option<NonZeroUsize> {
        Some(NonZeroUsize::new(n).expect("not 0"))
    }

    #[test]
    fn by_default_one_file_per_core_runs_at_once() {
        for cores in [1, 2, 3, 8, 64] {
            let parallelism = Parallelism::new(None, cores, 1000);
            assert_eq!(
                parallelism,
                Parallelism {
                    workers: cores,
                    threads: 1
                },
                "{cores} cores"
            );
        }
    }

    #[test]
    fn no_more_files_run_at_once_than_there_are_files() {
        // The cores the files leave idle go to their primitives.
        assert_eq!(Parallelism::new(None, 8, 3), Parallelism { workers: 3, threads: 2 });
        assert_eq!(Parallelism::new(None, 8, 1), Parallelism { workers: 1, threads: 8 });
        assert_eq!(Parallelism::new(jobs(4), 8, 2), Parallelism { workers: 2, threads: 4 });
        // Never none, whatever is asked.
        assert_eq!(Parallelism::new(None, 8, 0), Parallelism { workers: 1, threads: 8 });
        assert_eq!(Parallelism::new(None, 0, 5), Parallelism { workers: 1, threads: 1 });
    }

    #[test]
    fn jobs_sets_the_files_at_once_whatever_the_cores() {
        assert_eq!(
            Parallelism::new(jobs(2), 8, 100),
            Parallelism { workers: 2, threads: 4 }
        );
        assert_eq!(
            Parallelism::new(jobs(3), 8, 100),
            Parallelism { workers: 3, threads: 2 }
        );
        assert_eq!(
            Parallelism::new(jobs(1), 6, 100),
            Parallelism { workers: 1, threads: 6 }
        );
        // More than the cores: each file gets one thread.
        assert_eq!(
            Parallelism::new(jobs(16), 4, 100),
            Parallelism {
                workers: 16,
                threads: 1
            }
        );
    }

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
