//! Sustained motion (`ontogeny runs sustained DIR`): Chaumont, Egli & Adami's check of whether
//! a walker goes on walking after the time it was evolved for (section 3.5: at 20 s "almost
//! every resultant creature exhibited periodic motion and was able to perform for a much
//! longer period than the simulation time itself", yet "typically, 40% to 50% of the
//! creatures stop moving ... because they become unstable after several cycles").
//!
//! Each run's champion (rank 1, as `replay` ranks; the runs found as `runs plasticity` finds
//! them) walks again with its run's settings but for `seconds` (60) of measured walking, and
//! the root part's horizontal movement over the last `window` seconds (10) of the walk is
//! measured. It has **stopped** when that movement is below `still` metres (0.1). The check
//! needs a plain walker run (one world, one trial, developed before it walks); other runs are
//! left out with a note. Nothing is written.

use serde::Serialize;

use super::plasticity::{FoundRun, PlasticityError};
use crate::encoding::Genome;
use crate::run::pick::individual_by_rank;
use crate::run::{Run, encoding_of_run, unknown_encoding_of_run};
use crate::task::{Evaluation, Phase, Sample, Status, TaskKind};

/// What the check asks of each champion.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SustainedSettings {
    /// Seconds of measured walking (Chaumont's runs: 20 s; the check: 60 s).
    pub seconds: f64,
    /// The last seconds of the walk whose movement decides whether it stopped.
    pub window: f64,
    /// Less root movement (m) over the window than this is stopped.
    pub still: f64,
}

impl Default for SustainedSettings {
    fn default() -> Self {
        SustainedSettings {
            seconds: 60.0,
            window: 10.0,
            still: 0.1,
        }
    }
}

impl SustainedSettings {
    /// Checks the values: `seconds` in (0, 3600], `window` in (0, seconds], `still` > 0.
    pub fn check(&self) -> Result<(), String> {
        if !(self.seconds > 0.0 && self.seconds <= 3600.0) {
            return Err(format!(
                "--seconds must be in (0, 3600], not {}",
                self.seconds
            ));
        }
        if !(self.window > 0.0 && self.window <= self.seconds) {
            return Err(format!(
                "--window must be in (0, --seconds = {}], not {}",
                self.seconds, self.window
            ));
        }
        if !(self.still > 0.0 && self.still.is_finite()) {
            return Err(format!(
                "--still must be a positive distance, not {}",
                self.still
            ));
        }
        Ok(())
    }
}

/// One champion's long walk.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SustainedWalk {
    /// The run's condition (the folder that holds it).
    pub condition: String,
    /// The run's name in the tables.
    pub run: String,
    /// The generation the champion is from.
    pub generation: u32,
    /// Its stored fitness (its run's walk).
    pub stored: f64,
    /// Its fitness over the long walk.
    pub fitness: f64,
    /// D_w over the long walk (m): the root's horizontal distance from start to end.
    pub distance: f64,
    /// The root's horizontal distance over the last `window` seconds (m).
    pub last_window: f64,
    /// Whether it stopped: `last_window` < `still`, or the long walk failed.
    pub stopped: bool,
    /// The long walk's status (`ok`, `unstable`, `exploded`, ...).
    pub status: String,
}

/// The root part's horizontal distance between the last sample of the measured walk and the
/// last sample at least `window` seconds before it; `None` when the recording holds no such
/// pair.
pub fn root_movement_in_last(samples: &[Sample], window: f64) -> Option<f64> {
    let walking: Vec<&Sample> = samples
        .iter()
        .filter(|s| s.phase.is_none_or(|p| p == Phase::Measuring))
        .collect();
    let last = walking.last()?;
    let before = walking
        .iter()
        .rev()
        .find(|s| s.t <= last.t - window + 1e-9)?;
    let (a, b) = (before.parts.first()?.0, last.parts.first()?.0);
    Some((b.x - a.x).hypot(b.z - a.z))
}

/// Walks the champion of `found`, a run of genome `G`, as `settings` say; `Ok(None)` with a
/// note when the run has no complete generation or is not a plain walker run.
pub fn walk_champion<G: Genome>(
    found: &FoundRun,
    settings: &SustainedSettings,
) -> Result<Result<SustainedWalk, String>, PlasticityError> {
    let dir = &found.dir;
    let run = Run::<G>::open_read_only(dir)?;
    if run.last_generation()?.is_none() {
        return Ok(Err(format!(
            "{}: no complete generation yet; left out",
            dir.display()
        )));
    }
    let mut task = run.config().task.clone();
    if task.kind() != TaskKind::Walker || !task.is_plain() || task.develop.during() {
        return Ok(Err(format!(
            "{}: not a plain walker run (one world, one trial, developed before the walk); left out",
            dir.display()
        )));
    }
    let (generation, best) = individual_by_rank(&run, dir, None, 1)?;
    *task.seconds_mut() = settings.seconds;
    let walked = match best
        .genome
        .develop_held(run.limits(), best.develop_seed, None)
    {
        Ok(creature) => task.evaluate(&creature, true),
        Err(e) => Evaluation::invalid(task.kind().name(), e.0),
    };
    let last_window = root_movement_in_last(&walked.recording, settings.window);
    let ok = walked.status == Status::Ok;
    Ok(Ok(SustainedWalk {
        condition: found.condition.clone(),
        run: found.name.clone(),
        generation,
        stored: best.evaluation.fitness,
        fitness: walked.fitness,
        distance: walked.terms.get("D_w").copied().unwrap_or(f64::NAN),
        last_window: last_window.unwrap_or(f64::NAN),
        stopped: !ok || last_window.is_none_or(|m| m < settings.still),
        status: walked.status.name().to_string(),
    }))
}

