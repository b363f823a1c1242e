//! The run loop of a generational run: each generation bred and evaluated while the fine
//! reference re-walk of the previous generation's best walks beside it
//! ([`super::beside`]), so that the run's threads do not wait for that one long walk between
//! two generations. A generation whose best needs the walk is stored once its figure is in:
//! after the next generation's walks; one whose figure is known (an elite copy of the previous
//! best, the cache's, or none asked) is stored at once. A run stopped (or killed) before a
//! generation is stored makes that generation again when resumed, the same: it loses at most
//! the work of the two generations it was between.

use std::time::Instant;

use super::beside::{Evaluated, Pending, fine_pool};
use super::progress::Progress;
use super::{GenerationReport, Run, RunError};
use crate::encoding::Genome;
use crate::evolve::timing::GenerationTimes;

impl<G: Genome> Run<G> {
    /// Runs a generational run's remaining generations, calling `observer` after each is
    /// stored (one generation after its walks, with the last one's at the end).
    pub(super) fn run_generational(
        &mut self,
        progress: &mut Progress<G>,
        observer: &mut dyn FnMut(&GenerationReport),
    ) -> Result<(), RunError> {
        let generations = self.config.ga.generations as u32;
        let fine_pool = fine_pool();
        std::thread::scope(|scope| {
            let mut pending: Option<Pending<'_, G>> = None;
            let outcome = (|| -> Result<(), RunError> {
                for generation in progress.next..generations {
                    self.cancel.check()?;
                    let started = Instant::now();
                    let mut times = GenerationTimes::default();
                    let evaluations = self.breed(progress, generation, &mut times)?;
                    let evaluated = Evaluated {
                        generation,
                        evaluations,
                        reused: None,
                        times,
                        started,
                        evaluated: started.elapsed().as_secs_f64(),
                    };
                    let pool = fine_pool.as_ref();
                    self.hand_over(scope, pool, progress, &mut pending, evaluated, observer)?;
                }
                Ok(())
            })();
            self.finish_beside(progress, pending, outcome, observer)
        })
    }
}
