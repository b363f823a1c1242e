//! Reading the creature a verb is given (`eval`, `export`, `bench`) with the library's
//! [`ontogeny::encoding::load_creature`]: an L-system grown to its last frame, a
//! `creature.json`, or a graph genome's JSON, each checked before use.

use std::path::Path;

use ontogeny::creature::Creature;
use ontogeny::encoding::{LoadError, LoadOptions, load_creature as load};
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, DeriveOptions};

use super::derive::{DevelopmentArgs, derive_options};
use super::progress::Progress;

/// Loads a creature from `file` ([`ontogeny::encoding::load_creature`]) with the development
/// flags (seed and defines included), printing its notes and warnings; the development flags given for a JSON
/// file, which is not grown, are ignored with a warning.
pub(super) fn load_creature(
    file: &Path,
    development: &DevelopmentArgs,
    max_parts: usize,
) -> anyhow::Result<Creature> {
    load_creature_with(
        file,
        development,
        development.seed.seed(),
        max_parts,
        DEFAULT_MAX_MODULES,
        None,
    )
}

/// [`load_creature`] with a derived string's most modules, `max_modules` (a run's limit, for
/// its champion), in a habitat whose chemical array starts as `environment`, if given.
pub(super) fn load_creature_with(
    file: &Path,
    development: &DevelopmentArgs,
    seed: Option<u64>,
    max_parts: usize,
    max_modules: usize,
    environment: Option<&[f64]>,
) -> anyhow::Result<Creature> {
    if file.extension().is_some_and(|e| e == "json") {
        let flags = development.given();
        if !flags.is_empty() {
            tell!(
                "warning: {} {} a creature from a grammar; {} is not one: ignored",
                flags.join(", "),
                if flags.len() == 1 { "grows" } else { "grow" },
                file.display()
            );
        }
    }
    let options = LoadOptions {
        derive: DeriveOptions {
            seed,
            ..derive_options(development, max_modules)
        },
        habitat_environment: environment.map(<[f64]>::to_vec),
        defines: development.defines.defines.clone(),
        steps: development.steps,
        max_parts,
        ..LoadOptions::default()
    };
    let mut progress = Progress::new("growing");
    let loaded = load(file, &options, &mut |f| progress.set(f)).map_err(|e| match e {
        LoadError::Read { path, source } => {
            anyhow::Error::new(source).context(format!("cannot read {}", path.display()))
        }
        LoadError::Bad(d) => anyhow::Error::new(d),
    })?;
    progress.finish();
    for note in loaded.notes {
        tell!("{note}");
    }
    Ok(loaded.creature)
}