/// Walks the champion of every run of `runs`, in order, with a note for each run left out;
/// `progress(done, total)` is called after each. `Err` when no run could be walked.
pub fn walk_champions(
    runs: &[FoundRun],
    settings: &SustainedSettings,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Vec<SustainedWalk>, Vec<String>), PlasticityError> {
    settings.check().map_err(PlasticityError::Input)?;
    let mut walks = Vec::with_capacity(runs.len());
    let mut notes = Vec::new();
    for (done, found) in runs.iter().enumerate() {
        let encoding = encoding_of_run(&found.dir)?;
        let walked = crate::with_genome!(
            encoding.as_str(),
            G => walk_champion::<G>(found, settings),
            |other| Err(PlasticityError::Input(unknown_encoding_of_run(&found.dir, other)))
        )?;
        match walked {
            Ok(walk) => walks.push(walk),
            Err(note) => notes.push(note),
        }
        progress(done + 1, runs.len());
    }
    if walks.is_empty() {
        return Err(PlasticityError::Input(
            "no run could be walked: ".to_string() + &notes.join("; "),
        ));
    }
    Ok((walks, notes))
}

/// The table for people: a row per champion, then how many stopped.
pub fn text(settings: &SustainedSettings, walks: &[SustainedWalk]) -> String {
    let mut out = format!(
        "each champion walked {} s; stopped: its root moved less than {} m in the last {} s\n",
        crate::number::format_number(settings.seconds),
        crate::number::format_number(settings.still),
        crate::number::format_number(settings.window)
    );
    out.push_str("condition\trun\tgeneration\tstored fitness\tlong-walk fitness\tD_w (m)\tlast window (m)\tstopped\tstatus\n");
    for w in walks {
        out.push_str(&format!(
            "{}\t{}\t{}\t{:.4}\t{:.4}\t{:.3}\t{:.3}\t{}\t{}\n",
            w.condition,
            w.run,
            w.generation,
            w.stored,
            w.fitness,
            w.distance,
            w.last_window,
            if w.stopped { "yes" } else { "no" },
            w.status
        ));
    }
    let stopped = walks.iter().filter(|w| w.stopped).count();
    out.push_str(&format!(
        "stopped: {stopped} of {} ({:.0}%)\n",
        walks.len(),
        100.0 * stopped as f64 / walks.len() as f64
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{UnitQuaternion, Vector3};

    fn sample(t: f64, x: f64, z: f64, phase: Option<Phase>) -> Sample {
        Sample {
            t,
            phase,
            parts: vec![(Vector3::new(x, 0.5, z), UnitQuaternion::identity())],
            projectile: None,
            projectile_size: None,
            objects: Vec::new(),
            growth: Vec::new(),
        }
    }

    #[test]
    fn the_last_window_is_measured_on_the_walk_alone() {
        // The root at (0, 0) until t = 50 s, then 3 m along x and 4 m along z by t = 60 s:
        // 5 m in the last 10 s. A settling sample after it is not part of the walk.
        let samples = vec![
            sample(0.5, -9.0, 0.0, Some(Phase::Settling)),
            sample(40.0, 0.0, 0.0, Some(Phase::Measuring)),
            sample(50.0, 0.0, 0.0, Some(Phase::Measuring)),
            sample(55.0, 1.0, 1.0, Some(Phase::Measuring)),
            sample(60.0, 3.0, 4.0, Some(Phase::Measuring)),
        ];
        assert_eq!(root_movement_in_last(&samples, 10.0), Some(5.0));
        // Over the last 5 s: from (1, 1) to (3, 4), √13.
        assert_eq!(root_movement_in_last(&samples, 5.0), Some(13f64.sqrt()));
        // A window longer than the walk has no start.
        assert_eq!(root_movement_in_last(&samples, 30.0), None);
        assert_eq!(root_movement_in_last(&[], 10.0), None);
    }

    #[test]
    fn settings_out_of_range_are_refused_by_name() {
        let ok = SustainedSettings::default();
        assert!(ok.check().is_ok());
        let long_window = SustainedSettings { window: 61.0, ..ok };
        assert!(long_window.check().unwrap_err().contains("--window"));
        let nan = SustainedSettings {
            still: f64::NAN,
            ..ok
        };
        assert!(nan.check().unwrap_err().contains("--still"));
    }
}
