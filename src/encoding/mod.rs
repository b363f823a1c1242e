//! Genomes: the encodings that evolution searches, each developing into the one
//! [`Creature`] type that every task takes.
//!
//! This room owns the [`Genome`] trait and its encodings: random genomes within limits,
//! mutation, crossover, grafting and development. It knows nothing of physics or of the
//! genetic algorithm that calls it (`crate::evolve`).

use rand_chacha::ChaCha8Rng;
use serde::{Serialize, de::DeserializeOwned};

use crate::creature::Creature;
use crate::environment::Environment;
use crate::lang::ast::{Expr, UnaryOp};

pub mod continuous;
mod creature_limits;
pub mod direct;
mod draw;
pub mod graph;
pub mod limits;
pub mod load;
pub mod lsystem;
mod mirror;
pub(crate) mod projectile;
mod registry;
mod show;
mod show_habitats;

/// The building commands genomes write (the language's one table of commands).
pub use crate::lang::commands as command;
pub use continuous::{ContinuousGenome, ContinuousLimits};
pub use creature_limits::CreatureLimits;
pub use direct::{DirectGenome, DirectLimits};
pub use graph::{GraphGenome, GraphLimits, JointSet};
pub use limits::CheckedLimits;
pub use load::{LoadError, LoadOptions, Loaded, grow_grammar, load_creature};
pub use lsystem::{LSystemGenome, LSystemLimits};
pub use registry::{ENCODINGS, EncodingInfo, encoding_named};
pub use show::{ShowError, ShownGenome, read_genome_file, show_genome_file};
pub use show_habitats::{
    HabitatArray, HabitatCreature, HabitatPhenotypes, develop_in_habitat_arrays,
};

/// The random source every operator draws from: portable and explicitly seeded, split per
/// individual by the genetic algorithm.
pub type Rng = ChaCha8Rng;

/// Why a genome did not develop into a creature (an evaluation with status `invalid`).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct DevelopError(pub String);

/// What the creatures of a run are for, as far as an encoding needs to know: a task that
/// throws a projectile held by the root part (catapult, aim) asks some encodings to keep that
/// part as an arm (Chaumont et al. section 4.1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Purpose {
    /// Moving the whole body (walker, jump).
    #[default]
    Locomotion,
    /// Throwing the task's projectile from the root part (catapult, aim).
    Throwing,
}

