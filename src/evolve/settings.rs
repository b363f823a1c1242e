//! The genetic algorithm's settings: the operators' schedules of the published algorithms
//! ([`Preset`]) and the sizes and rates of a run (the `[ga]` table, [`GaSettings`]), with
//! their checks.

use serde::{Deserialize, Serialize};

use crate::sim::SettingError;

/// The operators' schedule of a published genetic algorithm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Preset {
    /// Chaumont, Egli & Adami 2007, 5.7: the best 20% survive unchanged; every new creature
    /// comes 40% from mutation alone, 30% from crossover and 30% from grafting of survivors.
    Chaumont,
    /// Walking with Dinosaurs 3.3: elites 20% survive, breeders the next 30%, the worst 50%
    /// are waste; each new creature is a breeder crossed with an elite, then mutated at a rate
    /// that rises as the fitness deviation falls.
    Wwd,
}

impl Preset {
    /// Every preset.
    pub const ALL: [Preset; 2] = [Preset::Chaumont, Preset::Wwd];

    /// Its name, as the command line and `config.toml` spell it.
    pub fn name(self) -> &'static str {
        match self {
            Preset::Chaumont => "chaumont",
            Preset::Wwd => "wwd",
        }
    }

    /// One line for people: where the schedule comes from.
    pub fn summary(self) -> &'static str {
        match self {
            Preset::Chaumont => "Chaumont et al. 5.7",
            Preset::Wwd => "Walking with Dinosaurs 3.3",
        }
    }

    /// The preset named `name`.
    pub fn named(name: &str) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| p.name() == name)
    }
}

/// How the `wwd` preset crosses a breeder with an elite (the `[ga]` key `wwd_crossover`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WwdCrossover {
    /// The encoding's ordinary crossover ([`crate::encoding::Genome::crossover`]): what runs
    /// begun before the key existed used, and what a `config.toml` without the key reads.
    #[default]
    Plain,
    /// Walking with Dinosaurs 3.3.1's crossover: a whole part of the elite, copied and turned
    /// half a turn, replaces a part of the breeder
    /// ([`crate::encoding::Genome::mirroring_crossover`]). New `wwd` runs use it.
    Mirroring,
}

impl WwdCrossover {
    /// Whether it is [`WwdCrossover::Plain`] (then the key is not written, and stored settings
    /// stay as they were).
    pub fn is_plain(&self) -> bool {
        *self == WwdCrossover::Plain
    }
}

/// How a run's generations follow one another (the `[ga]` key `algorithm`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Algorithm {
    /// A whole generation is bred, evaluated, and replaces the last but its elite: the
    /// published protocols (Chaumont et al., Walking with Dinosaurs). What a configuration
    /// without the key reads; it is not written.
    #[default]
    Generational,
    /// Births one at a time, each bred from the last stored generation that ended at least
    /// `in_flight` births before it, integrated in birth order, replacing the population's
    /// worst if better ([`crate::evolve::steady`]): no barrier between generations.
    SteadyState,
}

impl Algorithm {
    /// Every algorithm.
    pub const ALL: [Algorithm; 2] = [Algorithm::Generational, Algorithm::SteadyState];

    /// Its name, as the command line and `config.toml` spell it.
    pub fn name(self) -> &'static str {
        match self {
            Algorithm::Generational => "generational",
            Algorithm::SteadyState => "steady-state",
        }
    }

    /// One line for people.
    pub fn summary(self) -> &'static str {
        match self {
            Algorithm::Generational => "whole generations, the published protocols (the default)",
            Algorithm::SteadyState => {
                "one birth at a time, the worst replaced: no barrier between generations"
            }
        }
    }

    /// The algorithm named `name`.
    pub fn named(name: &str) -> Option<Algorithm> {
        Algorithm::ALL.into_iter().find(|a| a.name() == name)
    }

    /// Whether it is [`Algorithm::Generational`] (then the key is not written, and stored
    /// settings stay as they were).
    pub fn is_generational(&self) -> bool {
        *self == Algorithm::Generational
    }
}

/// The evaluations a steady-state run keeps in flight at the least when `in_flight` is not
/// given: twice 16 threads.
pub const DEFAULT_IN_FLIGHT: usize = 32;

/// The most births a steady-state run may keep in flight (`in_flight`, `evolve --in-flight`),
/// and the most `runs schedule --steady-state` replays.
pub const MAX_IN_FLIGHT: usize = 100_000;

