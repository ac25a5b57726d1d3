//! A reader that goes away (`dpd orderings | head -1`) ends every command quietly with status
//! 0: stdout or stderr a pipe whose reader closed it before the first write, or after reading
//! one line of an output larger than the pipe's buffer.
use super::cli_support;

use cli_support::{write, TINY};
use std::io::{BufRead, BufReader, PipeWriter};
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};

/// Which of the child's streams is the closed pipe.
#[derive(Clone, Copy, Debug)]
enum Closed {
    Stdout,
    Stderr,
}

/// A pipe whose read end is already closed: every write to it fails with `BrokenPipe`.
fn readerless_pipe() -> PipeWriter {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    writer
}

fn spawn(dir: &Path, args: &[&str], closed: Closed) -> Child {
    let mut command = Command::new(env!("CARGO_BIN_EXE_dpd"));
    command.args(args).current_dir(dir).stdin(Stdio::null());
    match closed {
        Closed::Stdout => command.stdout(readerless_pipe()).stderr(Stdio::piped()),
        Closed::Stderr => command.stdout(Stdio::piped()).stderr(readerless_pipe()),
    };
    command.spawn().unwrap()
}

/// Assert status 0 and no word of a panic or an error on stderr (when it is open).
fn quiet(out: &Output, what: &str) {
    let text = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{what}: {text}");
    assert!(
        !text.contains("panicked") && !text.contains("error"),
        "{what}: {text}"
    );
}

#[test]
fn closed_stdout_ends_every_kind_of_command_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let cases: [&[&str]; 7] = [
        &["orderings", "--max-len", "6"],
        &["orderings", "--max-len", "4", "--json"],
        &["check", "BAOOAB"],
        &["check", "BAOOAB", "--json"],
        &["schemes"],
        &["run", "--scene", &scene, "--dt", "0.05"],
        &["run", "--scene", &scene, "--dt", "0.05", "--json"],
    ];
    for args in cases {
        let out = spawn(dir.path(), args, Closed::Stdout)
            .wait_with_output()
            .unwrap();
        quiet(&out, &args.join(" "));
    }
}

/// The first line printed stops the runs as Ctrl-C does: the command ends at once, with 0.
#[test]
fn closed_stdout_stops_the_runs_and_ends_with_status_zero() {
    let dir = tempfile::tempdir().unwrap();
    let items = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/papers");
    let args = [
        "reproduce",
        "003-table-1",
        "--quick",
        "--items",
        items.to_str().unwrap(),
        "--out",
        "q",
    ];
    let out = spawn(dir.path(), &args, Closed::Stdout)
        .wait_with_output()
        .unwrap();
    quiet(&out, "reproduce");
    // The header is printed before the runs start, so none of them finishes a point (the
    // whole item takes a few seconds).
    assert!(dir.path().join("q/003-table-1.quick.json").exists());
    assert!(
        !dir.path().join("q/003-table-1.quick.sweep.json").exists(),
        "the runs went on after the reader left"
    );
}

/// `dpd orderings | head -1` on an output larger than the pipe's buffer.
#[test]
fn reader_leaving_after_one_line_ends_the_command_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_dpd"))
        .args(["orderings", "--max-len", "6", "--json"])
        .current_dir(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert_eq!(first, "[\n");
    let out = child.wait_with_output().unwrap();
    quiet(&out, "orderings --max-len 6 --json | head -1");
}

/// A closed stderr (the header and the progress messages) loses nothing on stdout.
#[test]
fn closed_stderr_keeps_the_results() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let args = ["run", "--scene", &scene, "--dt", "0.05", "--json"];
    let out = spawn(dir.path(), &args, Closed::Stderr)
        .wait_with_output()
        .unwrap();
    quiet(&out, "run with stderr closed");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["stable"], true);
    let bad = spawn(dir.path(), &["check", "Q"], Closed::Stderr)
        .wait_with_output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2), "bad input keeps its exit code");
}
