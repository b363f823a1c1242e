//! A run's profile (`ontogeny evolve --profile FILE`): where each generation's time went, one
//! JSON object per line (JSON Lines), written as each generation is stored. A generation's
//! line holds the wall time of its steps (breeding, developing, keying, evaluating, the wait
//! for the fine re-walk of its best, writing the store and the derived files, and the rest),
//! the threads and
//! ranks that ran it, and each walk the evaluator simulated, in the order it was handed them,
//! with its wall time, the thread and rank that ran it, and its creature's parts.
//!
//! The profile is kept apart from the run store: timings differ from one run to the next, and
//! the store of a run is the same on any number of threads, timed or not.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::evolve::timing::{GenerationTimes, WalkTime};
use crate::output::{self, OutputError};

/// One generation's line of a profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GenerationProfile {
    /// The generation's index.
    pub generation: u32,
    /// Worker threads of each rank (rayon's pool).
    pub threads: u32,
    /// Processes that evaluated (MPI ranks; 1 without MPI).
    pub ranks: u32,
    /// Individuals evaluated, as the run counts them (simulated or reused from the cache; the
    /// elite carried over is not): the numerator of the run's evaluations per second.
    pub evaluations: u64,
    /// Wall-clock seconds making the new genomes.
    pub breeding: f64,
    /// ... developing them into creatures.
    pub developing: f64,
    /// ... keying the creatures for the evaluation cache.
    pub keying: f64,
    /// ... in the evaluator's batch of walks (the part that runs in parallel over threads).
    pub evaluating: f64,
    /// ... waiting for the re-walk of the generation's best at the fine reference setting:
    /// it walks beside the run's next work (a generational run's next generation, a
    /// steady-state run's next block of births), so this is the part not hidden behind that
    /// work (0 when it is not re-walked, or its fine evaluation was known); where
    /// `fine_walk` is `None`, the re-walk itself.
    pub fine: f64,
    /// The fine re-walk's own seconds when it walked beside the run's next work (0 when its
    /// figure was known without one). `None` where `fine` is the walk itself: a run whose
    /// system refused the re-walk a thread of its own, and profiles written before the walk
    /// went beside.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fine_walk: Option<f64>,
    /// ... storing the generation and advancing the derived files.
    pub writing: f64,
    /// ... in everything else (the cache, combining a walk's units, the statistics).
    pub other: f64,
    /// The whole generation, from its start until it was written.
    pub total: f64,
    /// The walks the evaluator simulated, in the order it was handed them (none when the
    /// batch went to MPI ranks, which do not report their walks' times).
    pub walks: Vec<WalkTime>,
}

impl GenerationProfile {
    /// The line of generation `generation`, from the genetic algorithm's `times` and the run's
    /// own of the fine re-walk, writing, and the whole; `other` is what the steps leave.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        generation: u32,
        threads: u32,
        ranks: u32,
        evaluations: u64,
        times: GenerationTimes,
        fine: f64,
        writing: f64,
        total: f64,
    ) -> GenerationProfile {
        let steps = times.breeding + times.developing + times.keying + times.evaluating;
        GenerationProfile {
            generation,
            threads,
            ranks,
            evaluations,
            breeding: times.breeding,
            developing: times.developing,
            keying: times.keying,
            evaluating: times.evaluating,
            fine,
            fine_walk: None,
            writing,
            other: (total - steps - fine - writing).max(0.0),
            total,
            walks: times.walks,
        }
    }

    /// The line as if its fine re-walk had been walked alone before the generation was
    /// stored: `fine` the walk's own seconds and `total` with them in place of the wait (a
    /// line whose `fine` is the walk already is returned as it is). The schedule simulator
    /// replays every profile so, and models the walk beside the next generation as a lever.
    pub fn walked_alone(&self) -> GenerationProfile {
        match self.fine_walk {
            Some(walk) => GenerationProfile {
                total: self.total - self.fine + walk,
                fine: walk,
                fine_walk: None,
                ..self.clone()
            },
            None => self.clone(),
        }
    }

    /// The seconds outside the evaluator's batch: what runs before or after it, whatever the
    /// number of threads walking.
    pub fn outside_evaluation(&self) -> f64 {
        (self.total - self.evaluating).max(0.0)
    }
}

/// Why a profile could not be read.
#[derive(Debug, thiserror::Error)]
pub enum ProfileError {
    /// The file could not be read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The profile.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A line is not a generation's record.
    #[error("{}:{line}: not a generation of a profile (written by `ontogeny evolve --profile`): {problem}", path.display())]
    Line {
        /// The profile.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
        /// What is wrong with it.
        problem: String,
    },
    /// The file holds no generation.
    #[error("{}: no generation in the profile", path.display())]
    Empty {
        /// The profile.
        path: PathBuf,
    },
}

/// The generations of the profile at `path`, in the order written; blank lines are skipped.
/// A line that is not a generation's record, a negative or non-finite time, or a walk's thread
/// or rank beyond the generation's count is refused with its line number.
pub fn read_profile(path: &Path) -> Result<Vec<GenerationProfile>, ProfileError> {
    let text = crate::input::read_to_string(path).map_err(|source| ProfileError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let mut generations = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let bad = |problem: String| ProfileError::Line {
            path: path.to_path_buf(),
            line: n + 1,
            problem,
        };
        let g: GenerationProfile = serde_json::from_str(line).map_err(|e| bad(e.to_string()))?;
        check(&g).map_err(bad)?;
        generations.push(g);
    }
    if generations.is_empty() {
        return Err(ProfileError::Empty {
            path: path.to_path_buf(),
        });
    }
    Ok(generations)
}

/// Why `g` cannot be a generation's record, if it cannot.
fn check(g: &GenerationProfile) -> Result<(), String> {
    let times = [
        ("breeding", g.breeding),
        ("developing", g.developing),
        ("keying", g.keying),
        ("evaluating", g.evaluating),
        ("fine", g.fine),
        ("writing", g.writing),
        ("other", g.other),
        ("total", g.total),
    ];
    for (name, t) in times {
        if !(t.is_finite() && t >= 0.0) {
            return Err(format!("{name} is {t}, not a number of seconds"));
        }
    }
    if g.threads == 0 || g.ranks == 0 {
        return Err("threads and ranks must be at least 1".to_string());
    }
    for (i, w) in g.walks.iter().enumerate() {
        if !(w.seconds.is_finite() && w.seconds >= 0.0) {
            return Err(format!("walk {i} took {} s", w.seconds));
        }
        if w.thread >= g.threads || w.rank >= g.ranks {
            return Err(format!(
                "walk {i} ran on thread {} of rank {}, beyond {} threads and {} ranks",
                w.thread, w.rank, g.threads, g.ranks
            ));
        }
    }
    Ok(())
}

/// A profile being written: the file, and how many bytes of it are written.
#[derive(Debug)]
pub struct ProfileWriter {
    path: PathBuf,
    length: u64,
}

impl ProfileWriter {
    /// Starts the profile at `path`, empty (a file there is replaced; a target that is not a
    /// regular file is refused).
    pub fn create(path: &Path) -> Result<ProfileWriter, OutputError> {
        output::write(path, "")?;
        Ok(ProfileWriter {
            path: path.to_path_buf(),
            length: 0,
        })
    }

    /// Adds generation `g`'s line.
    pub fn add(&mut self, g: &GenerationProfile) -> Result<(), OutputError> {
        let mut line = serde_json::to_string(g).expect("a profile's line serialises");
        line.push('\n');
        output::replace_tail(&self.path, self.length, &line)?;
        self.length += line.len() as u64;
        Ok(())
    }
}