/// A genome of one encoding.
///
/// Every operator respects `Limits` by construction: a result never exceeds them, and no
/// operator loops until a random draw happens to fit (an encoding may make a newborn again a
/// bounded number of times, as the graph genome does when its parts interpenetrate). Development never panics: a genome that
/// does not develop gives a [`DevelopError`].
pub trait Genome:
    Clone + std::fmt::Debug + Send + Sync + Serialize + DeserializeOwned + 'static
{
    /// The encoding's limits and settings (serialisable: they are part of a run's config),
    /// each key within its documented range ([`CheckedLimits`]).
    type Limits: Clone
        + std::fmt::Debug
        + Default
        + Send
        + Sync
        + Serialize
        + DeserializeOwned
        + CheckedLimits;

    /// The encoding's name, as the CLI and the run store spell it.
    const NAME: &'static str;

    /// One line for people (the command line's help lists it beside [`Genome::NAME`]).
    const DESCRIPTION: &'static str = "";

    /// Keys of [`Genome::Limits`] added after runs had begun, with the value (a string) that
    /// a run begun before the key existed ran with: a resumed run's `config.toml` that lacks
    /// a key gets it, so that the run keeps what it ran with.
    const LIMITS_OF_OLDER_RUNS: &'static [(&'static str, &'static str)] = &[];

    /// The extension of the file that holds [`Genome::to_text`] (a run's `best.lsys`,
    /// `best.json`, ...).
    const TEXT_EXTENSION: &'static str = "lsys";

    /// Adapts `limits` to what the creatures are for (called when a run is assembled, from
    /// its task); the default changes nothing.
    fn adapt_limits(limits: &mut Self::Limits, purpose: Purpose) {
        let _ = (limits, purpose);
    }

    /// Lets the operators make, change and remove environment reads (and the neurons that
    /// read and write the chemical array) with chance `probability`, the `[ga]` key
    /// `environment_reads` (called when a run is assembled); the default, for an encoding
    /// whose genomes read no environment, changes nothing.
    fn allow_environment_reads(limits: &mut Self::Limits, probability: f64) {
        let _ = (limits, probability);
    }

    /// Lets the genomes carry their thrower's projectile as genes, its three edge lengths
    /// (m), newborns starting from `start` (called when a run whose `[task.catapult]` sets
    /// `evolve_projectile` is assembled; see the `projectile` module). Every encoding of the
    /// registry does; the default, for a genome without projectile genes, changes nothing
    /// (its creatures throw the task's projectile).
    fn evolve_projectile(limits: &mut Self::Limits, start: [f64; 3]) {
        let _ = (limits, start);
    }

    /// The edge lengths (m) of the projectile the genome carries, when it carries one (none
    /// by default).
    fn projectile(&self) -> Option<[f64; 3]> {
        None
    }

    /// A random genome within `limits`.
    fn random(limits: &Self::Limits, rng: &mut Rng) -> Self;

    /// A mutant: every mutation site changes with probability `rate`.
    fn mutate(&self, limits: &Self::Limits, rate: f64, rng: &mut Rng) -> Self;

    /// A child of `self` and `other` by crossover, or `None` when the encoding has none.
    fn crossover(&self, other: &Self, limits: &Self::Limits, rng: &mut Rng) -> Option<Self> {
        let _ = (other, limits, rng);
        None
    }

    /// A child of `self` with a piece of `other` grafted on, or `None` when the encoding has
    /// no grafting.
    fn graft(&self, other: &Self, limits: &Self::Limits, rng: &mut Rng) -> Option<Self> {
        let _ = (other, limits, rng);
        None
    }

    /// Walking with Dinosaurs' crossover (3.3.1): a child of `self` (the breeder) in which a
    /// part of `other` (the elite), copied whole with everything that grows from it, replaces
    /// a part of `self`; a copied body part is turned half a turn, "to have a greater chance
    /// of creating a mirroring part". What a part is and about which axis it turns is each
    /// encoding's (see its implementation). `None` when the encoding has no such crossover
    /// (the default) or `other` has no part to copy that fits `limits`: the genetic algorithm
    /// then mutates `self` alone and counts the fallback.
    fn mirroring_crossover(
        &self,
        other: &Self,
        limits: &Self::Limits,
        rng: &mut Rng,
    ) -> Option<Self> {
        let _ = (other, limits, rng);
        None
    }

    /// Develops the genome into a creature; `seed` drives any randomness of development
    /// (stochastic rules).
    fn develop(&self, limits: &Self::Limits, seed: u64) -> Result<Creature, DevelopError>;

    /// The initial values of the chemical array the genome develops in unless told
    /// otherwise, one per slot (empty by default: the genome has none).
    fn environment_values(&self) -> &[f64] {
        &[]
    }

    /// The chemical array the genome develops in unless told otherwise: its size and initial
    /// values ([`Genome::environment_values`]).
    fn environment(&self) -> Environment {
        Environment::new(self.environment_values().to_vec())
    }

    /// Develops the genome as [`Genome::develop`] does, but in a chemical array whose initial
    /// values are `env`'s (a habitat's): the same genome may grow another body. `env` must
    /// have the size of [`Genome::environment`], unless the genome has none: a genome that
    /// reads no environment grows [`Genome::develop`]'s creature in any array (the default,
    /// for encodings whose genomes never read one; `array_read` gives the others the array
    /// they read).
    fn develop_in(
        &self,
        limits: &Self::Limits,
        seed: u64,
        env: &Environment,
    ) -> Result<Creature, DevelopError> {
        check_environment_size(self.environment_values().len(), env)?;
        self.develop(limits, seed)
    }

    /// Develops the genome as a run develops it outside its habitats: in `env`
    /// ([`Genome::develop_in`]) or in its own array ([`Genome::develop`]), with the creature
    /// held to the limits every encoding shares ([`CheckedLimits::creature_limits`]:
    /// `max_neurons`, `max_chain`), one past them marked invalid by an error-level problem.
    /// What studies of stored genomes develop with, so that they see what the run saw.
    fn develop_held(
        &self,
        limits: &Self::Limits,
        seed: u64,
        env: Option<&Environment>,
    ) -> Result<Creature, DevelopError> {
        let mut creature = match env {
            Some(env) => self.develop_in(limits, seed, env)?,
            None => self.develop(limits, seed)?,
        };
        limits.creature_limits().apply(&mut creature);
        Ok(creature)
    }

    /// The grammar the genome develops from, with the options that derive and build it, in
    /// its own chemical array or in `env` (a habitat's, of the size [`Genome::develop_in`]
    /// asks for): what its creature grows from when it goes on developing during its
    /// evaluation (`develop = "during"`). `None` for a genome that does not develop in
    /// continuous time (the default).
    fn seedling(
        &self,
        _limits: &Self::Limits,
        _env: Option<&Environment>,
    ) -> Option<Result<crate::develop::Seedling, DevelopError>> {
        None
    }

    /// The genome as text for people (for L-system genomes, a valid `.lsys` file).
    fn to_text(&self) -> String;

    /// [`Genome::to_text`] preceded by `note` as comments, where the text form has comments
    /// (`#` lines by default); a text form without comments (JSON) is returned as it is.
    fn annotated_text(&self, note: &str) -> String {
        let mut out = String::new();
        for line in note.lines() {
            out.push_str("# ");
            out.push_str(line);
            out.push('\n');
        }
        out.push_str(&self.to_text());
        out
    }

    /// A genome read back from its text form ([`Genome::to_text`], a run's `best.lsys` or
    /// `best.json`), checked against `limits`; by default [`Genome::from_lsys`].
    fn read_text(text: &str, limits: &Self::Limits) -> Result<Self, DevelopError> {
        Self::from_lsys(text, limits)
    }

    /// The genome for people (`ontogeny genome show`): by default its text form, then the
    /// summary `ontogeny check` gives of that grammar but its first two lines (file and
    /// axiom): derivation length or time, symbols, rules, and findings placed in the grammar
    /// shown (`grammar:LINE:COLUMN`).
    fn show(&self) -> String {
        grammar_shown(&self.to_text())
    }

    /// A genome read from a hand-written `.lsys` file, to seed a first generation with its
    /// mutants; `Err` when the encoding cannot start from a grammar or the file does not fit
    /// the limits.
    fn from_lsys(text: &str, limits: &Self::Limits) -> Result<Self, DevelopError> {
        let _ = (text, limits);
        Err(DevelopError(format!(
            "the {} encoding cannot start from a grammar",
            Self::NAME
        )))
    }

    /// [`Genome::from_lsys`] for a run's seed: the genome, the run's `limits` widened where
    /// the seed is bigger (its mutants keep within them), and notes on what was rewritten or
    /// widened. By default the limits are kept and nothing is noted. `name` is the file's,
    /// for the locations in messages.
    fn seed_from_lsys(
        name: &str,
        text: &str,
        limits: &Self::Limits,
    ) -> Result<Seed<Self>, DevelopError> {
        let _ = name;
        Self::from_lsys(text, limits).map(|genome| Seed {
            genome,
            limits: limits.clone(),
            notes: Vec::new(),
        })
    }
}

