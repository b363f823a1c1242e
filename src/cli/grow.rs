//! `ontogeny grow`

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use ontogeny::creature::{Creature, Problem, Role};
use ontogeny::develop::{BuildOptions, GrowthFrame, for_each_growth_frame, kept_frame_plan};
use ontogeny::lang::Diagnostic;
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, DeriveOptions, FramePlan, LSystem};
use serde::Serialize;

use super::derive::{DevelopmentArgs, derive_options, discrete_steps};
use ontogeny::render::{MAX_GIF_IMAGES, evenly_in_time};

/// Flags of `ontogeny grow`.
#[derive(Args)]
pub struct GrowArgs {
    /// The L-system file (`.lsys`); `-` reads it from standard input.
    file: PathBuf,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// Seed for stochastic rules and random functions (default: the file's `seed:`, else 0).
    #[arg(long)]
    seed: Option<u64>,
    /// Stop with an error when the string grows longer than this.
    #[arg(long, default_value_t = DEFAULT_MAX_MODULES)]
    max_modules: usize,
    /// A creature with more parts than this is invalid.
    #[arg(long, default_value_t = BuildOptions::default().max_parts)]
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

/// What `grow` says about the final creature.
#[derive(Serialize)]
struct Summary {
    file: String,
    t: f64,
    frames: usize,
    parts: usize,
    joints: BTreeMap<String, usize>,
    neurons: usize,
    links: usize,
    sensors: usize,
    actuators: usize,
    mass: f64,
    bounding_box: [[f64; 3]; 2],
    valid: bool,
    problems: Vec<String>,
}

fn summarise(file: &str, t: f64, frames: usize, c: &Creature) -> Summary {
    let mut joints = BTreeMap::new();
    for j in &c.joints {
        let name = serde_json::to_value(j.kind)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default();
        *joints.entry(name).or_insert(0) += 1;
    }
    let (lo, hi) = c.bounding_box();
    Summary {
        file: file.to_string(),
        t,
        frames,
        parts: c.parts.len(),
        joints,
        neurons: c.brain.neurons.len(),
        links: c.brain.links.len(),
        sensors: c
            .brain
            .neurons
            .iter()
            .filter(|n| matches!(n.role, Role::Sensor { .. }))
            .count(),
        actuators: c
            .brain
            .neurons
            .iter()
            .filter(|n| matches!(n.role, Role::Actuator { .. }))
            .count(),
        mass: c.mass(),
        bounding_box: [[lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z]],
        valid: c.is_valid(),
        problems: no_part(c)
            .into_iter()
            .chain(c.problems.iter().map(Problem::to_string))
            .collect(),
    }
}

/// The problem of a creature without parts, which development does not list (growth may
/// start from nothing): there is nothing to simulate.
fn no_part(c: &Creature) -> Option<String> {
    c.parts.is_empty().then(|| {
        "error: no part: the string builds nothing (a part comes from forward or its maturing twin mforward; see README \"Building creatures\")".to_string()
    })
}

/// How long (centiseconds) each image of a growth animation of `images` images shows: a
/// quarter of a second, shorter for long animations so that the whole plays in at most
/// 30 s, and never under 4 cs (browsers slow shorter images down).
fn growth_image_delay(images: usize) -> u16 {
    (3000 / images.max(1)).clamp(4, 25) as u16
}

/// Draws `growth.gif` from `frames`, the frames [`growth_gif_steps`] chose (the first and
/// last kept), of `total` frames of growth, labelled with developmental time, with a note
/// when some are left out and a progress bar on a terminal.
fn write_growth_gif(frames: &[GrowthFrame], total: u64, path: &Path) -> anyhow::Result<()> {
    if (frames.len() as u64) < total {
        eprintln!(
            "note: {total} frames of growth: {} shows {} of them, evenly spaced in developmental \
             time, to keep to {MAX_GIF_IMAGES} frames",
            path.display(),
            frames.len()
        );
    }
    let labels: Vec<ontogeny::render::Overlay> = frames
        .iter()
        .map(|frame| ontogeny::render::Overlay {
            label: vec![format!("t = {}", ontogeny::lsystem::format_number(frame.t))],
            ..Default::default()
        })
        .collect();
    let mut progress = super::progress::Progress::new("drawing growth.gif");
    ontogeny::render::write_gif_with_progress(
        frames.iter().map(|frame| &frame.creature),
        &labels,
        path,
        480,
        300,
        &[growth_image_delay(frames.len())],
        ontogeny::render::Framing::Still,
        &mut |f| progress.set(f),
    )
    .map_err(super::render_error(path))?;
    progress.finish();
    Ok(())
}

/// Which frames (by step) `growth.gif` shows: at most [`MAX_GIF_IMAGES`], evenly spaced in
/// developmental time, the first and last kept; `wanted[step]` says whether frame `step` is one.
fn growth_gif_steps(plan: &FramePlan) -> Vec<bool> {
    let times: Vec<f64> = (0..=plan.last_step()).map(|k| plan.time(k)).collect();
    let mut wanted = vec![false; times.len()];
    for i in evenly_in_time(&times, MAX_GIF_IMAGES) {
        wanted[i] = true;
    }
    wanted
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
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
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
    write_growth_gif(shown, last.step + 1, &dir.join("growth.gif"))
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
    let lsys = LSystem::from_path(&args.file)?;
    let options = derive_options(&args.development, args.seed, args.max_modules);
    let build_options = BuildOptions {
        max_parts: args.max_parts,
        ..BuildOptions::default()
    };
    let steps = discrete_steps(&lsys, &options, args.development.steps, "growing")?;
    // Outputs that are not regular files are refused before anything is grown.
    if let Some(dir) = &args.out {
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
    progress.finish();
    let last = last.expect("at least the first frame");
    let frames = last.step as usize + 1;
    let summary = summarise(lsys.source().name(), last.t, frames, &last.creature);
    if let Some(dir) = &args.out {
        let grown = Grown {
            lsys: &lsys,
            options: &options,
            steps,
            build_options: &build_options,
        };
        write_out(dir, &grown, &last, &shown, &summary)?;
    }
    if args.json {
        say!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    let s = &summary;
    say!(
        "{}: grown to t = {} in {} frame(s)",
        s.file,
        ontogeny::lsystem::format_number(s.t),
        s.frames
    );
    let joints: Vec<String> = s.joints.iter().map(|(k, n)| format!("{n} {k}")).collect();
    say!(
        "parts: {}   joints: {}",
        s.parts,
        if joints.is_empty() {
            "none".to_string()
        } else {
            joints.join(", ")
        }
    );
    say!(
        "brain: {} neurons ({} sensors, {} actuators), {} links",
        s.neurons,
        s.sensors,
        s.actuators,
        s.links
    );
    let [lo, hi] = s.bounding_box;
    say!(
        "mass: {:.4}   bounding box: ({:.3}, {:.3}, {:.3}) to ({:.3}, {:.3}, {:.3})",
        s.mass,
        lo[0],
        lo[1],
        lo[2],
        hi[0],
        hi[1],
        hi[2]
    );
    say!("valid: {}", if s.valid { "yes" } else { "no" });
    for p in &s.problems {
        say!("  {p}");
    }
    if let Some(dir) = &args.out {
        say!(
            "wrote {0}/creature.json, {0}/frames.jsonl, {0}/creature.png and {0}/growth.gif",
            dir.display()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::growth_image_delay;

    #[test]
    fn a_growth_animation_plays_in_at_most_half_a_minute() {
        // Up to 120 images: a quarter of a second each.
        assert_eq!(growth_image_delay(1), 25);
        assert_eq!(growth_image_delay(120), 25);
        // 600 images (the most a GIF holds): 5 cs each, 30 s in all.
        assert_eq!(growth_image_delay(600), 5);
        assert!(growth_image_delay(300) as usize * 300 <= 3000);
        // Never under 4 cs.
        assert_eq!(growth_image_delay(10_000), 4);
        assert_eq!(growth_image_delay(0), 25);
    }
}