/// The genetic algorithm's settings (the `[ga]` table of a run's `config.toml`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GaSettings {
    /// The schedule.
    pub preset: Preset,
    /// Individuals per generation.
    pub population: usize,
    /// Generations, the first (random) one included.
    pub generations: usize,
    /// The fraction kept unchanged, and not evaluated again, from one generation to the next.
    pub elite: f64,
    /// Walking with Dinosaurs: the fraction after the elite that breeds (the rest is waste).
    pub breeders: f64,
    /// Chaumont: the fraction of new individuals made by mutation alone.
    pub asexual: f64,
    /// Chaumont: the fraction of new individuals made by crossover (grafting makes the rest).
    pub crossover: f64,
    /// Per-site mutation probability of an asexual child (Chaumont: 10%), and the base rate
    /// of Walking with Dinosaurs' adaptive mutation.
    pub mutation_rate: f64,
    /// Chaumont: the chance that a child of crossover or grafting is mutated (10%) ...
    pub mutation_chance_after_mating: f64,
    /// ... and its per-site mutation probability then (5%).
    pub mutation_rate_after_mating: f64,
    /// The chance that an operator makes, changes or removes an environment read of a
    /// genome that can read its environment (`lsystem`, `lsystem-continuous`). 0, the
    /// default, leaves genomes without reads and draws exactly as before the key existed; a
    /// configuration without the key reads as 0, and 0 is not written.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub environment_reads: f64,
    /// How many times a newborn whose parts interpenetrate is made again (Chaumont et al.
    /// 5.5: "If such collisions occur, the creature is eliminated and the system generates a
    /// new one until it finds a valid candidate"), its operator drawing again from the same
    /// random stream; the last try is kept (and evaluated as `self-intersecting`). 1 makes
    /// each newborn once. Chaumont's preset: 10; Walking with Dinosaurs': 1 (its illegal
    /// creatures score the failure floor, 3.5.1). A configuration stored without the key, by
    /// a release before it existed, reads as 1, and 1 is not written.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub regenerate: usize,
    /// Walking with Dinosaurs: how a breeder and an elite are crossed. The `wwd` preset's is
    /// `mirroring` (3.3.1); a configuration without the key reads as `plain`, the crossover
    /// runs begun before the key existed used, so that they resume as they ran; `plain` is
    /// not written. Chaumont's preset does not read it.
    #[serde(default, skip_serializing_if = "WwdCrossover::is_plain")]
    pub wwd_crossover: WwdCrossover,
    /// How generations follow one another. A configuration without the key reads as
    /// `generational`, which is not written.
    #[serde(default, skip_serializing_if = "Algorithm::is_generational")]
    pub algorithm: Algorithm,
    /// Steady-state: the evaluations in flight at the least, W: birth b is bred from the last
    /// generation that ended at or before birth b + 1 − W. Part of the algorithm (a result
    /// depends on it, never on the threads or ranks). `None` (not written) for a generational
    /// run; a steady-state run stores it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub in_flight: Option<usize>,
}

/// The value of [`GaSettings::regenerate`] a stored configuration without the key ran with.
fn one() -> usize {
    1
}

/// Whether [`GaSettings::regenerate`] is 1 (so that it is not written).
fn is_one(v: &usize) -> bool {
    *v == 1
}