/// A grammar genome's text for people ([`Genome::show`]'s default): the text, then the
/// summary `ontogeny check` gives of that grammar but its first two lines.
pub(crate) fn grammar_shown(text: &str) -> String {
    let summary = match crate::lsystem::LSystem::from_text("grammar", text) {
        Ok(lsys) => lsys
            .check()
            .text()
            .lines()
            .skip(2)
            .collect::<Vec<_>>()
            .join("\n"),
        Err(d) => format!("the text does not compile: {d}"),
    };
    format!("{}\n{summary}", text.trim_end())
}

/// [`grammar_shown`] for a genome that may read its environment: then its reads, a line
/// each, under `environment reads:` (nothing more when it reads nothing).
pub(crate) fn grammar_shown_with_reads(text: &str, reads: &[String]) -> String {
    let mut shown = grammar_shown(text);
    if !reads.is_empty() {
        shown.push_str("\nenvironment reads:");
        for line in reads {
            shown.push_str("\n  ");
            shown.push_str(line);
        }
    }
    shown
}

/// The lines of [`grammar_shown_with_reads`]'s reads that list the environment neurons a
/// genome writes (`chem`, `secrete`), given each one written with its slot: a line per
/// neuron and slot, `chem(0): 2 written`, in the order of those names.
pub(crate) fn neurons_written(
    written: impl IntoIterator<Item = (command::Command, f64)>,
) -> Vec<String> {
    let mut neurons = std::collections::BTreeMap::new();
    for (c, slot) in written {
        *neurons
            .entry(format!("{}({slot})", c.name()))
            .or_insert(0usize) += 1;
    }
    neurons
        .into_iter()
        .map(|(neuron, n)| format!("{neuron}: {n} written"))
        .collect()
}

