//! `ontogeny grow`

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use ontogeny::creature::Summary;
use ontogeny::develop::{
    BuildOptions, GrowthFrame, for_each_growth_frame, grow_last, kept_frame_plan,
};
use ontogeny::lang::Diagnostic;
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, DeriveOptions, LSystem};
use ontogeny::output::FolderKind;

use super::derive::{DevelopmentArgs, discrete_steps};
use ontogeny::render::growth::{growth_gif_note, growth_gif_steps, write_growth_gif};

/// Grow creatures: build the body and brain the derived strings describe, at every
/// frame, and summarise the last one (parts, joints, brain, mass, size, validity).
#[derive(Args)]
pub struct GrowArgs {
    /// The L-system file (`.lsys`); `-` reads it from standard input.
    file: PathBuf,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// Stop with an error when the string grows longer than this.
    #[arg(long, default_value_t = DEFAULT_MAX_MODULES)]
    max_modules: usize,
    /// A creature with more parts than this is invalid.
    #[arg(long, default_value_t = BuildOptions::default().max_parts, value_parser = super::parse_part_count)]
    max_parts: usize,
    /// Write creature.json (the final creature), frames.jsonl (one creature per frame),
    /// creature.png (a 3/4 view of the body and a drawing of the brain) and growth.gif (the
    /// frames as an animation) into this directory.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

/// Writes `--out`: creature.json, frames.jsonl (every frame, built again one at a time as it
/// is written, so that no more than one is held), creature.png and growth.gif (`shown`, the
/// frames chosen for it). Called once growing has succeeded, so that a failed growth writes
/// nothing.
fn write_out(
    dir: &Path,
    grown: &Grown<'_>,
    last: &GrowthFrame,
    shown: &[GrowthFrame],
    summary: &Summary,
) -> anyhow::Result<()> {
    ontogeny::output::prepare_folder(dir, FolderKind::Growth)?;
    super::check_outputs(OUT_FILES.map(|f| dir.join(f)))?;
    let path = dir.join("creature.json");
    ontogeny::output::write(&path, serde_json::to_string_pretty(&last.creature)?)?;
    let path = dir.join("frames.jsonl");
    let mut progress = super::progress::Progress::new("writing frames.jsonl");
    ontogeny::output::write_with(&path, |out| -> anyhow::Result<()> {
        for_each_growth_frame(
            grown.lsys,
            grown.options,
            grown.steps,
            grown.build_options,
            |_, _| true,
            &mut |f| progress.set(f),
            |frame| {
                serde_json::to_writer(&mut *out, &frame)
                    .map_err(std::io::Error::from)
                    .and_then(|()| writeln!(out))
                    .with_context(|| format!("cannot write {}", path.display()))
            },
        )?;
        Ok(())
    })?;
    progress.finish();
    let path = dir.join("creature.png");
    ontogeny::render::write_png(&last.creature, &summary.file, &path, 960, 600)
        .map_err(super::render_error(&path))?;
    let path = dir.join("growth.gif");
    if let Some(note) = growth_gif_note(shown.len(), last.step + 1, &path) {
        tell!("{note}");
    }
    let mut progress = super::progress::Progress::new("drawing growth.gif");
    write_growth_gif(shown, &path, &mut |f| progress.set(f)).map_err(super::render_error(&path))
}

/// The files `--out` writes.
const OUT_FILES: [&str; 4] = [
    "creature.json",
    "frames.jsonl",
    "creature.png",
    "growth.gif",
];

/// What one growth is made of, to grow it again frame by frame.
struct Grown<'a> {
    lsys: &'a LSystem,
    options: &'a DeriveOptions,
    steps: Option<u64>,
    build_options: &'a BuildOptions,
}

/// Grows the file into creatures and reports on the last one. Only the frames needed are
/// held: the last one, and with `--out` the ones `growth.gif` shows (at most
/// [`ontogeny::develop::MAX_KEPT_FRAMES`] frames may be written).
pub fn run(args: &GrowArgs) -> anyhow::Result<()> {
    let (lsys, options) = args.development.load(&args.file, args.max_modules)?;
    // A picture: overlapping parts and a body in pieces are warnings here, errors where
    // physics needs the creature (`eval`, `evolve`).
    let build_options = BuildOptions {
        max_parts: args.max_parts,
        for_picture: true,
        ..BuildOptions::default()
    };
    let steps = discrete_steps(&lsys, &options, args.development.steps, "growing")?;
    // A folder of the user's, and outputs that are not regular files, are refused before
    // anything is grown.
    if let Some(dir) = &args.out {
        ontogeny::output::check_folder(dir, FolderKind::Growth)?;
        super::check_outputs(OUT_FILES.map(|f| dir.join(f)))?;
    }
    // With --out every frame is written: refused at once when there are too many.
    let gif_steps = match &args.out {
        Some(_) => Some(growth_gif_steps(&kept_frame_plan(&lsys, &options, steps)?)),
        None => None,
    };
    let mut progress = super::progress::Progress::new("growing");
    let mut shown = Vec::new();
    let mut last = None;
    if gif_steps.is_none() {
        // Only the last creature is wanted: grown cut short where it is decided.
        let grown = grow_last(&lsys, &options, steps, &build_options, &mut |f| {
            progress.set(f)
        })?;
        if let Some(shortcut) = grown.shortcut {
            tell!("note: {shortcut}");
        }
        last = Some(grown.frame);
    } else {
        for_each_growth_frame(
            &lsys,
            &options,
            steps,
            &build_options,
            |step, is_last| {
                is_last
                    || gif_steps
                        .as_ref()
                        .is_some_and(|wanted| wanted.get(step as usize) == Some(&true))
            },
            &mut |f| progress.set(f),
            |frame| {
                if gif_steps.is_some() {
                    shown.push(frame.clone());
                }
                last = Some(frame);
                Ok::<(), Diagnostic>(())
            },
        )?;
    }
    progress.finish();
    let last = last.expect("at least the first frame");
    let frames = last.step as usize + 1;
    let summary = Summary::of(lsys.source().name(), last.t, frames, &last.creature);
    if let Some(dir) = &args.out {
        let grown = Grown {
            lsys: &lsys,
            options: &options,
            steps,
            build_options: &build_options,
        };
        write_out(dir, &grown, &last, &shown, &summary)?;
    }
    if let Some(dir) = &args.out {
        tell!(
            "{}",
            ontogeny::output::wrote(&OUT_FILES.map(|f| dir.join(f)))
        );
    }
    match args.json {
        true => say!("{}", serde_json::to_string_pretty(&summary)?),
        false => say!("{}", summary.text()),
    }
    Ok(())
}
