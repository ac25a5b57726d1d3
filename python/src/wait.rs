//! Long work without the GIL that Ctrl-C still stops.

use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

/// How often the waiting thread looks for a pending signal (Ctrl-C).
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Run `work` on a worker thread with the GIL released, while this thread waits and checks
/// for signals. On a signal, `stop` is set (the work is expected to end soon after), the work
/// is waited for and the signal's exception (`KeyboardInterrupt`) is returned.
pub fn interruptible<R: Send>(
    py: Python<'_>,
    stop: &AtomicBool,
    work: impl FnOnce() -> R + Send,
) -> PyResult<R> {
    let mut signal = None;
    let result = py.allow_threads(|| {
        let (done, finished) = mpsc::channel();
        std::thread::scope(|s| {
            let worker = s.spawn(move || {
                let r = work();
                // The receiver outlives this thread: the send cannot fail.
                let _ = done.send(());
                r
            });
            while let Err(mpsc::RecvTimeoutError::Timeout) = finished.recv_timeout(SIGNAL_POLL) {
                if signal.is_none() {
                    if let Err(e) = Python::with_gil(|py| py.check_signals()) {
                        stop.store(true, Ordering::Relaxed);
                        signal = Some(e);
                    }
                }
            }
            worker.join()
        })
    });
    let result = result.unwrap_or_else(|panic| std::panic::resume_unwind(panic));
    match signal {
        Some(e) => Err(e),
        None => Ok(result),
    }
}
