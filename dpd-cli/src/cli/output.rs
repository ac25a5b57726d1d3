//! Everything the program prints goes through here, so that a reader that goes away ends every
//! command the same way: quietly, with status 0 (`dpd orderings | head -1`).
//!
//! Rust ignores SIGPIPE, so a write to a pipe whose reader has closed it fails with
//! `BrokenPipe`, and `println!` turns that failure into a panic (exit code 101 and a backtrace).
//! [`outln!`] and [`errln!`] write without panicking instead (`dpd-cli/clippy.toml` refuses
//! `println!` and its kin in this crate). The first failed write to stdout silences it for the
//! rest of the run and stops the runs as Ctrl-C does, so the finished results are saved; then
//! [`finish`] gives status 0 for a closed pipe, or 1 with a message for any other failure (a
//! full disk: what was printed is lost). A failed write to stderr is ignored: there is nowhere
//! left to report it, and the results on stdout and in files are unaffected.

use super::{progress, INTERRUPTED};
use std::fmt;
use std::io::{self, Write};
use std::process::ExitCode;
use std::sync::OnceLock;

/// The first error of a write to stdout; nothing is written after it.
static STDOUT_FAILED: OnceLock<io::Error> = OnceLock::new();

/// `print!` to stdout without a panic on a closed pipe.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::output::stdout(format_args!($($arg)*))
    };
}

/// `println!` to stdout without a panic on a closed pipe.
macro_rules! outln {
    () => {
        $crate::cli::output::stdout(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::cli::output::stdout(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `eprint!` to stderr without a panic on a closed pipe.
macro_rules! err {
    ($($arg:tt)*) => {
        $crate::cli::output::stderr(format_args!($($arg)*))
    };
}

/// `eprintln!` to stderr without a panic on a closed pipe.
macro_rules! errln {
    () => {
        $crate::cli::output::stderr(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::cli::output::stderr(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// Write to stdout unless an earlier write failed; a failure stops the runs.
pub fn stdout(text: fmt::Arguments<'_>) {
    if STDOUT_FAILED.get().is_some() {
        return;
    }
    if let Err(e) = io::stdout().lock().write_fmt(text) {
        stdout_failed(e);
    }
}

/// Write to stderr, ignoring a failure.
pub fn stderr(text: fmt::Arguments<'_>) {
    let _ = io::stderr().lock().write_fmt(text);
}

fn stdout_failed(e: io::Error) {
    // Only the first error is kept: it is the one that says why the output ended.
    let _ = STDOUT_FAILED.set(e);
    progress::stop();
}

/// The exit code of a command that returned `code`, once what it printed is flushed: 0 when
/// the reader of stdout went away (the runs it stopped are reported as interrupted, which is
/// then no failure), 1 when stdout failed otherwise, else `code`.
pub fn finish(code: ExitCode) -> ExitCode {
    if STDOUT_FAILED.get().is_none() {
        if let Err(e) = io::stdout().lock().flush() {
            stdout_failed(e);
        }
    }
    match STDOUT_FAILED.get() {
        None => code,
        Some(e) if e.kind() == io::ErrorKind::BrokenPipe => {
            if code == ExitCode::from(INTERRUPTED) {
                ExitCode::SUCCESS
            } else {
                code
            }
        }
        Some(e) => {
            errln!("dpd: error: cannot write to stdout: {e}");
            ExitCode::FAILURE
        }
    }
}
