//! `ontogeny export`

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use ontogeny::export::to_mjcf_in;
use ontogeny::sim::WorldSpec;

use super::derive::DevelopmentArgs;
use super::input::load_creature;
use super::physics::PhysicsArgs;

/// Export formats.
#[derive(Clone, Copy, ValueEnum)]
enum FormatArg {
    /// MuJoCo's MJCF (XML), Z up.
    Mjcf,
}

/// Write a creature (an `.lsys` grown to its last frame, or to developmental time T with
/// `--time T`, or a `creature.json`) with the simulator's settings as a MuJoCo MJCF model.
#[derive(Args)]
#[command(after_long_help = "\
Writes the creature as a MuJoCo MJCF model: the body tree from the root part with a free \
joint, one box geom per part (sizes are half-extents), the joints as hinges with their ranges \
(radians; a joint of 2 or 3 degrees of freedom is 2 or 3 hinges), one actuator per driven \
degree of freedom matching --actuator, contact exclusions between jointed parts, and the \
density, friction and time step of the simulator. Ontogeny's Y-up world is rotated so that Z \
is up. docs/guide/exporting.md details every mapping. MJCF has no growth: a grammar in \
continuous time is exported as the creature at one developmental time (its `time:`, or \
--time T), as a walk with `develop = \"during\"` drops it at `develop_t0` = T.

Examples:
  ontogeny export examples/quadruped.lsys --out quadruped.xml
  ontogeny export out/snake/creature.json --actuator angle > snake.xml
  ontogeny export examples/grow-while-walking.lsys --time 2 --out grown-at-2.xml")]
pub struct ExportArgs {
    /// An L-system file (`.lsys`, grown to its last frame) or a `creature.json`.
    file: PathBuf,
    /// The format to write.
    #[arg(long, value_enum, default_value = "mjcf")]
    format: FormatArg,
    /// Write the model to this file (default: standard output).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// Most parts: a creature grown from an L-system with more is invalid, a
    /// `creature.json` with more is refused.
    #[arg(long, default_value_t = ontogeny::develop::BuildOptions::default().max_parts, value_parser = super::parse_part_count)]
    max_parts: usize,
    #[command(flatten)]
    physics: PhysicsArgs,
    /// A configuration file whose `[task.world]` the creature is exported in: its ground,
    /// obstacles, objects and medium (default: flat ground in air).
    #[arg(long, value_name = "CONFIG")]
    world: Option<PathBuf>,
}

/// The `[task.world]` table of the configuration file at `path`, checked (none: the flat
/// world).
fn read_world(path: &std::path::Path) -> anyhow::Result<WorldSpec> {
    let source = ontogeny::run::config::read_config_source(path)?;
    let table: toml::Table = toml::from_str(source.text())
        .map_err(|e| super::bad(format!("{}: {}", path.display(), e.message())))?;
    let Some(value) = table.get("task").and_then(|task| task.get("world")) else {
        return Ok(WorldSpec::default());
    };
    let world = value
        .clone()
        .try_into::<WorldSpec>()
        .map_err(|e| super::bad(format!("{}: [task.world]: {}", path.display(), e.message())))?;
    world
        .check()
        .map_err(|e| super::bad(format!("{}: [task.world]: {e}", path.display())))?;
    Ok(world)
}

/// The developmental time of the creature exported, when `args.file` is a grammar in
/// continuous time: `--time`, else the file's `time:`.
fn developmental_time(args: &ExportArgs) -> Option<f64> {
    if args.file.extension().is_none_or(|e| e != "lsys") {
        return None;
    }
    let overrides = ontogeny::lsystem::Overrides {
        defines: args.development.defines.defines.clone(),
        seed: args.development.seed.seed(),
    };
    let lsys = ontogeny::lsystem::LSystem::from_path_with(&args.file, &overrides).ok()?;
    let derive = super::derive::derive_options(&args.development, 0);
    derive.time.or(lsys.time())
}

/// Exports the creature.
pub fn run(args: &ExportArgs) -> anyhow::Result<()> {
    let creature = load_creature(&args.file, &args.development, args.max_parts)?;
    if let Some(t) = developmental_time(args) {
        tell!(
            "note: MJCF has no growth: the model is the creature at developmental time {} (choose \
             another moment with --time T); in MuJoCo it does not grow",
            ontogeny::number::format_number(t)
        );
    }
    let sim = args.physics.sim_options()?;
    let world = match &args.world {
        Some(path) => read_world(path)?,
        None => WorldSpec::default(),
    };
    let name = args
        .file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "creature".to_string());
    let text = match args.format {
        FormatArg::Mjcf => to_mjcf_in(&creature, &sim, &name, &world),
    }
    .map_err(|e| super::bad(format!("{}: cannot export: {e}", args.file.display())))?;
    match &args.out {
        Some(path) => {
            ontogeny::output::write(path, &text)?;
            tell!("{}", ontogeny::output::wrote(&[path]));
        }
        None => {
            use std::io::Write as _;
            std::io::stdout().lock().write_all(text.as_bytes())?;
        }
    }
    Ok(())
}
