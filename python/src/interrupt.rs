//! Ctrl-C during a long call. The work runs on a worker thread without the GIL, holding a
//! [`Cancel`] token; the calling thread waits for it, and every 50 ms takes the GIL back to
//! run Python's signal handlers (`PyErr_CheckSignals`). When a handler raises (Ctrl-C's
//! `KeyboardInterrupt`, or whatever a handler of the user's raises), the token is set, the
//! work stops at its next check (a growth's next frame, an evaluation's next control step, an
//! evolution's next evaluation), and the call raises that exception. Signals reach Python's
//! handlers only on the main thread, so a call made from another thread is not interrupted.

use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use ontogeny::cancel::{Cancel, Interrupted};
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError};
use pyo3::prelude::*;

/// How often the calling thread runs Python's signal handlers while the work goes on.
const SIGNAL_CHECK: Duration = Duration::from_millis(50);

/// The worker thread's stack: a main thread's usual 8 MiB, as the work would have had on the
/// calling thread.
const WORKER_STACK: usize = 8 << 20;

/// Runs `work` on a worker thread without the GIL and returns its result, or the exception
/// a signal handler raised while it ran (the work then stopped through its token).
pub fn interruptible<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&Cancel) -> T + Send,
{
    let cancel = Cancel::new();
    std::thread::scope(|scope| {
        let (sender, mut receiver) = mpsc::channel();
        let token = &cancel;
        let worker = std::thread::Builder::new()
            .name("ontogeny".into())
            .stack_size(WORKER_STACK)
            .spawn_scoped(scope, move || {
                // The receiver is gone only once the call has returned: nothing to tell.
                let _ = sender.send(work(token));
            })
            .map_err(|e| PyOSError::new_err(format!("cannot start a worker thread: {e}")))?;
        loop {
            // The receiver goes into the GIL-free wait and comes back out (it is not `Sync`).
            let (received, back) =
                py.detach(move || (receiver.recv_timeout(SIGNAL_CHECK), receiver));
            receiver = back;
            match received {
                Ok(result) => {
                    // It has sent its result: the thread ends at once.
                    let _ = py.detach(|| worker.join());
                    return Ok(result);
                }
                Err(RecvTimeoutError::Disconnected) => {
                    // The worker panicked before sending: its panic goes on here, where pyo3
                    // turns it into a Python exception.
                    match py.detach(|| worker.join()) {
                        Err(panic) => std::panic::resume_unwind(panic),
                        Ok(()) => unreachable!("a worker that ends sends its result"),
                    }
                }
                Err(RecvTimeoutError::Timeout) => {
                    if let Err(raised) = py.check_signals() {
                        cancel.cancel();
                        // Its result, whatever it is, is dropped with the call.
                        let _ = py.detach(|| worker.join());
                        return Err(raised);
                    }
                }
            }
        }
    })
}

/// Work that stopped through its token as Python sees it: `KeyboardInterrupt`. (The token is
/// set only when a signal handler has raised, and then the handler's exception is raised
/// instead; this is the answer should the work report it anyway.)
pub fn interrupted_error(e: Interrupted) -> PyErr {
    PyKeyboardInterrupt::new_err(e.to_string())
}
