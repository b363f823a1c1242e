//! What opening a page involves beyond its data: a run's individuals developed on request
//! ([`run_developer`]), and the warnings for the flags that do nothing for the page
//! ([`ignored_flags`]).

use std::path::PathBuf;

use super::{Developer, Kind, Target};
use crate::encoding::Genome;
use crate::evolve::run::Run;

/// The flags of `ontogeny view` that may do nothing for a page.
#[derive(Clone, Debug, Default)]
pub struct PageFlags {
    /// The growth flags given (`--steps`, `--seed`, ...), by name.
    pub growth: Vec<&'static str>,
    /// Whether `--size` was given.
    pub size: bool,
    /// Whether `--snapshot` was given.
    pub snapshot: bool,
    /// `--frame`.
    pub frame: Option<i64>,
}

/// What `flags` do not do for the page of `target` (of `frames` frames, when known), one
/// warning each: growth flags with a directory (its creatures are already grown), `--size`
/// without `--snapshot`, `--frame` on a run page or past the page's frames.
pub fn ignored_flags(flags: &PageFlags, target: &Target, frames: Option<usize>) -> Vec<String> {
    let mut warnings = Vec::new();
    if target.kind != Kind::Lsys && !flags.growth.is_empty() {
        warnings.push(format!(
            "{} grow a creature from a grammar; {} is not an .lsys file: ignored",
            flags.growth.join(", "),
            target.path.display()
        ));
    }
    if flags.size && !flags.snapshot {
        warnings.push("--size sets the size of a --snapshot picture: ignored".to_string());
    }
    if let Some(k) = flags.frame {
        if target.kind == Kind::Run {
            warnings.push(format!(
                "--frame {k}: a run page has no frames (open an individual with ?gen=G&index=I \
                 in its address): ignored"
            ));
        } else if let Some(n) = frames {
            let n = n as i64;
            if n == 0 {
                warnings.push(format!("--frame {k}: the recording has no frames: ignored"));
            } else if k >= n || k < -n {
                warnings.push(format!(
                    "--frame {k}: there are {n} frames (0 to {}, or -{n} to -1): showing the {}",
                    n - 1,
                    if k >= n { "last" } else { "first" }
                ));
            }
        }
    }
    warnings
}

/// A function that develops individual `(generation, index)` of the run in `dir`, whose
/// genomes are `G`s.
pub fn run_developer<G: Genome + 'static>(dir: PathBuf) -> Developer {
    Box::new(move |generation, index| {
        // Read-only: the viewer never changes a run's files.
        let run = Run::<G>::open_read_only(&dir).map_err(|e| e.to_string())?;
        let population = run.population(generation).map_err(|e| e.to_string())?;
        let individual = population.get(index as usize).ok_or_else(|| {
            format!(
                "generation {generation} has {} individual(s); there is no individual {index}",
                population.len()
            )
        })?;
        individual
            .genome
            .develop(&run.config().limits, individual.develop_seed)
            .map_err(|e| format!("the genome does not develop: {e}"))
    })
}
