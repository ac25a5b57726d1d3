//! Progress bars and Ctrl-C for the commands that run simulations.

use indicatif::{ProgressBar, ProgressStyle};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Once;

static STOP: AtomicBool = AtomicBool::new(false);

/// The flag that Ctrl-C sets. The first Ctrl-C asks the runs to stop after their current
/// chunk of steps and keeps what is finished; a second one exits at once.
pub fn stop_flag() -> &'static AtomicBool {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let installed = ctrlc::set_handler(|| {
            if STOP.swap(true, Ordering::SeqCst) {
                std::process::exit(super::INTERRUPTED.into());
            }
            errln!("\ndpd: stopping, finished results are kept (Ctrl-C again to abort)");
        });
        if let Err(e) = installed {
            errln!("dpd: warning: Ctrl-C will not stop cleanly: {e}");
        }
    });
    &STOP
}

/// Ask the runs to stop as the first Ctrl-C does (the reader of stdout went away).
pub fn stop() {
    STOP.store(true, Ordering::SeqCst);
}

/// A bar over `total` steps on stderr (drawn only on a terminal).
pub fn bar(total: u64, message: String) -> ProgressBar {
    let bar = ProgressBar::new(total);
    let style = ProgressStyle::with_template(
        "{elapsed_precise} [{wide_bar}] {percent:>3}% eta {eta:>4} {msg}",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar.set_message(message);
    bar
}