/// Whether a setting is 0 (so that it is not written, and stored settings stay as they were).
fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl GaSettings {
    /// The preset's published settings.
    pub fn preset(preset: Preset) -> GaSettings {
        match preset {
            Preset::Chaumont => GaSettings {
                preset,
                population: 300,
                generations: 100,
                elite: 0.2,
                breeders: 0.0,
                asexual: 0.4,
                crossover: 0.3,
                mutation_rate: 0.1,
                mutation_chance_after_mating: 0.1,
                mutation_rate_after_mating: 0.05,
                environment_reads: 0.0,
                regenerate: 10,
                wwd_crossover: WwdCrossover::Plain,
                algorithm: Algorithm::Generational,
                in_flight: None,
            },
            Preset::Wwd => GaSettings {
                preset,
                population: 300,
                generations: 100,
                elite: 0.2,
                breeders: 0.3,
                asexual: 0.0,
                crossover: 1.0,
                mutation_rate: 0.05,
                mutation_chance_after_mating: 1.0,
                mutation_rate_after_mating: 0.05,
                environment_reads: 0.0,
                regenerate: 1,
                wwd_crossover: WwdCrossover::Mirroring,
                algorithm: Algorithm::Generational,
                in_flight: None,
            },
        }
    }

    /// Checks every value; the error names the setting (its key in the `[ga]` table, or the
    /// two keys whose sum is out of range).
    pub fn check(&self) -> Result<(), SettingError> {
        let fraction = |key: &'static str, v: f64| {
            if (0.0..=1.0).contains(&v) {
                Ok(())
            } else {
                Err(SettingError::out_of_range(key, "between 0 and 1", v))
            }
        };
        if !(2..=100_000).contains(&self.population) {
            return Err(SettingError::out_of_range(
                "population",
                "2 to 100000",
                self.population,
            ));
        }
        if !(1..=100_000).contains(&self.generations) {
            return Err(SettingError::out_of_range(
                "generations",
                "1 to 100000",
                self.generations,
            ));
        }
        fraction("elite", self.elite)?;
        fraction("breeders", self.breeders)?;
        fraction("asexual", self.asexual)?;
        fraction("crossover", self.crossover)?;
        fraction("mutation_rate", self.mutation_rate)?;
        fraction(
            "mutation_chance_after_mating",
            self.mutation_chance_after_mating,
        )?;
        fraction(
            "mutation_rate_after_mating",
            self.mutation_rate_after_mating,
        )?;
        fraction("environment_reads", self.environment_reads)?;
        if !(1..=100).contains(&self.regenerate) {
            return Err(SettingError::out_of_range(
                "regenerate",
                "1 to 100",
                self.regenerate,
            ));
        }
        if self.asexual + self.crossover > 1.0 + 1e-12 {
            return Err(SettingError::out_of_range(
                "asexual + crossover",
                "at most 1",
                self.asexual + self.crossover,
            ));
        }
        if self.elite + self.breeders > 1.0 + 1e-12 {
            return Err(SettingError::out_of_range(
                "elite + breeders",
                "at most 1",
                self.elite + self.breeders,
            ));
        }
        if self.survivors() == 0 {
            return Err(SettingError {
                table: String::new(),
                key: "elite",
                problem: format!(
                    "{} of a population of {} keeps nobody to breed from",
                    self.elite, self.population
                ),
            });
        }
        self.check_algorithm()
    }

    /// The steady-state algorithm's checks: `in_flight` only with it, 1 to [`MAX_IN_FLIGHT`], and a
    /// child to breed in each block.
    fn check_algorithm(&self) -> Result<(), SettingError> {
        match (self.algorithm, self.in_flight) {
            (Algorithm::Generational, Some(_)) => Err(SettingError {
                table: String::new(),
                key: "in_flight",
                problem: "is read by algorithm = \"steady-state\" only".into(),
            }),
            (Algorithm::SteadyState, Some(w)) if !(1..=MAX_IN_FLIGHT).contains(&w) => Err(
                SettingError::out_of_range("in_flight", &format!("1 to {MAX_IN_FLIGHT}"), w),
            ),
            (Algorithm::SteadyState, _) if self.survivors() >= self.population => {
                Err(SettingError {
                    table: String::new(),
                    key: "elite",
                    problem: format!(
                        "{} of a population of {} keeps everyone: steady-state breeds the rest",
                        self.elite, self.population
                    ),
                })
            }
            _ => Ok(()),
        }
    }

    /// The children of a generation: the population less the elite (a steady-state run's
    /// block of births).
    pub fn children(&self) -> usize {
        self.population - self.survivors().min(self.population)
    }

    /// Steady-state: the evaluations in flight at the least ([`DEFAULT_IN_FLIGHT`] when not
    /// given).
    pub fn in_flight(&self) -> usize {
        self.in_flight.unwrap_or(DEFAULT_IN_FLIGHT)
    }

    /// How many individuals survive unchanged (at least one).
    pub fn survivors(&self) -> usize {
        ((self.elite * self.population as f64).round() as usize).clamp(1, self.population)
    }

    /// Walking with Dinosaurs: how many breeders follow the elite (at least one).
    pub fn breeder_count(&self) -> usize {
        ((self.breeders * self.population as f64).round() as usize).clamp(
            1,
            self.population - self.survivors().min(self.population - 1),
        )
    }
}
