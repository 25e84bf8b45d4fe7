//! `tbasis-gltf`: writes TANGENT attributes into glTF files (README: "tbasis-gltf").
//!
//! Exit status: 0 when every file was written, 1 when any file failed (each failure is reported
//! on stderr and leaves no output), 2 for a bad command line. With `--check`, which writes
//! nothing: 0 when no file would change, 1 when some would, 2 for a bad command line or a file
//! that failed.

use std::process::ExitCode;

use clap::Parser;
use tbasis_gltf::{args, batch, convert};

fn main() -> ExitCode {
    let args = args::Args::parse();
    let jobs = match args.jobs() {
        Ok(jobs) => jobs,
        Err(message) => {
            eprintln!("tbasis-gltf: {message}");
            return ExitCode::from(2);
        }
    };
    let parallelism = batch::Parallelism::on_this_machine(args.jobs, jobs.len());
    let settings = convert::Settings {
        options: args.options(),
        overwrite: args.overwrite,
        allow_outside_uris: args.allow_outside_uris,
        replace_side_files: args.force,
        threads: parallelism.threads,
        side_files: convert::SideFiles::default(),
    };
    let totals = batch::run(&jobs, &settings, parallelism.workers, args.quiet);
    if totals.failed > 0 && jobs.len() > 1 {
        eprintln!("tbasis-gltf: {} of {} files failed", totals.failed, jobs.len());
    }
    match (args.check, totals.failed, totals.changed) {
        (false, 0, _) | (true, 0, 0) => ExitCode::SUCCESS,
        (false, _, _) | (true, 0, _) => ExitCode::FAILURE,
        (true, _, _) => ExitCode::from(2),
    }
}
