//! The run store's rows as Rust records: the run, an individual, a stored evaluation key
//! (a generation's record is the genetic algorithm's, [`crate::evolve::record`]); and the
//! conversions between a row and a record.

use rusqlite::Row;

/// What a run is: written once, when the run starts.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRecord {
    /// The text of the run's `config.toml` (every setting).
    pub config: String,
    /// The run's master seed.
    pub seed: u64,
    /// The encoding's name, e.g. `lsystem`.
    pub encoding: String,
    /// The task's name, e.g. `walker`.
    pub task: String,
    /// The version of ontogeny that started the run (`CARGO_PKG_VERSION`).
    pub version: String,
}

impl RunRecord {
    /// The task its settings give (`[task]` of [`RunRecord::config`]); `None` when the text
    /// cannot be read as one.
    pub fn task_spec(&self) -> Option<crate::task::TaskSpec> {
        let config = crate::run::config::parse_table(&self.config).ok()?;
        config.get("task")?.clone().try_into().ok()
    }

    /// The generations its settings plan (`[ga] generations` of [`RunRecord::config`]);
    /// `None` when the text cannot be read as one.
    pub fn planned_generations(&self) -> Option<u64> {
        let config = crate::run::config::parse_table(&self.config).ok()?;
        u64::try_from(config.get("ga")?.get("generations")?.as_integer()?).ok()
    }
}

/// One individual of one generation.
#[derive(Debug, Clone, PartialEq)]
pub struct IndividualRecord {
    /// The index of its generation.
    pub generation: u32,
    /// Its index within the generation, from 0.
    pub index: u32,
    /// Its parents' indices (empty for a random individual) in generation
    /// [`IndividualRecord::parents_generation`]: for an elite (operator `elite`, a member
    /// carried over, or in a steady-state run kept through a block) its own index in the
    /// generation before.
    pub parents: Vec<u32>,
    /// The generation its `parents` index: the previous generation in a generational run
    /// and for an elite; for a steady-state run's newborn the generation its birth was bred
    /// from ([`crate::evolve::steady::Blocks::source`]). `None` for an individual of
    /// generation 0 (it has no parents), and for one stored before schema version 5, whose
    /// parents are in the previous generation (in a steady-state run, the generation its
    /// birth was bred from, not recorded).
    pub parents_generation: Option<u32>,
    /// The operator that made it, e.g. `mutation`, `crossover`, `random`, `elite`.
    pub operator: String,
    /// The genome as text, for people (an L-system's `.lsys` text, say).
    pub genome_text: String,
    /// The genome as JSON (serde), to resume a run.
    pub genome_json: String,
    /// Its fitness; a failed evaluation scores the failure floor −999999, a normal value.
    pub fitness: f64,
    /// The evaluation's status, e.g. `ok` or the reason it failed.
    pub status: String,
    /// The fitness terms as a JSON object.
    pub terms_json: String,
    /// How many parts its body has.
    pub parts: u32,
    /// How many joints its body has.
    pub joints: u32,
    /// How many neurons its brain has.
    pub neurons: u32,
    /// Whether its evaluation was taken from an identical creature evaluated earlier in the
    /// run (always false for an elite, which is carried over, and in a run without cache).
    pub reused: bool,
    /// The key of its creature and the run's task, as 64 hex digits (`None` when it did not
    /// develop, or it was stored before schema version 3).
    pub evaluation_key: Option<String>,
}

/// The evaluation key, fitness and reuse of one stored individual: what a resumed run needs
/// to rebuild its evaluation cache.
#[derive(Debug, Clone, PartialEq)]
pub struct StoredKey {
    /// The index of its generation.
    pub generation: u32,
    /// Its index within the generation.
    pub index: u32,
    /// Its fitness (NaN where the store holds NULL).
    pub fitness: f64,
    /// Whether its evaluation was reused.
    pub reused: bool,
    /// Its evaluation key as 64 hex digits, if it has one.
    pub evaluation_key: Option<String>,
}

/// NaN becomes NULL: SQLite has no NaN (it would store NULL anyway, but say so).
pub(super) fn real(x: f64) -> Option<f64> {
    (!x.is_nan()).then_some(x)
}

/// NULL becomes NaN.
pub(super) fn get_real(r: &Row<'_>, i: usize) -> rusqlite::Result<f64> {
    Ok(r.get::<_, Option<f64>>(i)?.unwrap_or(f64::NAN))
}

pub(super) fn individual_from_row(r: &Row<'_>) -> rusqlite::Result<IndividualRecord> {
    let parents: String = r.get(2)?;
    let parents = serde_json::from_str(&parents).map_err(|e| {
        rusqlite::Error::FromSqlConversionFailure(2, rusqlite::types::Type::Text, Box::new(e))
    })?;
    Ok(IndividualRecord {
        generation: r.get(0)?,
        index: r.get(1)?,
        parents,
        operator: r.get(3)?,
        genome_text: r.get(4)?,
        genome_json: r.get(5)?,
        fitness: get_real(r, 6)?,
        status: r.get(7)?,
        terms_json: r.get(8)?,
        parts: r.get(9)?,
        joints: r.get(10)?,
        neurons: r.get(11)?,
        reused: r.get(12)?,
        evaluation_key: r.get(13)?,
        parents_generation: r.get(14)?,
    })
}
