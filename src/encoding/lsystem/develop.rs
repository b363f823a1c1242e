//! The L-system genome's development: its text grown through the language, exactly as
//! `ontogeny grow` grows a file, building only the last frame; and what makes a creature a
//! driven walker.

use super::*;

/// Grows `text` as `ontogeny grow --max-modules M --max-parts P` does, building only the
/// last frame (`develop::grow` builds every frame the same way, so its last creature is this
/// one); `seed` drives stochastic rules; `env`, of the size of the text's `environment:`,
/// replaces its initial values (as `--env` does). One budget more than `grow`'s: the
/// builder interprets at most `max_modules` modules in all, the passes of repeat blocks
/// included (past it the creature is invalid), so that a genome's repeat blocks never make
/// its development more work than a string of `max_modules` modules; a text without repeat
/// blocks develops exactly as `grow` grows it.
pub(crate) fn develop_text(
    text: &str,
    max_modules: usize,
    max_parts: usize,
    seed: u64,
    env: Option<&Environment>,
) -> Result<Creature, DevelopError> {
    let lsys = LSystem::from_text("genome.lsys", text)
        .map_err(|d| DevelopError(format!("the genome does not compile: {d}")))?;
    let options = DeriveOptions {
        seed: Some(seed),
        max_modules,
        env: env
            .map(|e| e.values().iter().copied().enumerate().collect())
            .unwrap_or_default(),
        ..DeriveOptions::default()
    };
    let build_options = BuildOptions {
        max_parts,
        ..BuildOptions::default()
    };
    last_frame(&lsys, &options, |shown, env, t| {
        let build_options = BuildOptions {
            max_repeated_modules: max_modules.saturating_sub(shown.len()),
            ..build_options
        };
        build(shown, lsys.symbols(), env, Some(t), &build_options)
    })
    .map_err(|d| DevelopError(d.to_string()))
}

/// Runs `lsys` to its last frame, as `ontogeny grow` does, and gives `visit` that frame's
/// string after the interpretation rules (what the builder sees), its environment and time.
pub(crate) fn last_frame<T>(
    lsys: &LSystem,
    options: &DeriveOptions,
    visit: impl FnOnce(&ModuleString, &Environment, f64) -> T,
) -> Result<T, lang::Diagnostic> {
    let mut visit = Some(visit);
    let mut out = None;
    lsys.for_each_frame(options, None, |frame| {
        if frame.last
            && let Some(visit) = visit.take()
        {
            let shown = lsys.interpret(frame.string, frame.t, options)?;
            out = Some(visit(&shown, frame.env, frame.t));
        }
        Ok::<(), lang::Diagnostic>(())
    })?;
    out.ok_or_else(|| {
        lang::Diagnostic::without_location(
            lang::DiagnosticKind::Runtime,
            "development produced no frame".to_string(),
        )
    })
}

/// Whether a creature can walk: valid, at least 2 parts, and a movable joint that an
/// actuator neuron with an input drives.
pub fn is_driven_walker(creature: &Creature) -> bool {
    let driven = creature.brain.neurons.iter().enumerate().any(|(k, n)| {
        matches!(
            n.role,
            Role::Actuator {
                actuator: Actuator::Joint { .. }
            }
        ) && creature
            .brain
            .links
            .iter()
            .any(|l| l.to == k && l.weight != 0.0)
    });
    creature.is_valid() && creature.parts.len() >= 2 && driven
}

/// The most modules any string `text` derives holds, and the parts of its last creature,
/// grown as [`develop_text`] grows it under the widest limits that any run may set
/// ([`MOST_MODULES`](crate::encoding::limits::MOST_MODULES),
/// [`MOST_PARTS`](crate::encoding::limits::MOST_PARTS)); `Err` says why it does not grow.
pub(crate) fn grown_size(text: &str) -> Result<(usize, usize), String> {
    let lsys = LSystem::from_text("genome.lsys", text).map_err(|d| d.message)?;
    let options = DeriveOptions {
        seed: Some(0),
        max_modules: crate::encoding::limits::MOST_MODULES,
        ..DeriveOptions::default()
    };
    let build_options = BuildOptions {
        max_parts: crate::encoding::limits::MOST_PARTS,
        ..BuildOptions::default()
    };
    let mut most = 0;
    let mut parts = None;
    lsys.for_each_frame(&options, None, |frame| {
        most = most.max(frame.string.len());
        if frame.last {
            let creature = build_frame(&lsys, &frame, &options, &build_options)?;
            parts = Some(creature.parts.len());
        }
        Ok::<(), lang::Diagnostic>(())
    })
    .map_err(|d| d.message)?;
    parts
        .map(|parts| (most, parts))
        .ok_or_else(|| "it makes no frame".to_string())
}
