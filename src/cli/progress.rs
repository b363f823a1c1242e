//! Progress of long work on a terminal: a bar on standard error once the work has run for
//! [`SHOW_AFTER`] seconds and looks to need more than [`SHOW_IF_LONGER`] in all; nothing
//! when standard error is not a terminal (pipes, logs, tests stay clean).

use std::io::IsTerminal;
use std::time::Instant;

/// Seconds of work before a bar may appear.
pub const SHOW_AFTER: f64 = 1.0;

/// The least expected duration (s) of work that gets a bar.
pub const SHOW_IF_LONGER: f64 = 2.0;

/// Whether work that has run `elapsed` seconds and is `fraction` done deserves a bar: it has
/// run [`SHOW_AFTER`] seconds and, at its pace so far, takes more than [`SHOW_IF_LONGER`].
pub fn worth_showing(elapsed: f64, fraction: f64) -> bool {
    elapsed >= SHOW_AFTER && fraction < 1.0 && elapsed / fraction.max(1e-9) > SHOW_IF_LONGER
}

/// A progress bar that shows itself only on a terminal and only for long work, in the style
/// of `evolve`'s.
pub struct Progress {
    what: String,
    terminal: bool,
    started: Instant,
    bar: Option<indicatif::ProgressBar>,
}

impl Progress {
    /// Progress of `what` (e.g. "walker"), shown on standard error if it is a terminal.
    pub fn new(what: impl Into<String>) -> Progress {
        Progress::on(what, std::io::stderr().is_terminal())
    }

    /// Progress shown only if `terminal` (and standard error is one: indicatif draws
    /// nowhere else).
    pub fn on(what: impl Into<String>, terminal: bool) -> Progress {
        Progress {
            what: what.into(),
            terminal,
            started: Instant::now(),
            bar: None,
        }
    }

    /// The work is `fraction` (0 to 1) done.
    pub fn set(&mut self, fraction: f64) {
        if !self.terminal {
            return;
        }
        if self.bar.is_none() {
            if !worth_showing(self.started.elapsed().as_secs_f64(), fraction) {
                return;
            }
            let bar = indicatif::ProgressBar::new(1000);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:30} {msg} {percent}%  [{elapsed_precise}, {eta} left]",
                )
                .expect("a valid template"),
            );
            bar.set_message(self.what.clone());
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            bar.set_position((fraction.clamp(0.0, 1.0) * 1000.0).round() as u64);
        }
    }

    /// The work is over: the bar, if shown, is cleared.
    pub fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }

    /// Whether a bar is showing.
    #[cfg(test)]
    fn showing(&self) -> bool {
        self.bar.is_some()
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_long_work_gets_a_bar() {
        // Under a second: too early to tell.
        assert!(!worth_showing(0.5, 0.01));
        // 1.5 s for 90%: about 1.7 s in all, nearly done.
        assert!(!worth_showing(1.5, 0.9));
        // 1.5 s for 10%: about 15 s in all.
        assert!(worth_showing(1.5, 0.1));
        // Nothing done yet after a second: long.
        assert!(worth_showing(1.0, 0.0));
        // Done.
        assert!(!worth_showing(30.0, 1.0));
    }

    #[test]
    fn nothing_is_shown_off_a_terminal() {
        let mut progress = Progress::on("walker", false);
        // Started long ago, barely begun: a terminal would show a bar.
        progress.started = Instant::now() - std::time::Duration::from_secs(10);
        progress.set(0.01);
        assert!(!progress.showing());
        let mut progress = Progress::on("walker", true);
        progress.started = Instant::now() - std::time::Duration::from_secs(10);
        progress.set(0.01);
        assert!(progress.showing());
        progress
            .bar
            .as_ref()
            .unwrap()
            .set_draw_target(indicatif::ProgressDrawTarget::hidden());
        progress.finish();
        assert!(!progress.showing());
    }
}
