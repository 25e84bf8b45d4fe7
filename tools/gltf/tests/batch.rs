//! A batch of files runs on several threads, by default one file per core at once, and prints
//! one line per file in the order the files were given, whichever finishes first; a large batch
//! shows a progress bar on a terminal, and nowhere else.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use common::fixture::Fixture;
use common::{needs, tool};
use serde_json::json;
use tbasis_gltf::batch::LARGE_BATCH;

/// A grid of `side` by `side` vertices whose UVs mirror at its middle column, 16-bit indices:
/// large enough to take far longer than the mirrored quad.
fn grid(side: usize) -> Fixture {
    let mut f = Fixture::empty_primitive();
    let (mut positions, mut texcoords, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    for y in 0..side {
        for x in 0..side {
            positions.push([x as f32, y as f32, ((x * 7 + y * 3) % 5) as f32 * 0.1]);
            texcoords.push([x.min(side - 1 - x) as f32 * 0.1, y as f32 * 0.1]);
        }
    }
    for y in 0..side - 1 {
        for x in 0..side - 1 {
            let v = (y * side + x) as u16;
            let s = side as u16;
            indices.extend([v, v + 1, v + s + 1, v, v + s + 1, v + s]);
        }
    }
    let position = f.floats(&positions, "VEC3", true);
    let normal = f.floats(&vec![[0.0f32, 0.0, 1.0]; positions.len()], "VEC3", false);
    let texcoord = f.floats(&texcoords, "VEC2", false);
    let indices = f.u16_indices(&indices);
    *f.primitive(0) = json!({ "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord }, "indices": indices, "mode": 4 });
    f
}

#[test]
fn summaries_follow_the_order_of_the_files() {
    let dir = tool::fresh_dir("batch-order");
    // The first file is slow, the others quick: on two threads the quick ones end first.
    let mut inputs = vec![grid(250).write_glb(&dir, "large")];
    inputs.extend((0..6).map(|k| Fixture::mirrored_quad().write_glb(&dir, &format!("quad{k}"))));
    let out = dir.join("out");
    let mut args = vec![
        "--jobs".into(),
        "2".into(),
        "--out-dir".into(),
        out.clone().into_os_string(),
    ];
    args.extend(inputs.iter().map(|input| input.clone().into_os_string()));
    let result = tool::run(&args);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(result.status.success(), "{stdout}");
    let named: Vec<&str> = stdout
        .lines()
        .map(|line| line.split(" -> ").next().unwrap_or(line))
        .collect();
    let given: Vec<String> = inputs.iter().map(|input| input.display().to_string()).collect();
    assert_eq!(named, given, "{stdout}");
    // The premise: the large file took longer than each quad (`..., 0.25 s` ends each line).
    let seconds = |line: &str| -> f64 {
        line.rsplit(", ")
            .next()
            .unwrap()
            .trim_end_matches(" s")
            .parse()
            .unwrap()
    };
    let times: Vec<f64> = stdout.lines().map(seconds).collect();
    assert!(times[1..].iter().all(|&t| t <= times[0]), "{stdout}");
}

/// `count` mirrored quads in `dir`, `quad0.glb` and on, named in an order other than their
/// names' (the last first), as the command line gives them.
fn quads(dir: &Path, count: usize) -> Vec<String> {
    let bytes = std::fs::read(Fixture::mirrored_quad().write_glb(dir, "quad")).expect("the quad");
    (0..count)
        .rev()
        .map(|k| {
            let name = format!("quad{k}.glb");
            std::fs::write(dir.join(&name), &bytes).expect("write a quad");
            name
        })
        .collect()
}

/// The file each line of a `--check` run's stdout is about: `NAME: would change ...`.
fn files_named(stdout: &str) -> Vec<&str> {
    stdout
        .lines()
        .map(|line| line.split(": ").next().unwrap_or(line))
        .collect()
}

/// `text` quoted for `sh`.
fn quoted(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

/// Runs the tool in `dir` with `args` (no quotes needed) on a pseudo-terminal, its stdout sent to
/// a file: how it ended, what came out on the terminal (its stderr alone) and its stdout.
fn run_on_terminal(dir: &Path, args: &[String]) -> (Output, String, String) {
    let line = format!(
        "{} {} > stdout.txt",
        quoted(env!("CARGO_BIN_EXE_tbasis-gltf")),
        args.join(" ")
    );
    let output = Command::new("script")
        .args(["-qec", &line, "/dev/null"])
        .current_dir(dir)
        // The shell `script` runs the line with; a terminal on which indicatif draws (it draws
        // nothing where TERM is unset or `dumb`).
        .env("SHELL", "/bin/sh")
        .env("TERM", "xterm")
        .stdin(Stdio::null())
        .output()
        .expect("script starts");
    let terminal = String::from_utf8_lossy(&output.stdout).into_owned();
    let stdout = std::fs::read_to_string(dir.join("stdout.txt")).expect("the tool's stdout");
    print!("{stdout}");
    eprintln!("on the terminal: {terminal:?}");
    (output, terminal, stdout)
}

/// Whether `terminal` shows the bar of a batch of `files`: `{bar} 3/8 files, 0s elapsed, ...`.
fn shows_bar(terminal: &str, files: usize) -> bool {
    terminal.contains(&format!("/{files} files, ")) && terminal.contains(" elapsed, about ")
}

#[test]
fn a_large_batch_shows_a_progress_bar_on_a_terminal() {
    if !needs::TERMINAL.found_or_skip() {
        return;
    }
    let dir = tool::fresh_dir("batch-bar");
    let given = quads(&dir, LARGE_BATCH);
    let mut args = vec!["--check".to_string()];
    args.extend(given.iter().cloned());
    let (output, terminal, stdout) = run_on_terminal(&dir, &args);
    // Every quad would change: status 1.
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    assert!(
        shows_bar(&terminal, LARGE_BATCH),
        "no progress bar on the terminal: {terminal:?}"
    );
    assert_eq!(files_named(&stdout), given, "{stdout}");
}

#[test]
fn a_smaller_batch_shows_no_progress_bar_on_a_terminal() {
    if !needs::TERMINAL.found_or_skip() {
        return;
    }
    let dir = tool::fresh_dir("batch-no-bar-small");
    let given = quads(&dir, LARGE_BATCH - 1);
    let mut args = vec!["--check".to_string()];
    args.extend(given.iter().cloned());
    let (output, terminal, stdout) = run_on_terminal(&dir, &args);
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    assert_eq!(terminal, "", "the terminal shows more than nothing");
    assert_eq!(files_named(&stdout), given, "{stdout}");
}

#[test]
fn quiet_shows_no_progress_bar_on_a_terminal() {
    if !needs::TERMINAL.found_or_skip() {
        return;
    }
    let dir = tool::fresh_dir("batch-no-bar-quiet");
    let given = quads(&dir, LARGE_BATCH);
    let mut args = vec!["--check".to_string(), "--quiet".to_string()];
    args.extend(given.iter().cloned());
    let (output, terminal, stdout) = run_on_terminal(&dir, &args);
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    assert_eq!(terminal, "", "the terminal shows more than nothing");
    assert_eq!(stdout, "");
}

#[test]
fn a_large_batch_shows_no_progress_bar_off_a_terminal() {
    let dir = tool::fresh_dir("batch-no-bar-pipe");
    let given = quads(&dir, LARGE_BATCH);
    let output = tool::command()
        .arg("--check")
        .args(&given)
        .current_dir(&dir)
        // As on a terminal where the bar draws: only stderr's being a pipe keeps it off.
        .env("TERM", "xterm")
        .stdin(Stdio::null())
        .output()
        .expect("tbasis-gltf starts");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    print!("{stdout}");
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    assert_eq!(stderr, "", "stderr holds more than nothing");
    assert_eq!(files_named(&stdout), given, "{stdout}");
}

/// By default as many files as there are cores are read at once, and their lines come out in the
/// order given whichever ends first. The inputs are named pipes (FIFOs): a file being read is one
/// whose pipe has a reader, which a non-blocking open for writing finds (it fails with ENXIO
/// without one). Holding the write end open, without writing, keeps its reader waiting, and so its
/// worker busy; with one more file than cores, the files read at once are the tool's workers.
#[cfg(target_os = "linux")]
#[test]
fn by_default_one_file_per_core_runs_at_once() {
    use rustix::fs::{Mode, OFlags};
    use std::os::fd::OwnedFd;
    use std::time::{Duration, Instant};

    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let dir = tool::fresh_dir("batch-cores");
    let files: Vec<PathBuf> = (0..=cores).map(|k| dir.join(format!("pipe{k}.glb"))).collect();
    for file in &files {
        rustix::fs::mknodat(
            rustix::fs::CWD,
            file,
            rustix::fs::FileType::Fifo,
            Mode::RUSR | Mode::WUSR,
            0,
        )
        .expect("make a FIFO");
    }
    let bytes = std::fs::read(Fixture::mirrored_quad().write_glb(&dir, "quad")).expect("the quad");
    let child = tool::command()
        .arg("--check")
        .args(&files)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("tbasis-gltf starts");
    // A failed test must not leave the tool waiting on a FIFO.
    let mut child = KillOnDrop(Some(child));
    // The write end of `file`, if something has it open for reading.
    let open_if_read = |file: &Path| -> Option<OwnedFd> {
        match rustix::fs::open(file, OFlags::WRONLY | OFlags::NONBLOCK | OFlags::CLOEXEC, Mode::empty()) {
            Ok(fd) => Some(fd),
            Err(rustix::io::Errno::NXIO) => None,
            Err(e) => panic!("{}: {e}", file.display()),
        }
    };
    // Long enough for a loaded machine to start the tool and its threads; only a failure waits it
    // out.
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut writers: Vec<Option<OwnedFd>> = files.iter().map(|_| None).collect();
    loop {
        for (file, writer) in files.iter().zip(&mut writers) {
            if writer.is_none() {
                *writer = open_if_read(file);
            }
        }
        let being_read = writers.iter().filter(|writer| writer.is_some()).count();
        if being_read >= cores || Instant::now() > deadline {
            break;
        }
        if let Some(status) = child.get().try_wait().expect("wait for the tool") {
            panic!("the tool ended ({status}) with {being_read} of its files being read");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    // A worker too many would open the last file as well: it gets a moment to.
    let settled = Instant::now() + Duration::from_millis(200);
    while Instant::now() < settled && writers[cores].is_none() {
        writers[cores] = open_if_read(&files[cores]);
        std::thread::sleep(Duration::from_millis(5));
    }
    let read: Vec<usize> = (0..files.len()).filter(|&k| writers[k].is_some()).collect();
    // The first `cores` files, in the order given: the last waits for a free worker.
    assert_eq!(
        read,
        (0..cores).collect::<Vec<_>>(),
        "files read at once with {cores} cores"
    );
    // The files then get their bytes out of order: the last one read first, then the one that
    // waited (which a worker takes only once a file is done: that one), then the others back to
    // the first. So the first file ends after others, whose lines must wait for its own.
    let mut order: Vec<usize> = (0..cores).rev().collect();
    order.insert(1, cores);
    let deadline = Instant::now() + Duration::from_secs(60);
    for k in order {
        let writer = loop {
            if let Some(writer) = writers[k].take().or_else(|| open_if_read(&files[k])) {
                break writer;
            }
            assert!(Instant::now() < deadline, "{} never read", files[k].display());
            std::thread::sleep(Duration::from_millis(5));
        };
        std::io::Write::write_all(&mut std::fs::File::from(writer), &bytes).expect("write into the FIFO");
    }
    let output = child
        .0
        .take()
        .expect("the tool")
        .wait_with_output()
        .expect("wait for the tool");
    let stdout = String::from_utf8_lossy(&output.stdout);
    print!("{stdout}");
    eprint!("{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    let given: Vec<String> = files.iter().map(|file| file.display().to_string()).collect();
    assert_eq!(files_named(&stdout), given, "{stdout}");
}

/// A child process, killed and waited for if it is still there when this is dropped.
struct KillOnDrop(Option<std::process::Child>);

impl KillOnDrop {
    fn get(&mut self) -> &mut std::process::Child {
        self.0.as_mut().expect("the child")
    }
}

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        if let Some(mut child) = self.0.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}