/// Most slots a genome's environment may have.
const MAX_ENVIRONMENT: usize = 16;

/// `Err` saying what is wrong unless a genome's environment, its array's initial `values`, has
/// at most [`MAX_ENVIRONMENT`] slots and finite values (part of a genome's check of itself).
pub(crate) fn check_environment_values(values: &[f64]) -> Result<(), String> {
    if values.len() > MAX_ENVIRONMENT {
        return Err(format!(
            "its environment has {} slots, more than {MAX_ENVIRONMENT}",
            values.len()
        ));
    }
    match values.iter().find(|v| !v.is_finite()) {
        Some(v) => Err(format!("its environment holds {v}, not a finite number")),
        None => Ok(()),
    }
}

/// The array a genome whose own array holds `values` reads when it develops in a habitat's
/// `env` ([`Genome::develop_in`]): `env`, or none when the genome has no array (it grows the
/// same creature in any); `Err` unless `env` has the genome's size.
pub(crate) fn array_read<'e>(
    values: &[f64],
    env: &'e Environment,
) -> Result<Option<&'e Environment>, DevelopError> {
    check_environment_size(values.len(), env)?;
    Ok((!values.is_empty()).then_some(env))
}

/// `Err` unless `env` has `size` slots (the size of the array a genome develops in), or the
/// genome has no array (`size` 0), which any array leaves as it is.
pub(crate) fn check_environment_size(size: usize, env: &Environment) -> Result<(), DevelopError> {
    if env.len() == size || size == 0 {
        Ok(())
    } else {
        Err(DevelopError(format!(
            "the genome develops in an environment of {size} slot(s), not {}",
            env.len()
        )))
    }
}

/// A genome read from a hand-written grammar to seed a run ([`Genome::seed_from_lsys`]).
#[derive(Clone, Debug)]
pub struct Seed<G: Genome> {
    /// The genome.
    pub genome: G,
    /// The run's limits, widened to fit the genome.
    pub limits: G::Limits,
    /// What was rewritten or widened, for people.
    pub notes: Vec<String>,
}

/// Every (item, slot) index pair of `items`, where item `i` has `slots(&items[i])` slots, in
/// order: the places an operator can pick among (a node's connections, a production's pairs).
pub(crate) fn index_pairs<T>(items: &[T], slots: impl Fn(&T) -> usize) -> Vec<(usize, usize)> {
    items
        .iter()
        .enumerate()
        .flat_map(|(i, item)| (0..slots(item)).map(move |j| (i, j)))
        .collect()
}

/// A constant number written as such in a hand-written file (`0.5`, `-1`); with
/// `nested_minus`, minus signs may nest (`-(-1)` is 1), else only one is read.
pub(crate) fn number(e: &Expr, nested_minus: bool) -> Option<f64> {
    match e {
        Expr::Number(v, _) => Some(*v),
        Expr::Unary {
            op: UnaryOp::Neg,
            operand,
            ..
        } => match operand.as_ref() {
            Expr::Number(v, _) => Some(-v),
            nested if nested_minus => number(nested, true).map(|v| -v),
            _ => None,
        },
        _ => None,
    }
}
