//! Stopping long work from outside it: a [`Cancel`] token that a caller holds a clone of and
//! sets (from another thread: a watcher of Ctrl-C, a time limit), and that the library's long
//! loops check — growth between frames ([`develop::for_each_growth_frame`]), an evaluation
//! at every control step ([`task::TaskSpec::evaluate_watched`]), evolution between
//! evaluations ([`run::Run::set_cancel`]). Work whose token is set stops at its next
//! check with [`Interrupted`], writing nothing more; a token nobody sets (the default) changes
//! nothing, so the command line, which never sets one, never sees `Interrupted`.
//!
//! A check is one relaxed atomic load: far cheaper than the step of physics or derivation it
//! sits beside.
//!
//! [`develop::for_each_growth_frame`]: crate::develop::for_each_growth_frame
//! [`task::TaskSpec::evaluate_watched`]: crate::task::TaskSpec::evaluate_watched
//! [`run::Run::set_cancel`]: crate::run::Run::set_cancel

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A cancellation token: clones share one flag, which [`Cancel::cancel`] sets for good.
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// A token not yet set.
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Sets the token: work that checks it (or a clone) stops at its next check.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether the token has been set.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// `Err(Interrupted)` once the token has been set.
    pub fn check(&self) -> Result<(), Interrupted> {
        if self.is_cancelled() {
            Err(Interrupted)
        } else {
            Ok(())
        }
    }
}

/// Work stopped because its [`Cancel`] token was set, not because of anything in its input.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("interrupted")]
pub struct Interrupted;

#[cfg(test)]
mod tests {
    use super::{Cancel, Interrupted};

    #[test]
    fn a_clone_of_a_token_sees_it_set() {
        let token = Cancel::new();
        let held = token.clone();
        assert_eq!(held.check(), Ok(()));
        token.cancel();
        assert!(held.is_cancelled());
        assert_eq!(held.check(), Err(Interrupted));
        assert_eq!(Interrupted.to_string(), "interrupted");
    }

    #[test]
    fn separate_tokens_do_not_share_their_flag() {
        let one = Cancel::new();
        let other = Cancel::default();
        one.cancel();
        assert!(!other.is_cancelled());
    }
}
