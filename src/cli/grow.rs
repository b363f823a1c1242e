//! `ontogeny grow`

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use ontogeny::creature::{Creature, Problem, Role, Severity};
use ontogeny::develop::{BuildOptions, GrowthFrame, grow_with_progress};
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, LSystem};
use serde::Serialize;

use super::derive::{DevelopmentArgs, derive_options, discrete_steps};
use super::eval::{MAX_GIF_FRAMES, evenly_in_time};

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
            .chain(c.problems.iter().map(problem_line))
            .collect(),
    }
}

/// A problem development found, as `grow` and `eval` print it: "warning: MESSAGE [MODULE] at
/// t = T".
pub(super) fn problem_line(p: &Problem) -> String {
    let level = match p.severity {
        Severity::Warning => "warning",
        Severity::Error => "error",
    };
    let module = p
        .module
        .as_deref()
        .map(|m| format!(" [{m}]"))
        .unwrap_or_default();
    let t = p.t.map(|t| format!(" at t = {t}")).unwrap_or_default();
    format!("{level}: {}{module}{t}", p.message)
}

/// The problem of a creature without parts, which development does not list (growth may
/// start from nothing): there is nothing to simulate.
fn no_part(c: &Creature) -> Option<String> {
    c.parts.is_empty().then(|| {
        "error: no part: the string builds nothing (a part comes from forward or its maturing twin mforward; see README \"Building creatures\")".to_string()
    })
}

/// How long (centiseconds) each frame of a growth animation of `frames` frames shows: a
/// quarter of a second, shorter for long animations so that the whole plays in at most
/// 30 s, and never under 4 cs (browsers slow shorter frames down).
fn growth_frame_delay(frames: usize) -> u16 {
    (3000 / frames.max(1)).clamp(4, 25) as u16
}

/// Draws `growth.gif`: the frames of growth labelled with developmental time, at most
/// [`MAX_GIF_FRAMES`] of them (evenly spaced in developmental time, the first and last
/// kept, with a note when some are left out), with a progress bar on a terminal.
fn write_growth_gif(frames: &[GrowthFrame], path: &Path) -> anyhow::Result<()> {
    let times: Vec<f64> = frames.iter().map(|f| f.t).collect();
    let chosen = evenly_in_time(&times, MAX_GIF_FRAMES);
    if chosen.len() < frames.len() {
        eprintln!(
            "note: {} frames of growth: {} shows {} of them, evenly spaced in developmental \
             time, to keep to {MAX_GIF_FRAMES} frames",
            frames.len(),
            path.display(),
            chosen.len()
        );
    }
    let labels: Vec<ontogeny::render::Overlay> = chosen
        .iter()
        .map(|&i| ontogeny::render::Overlay {
            label: vec![format!(
                "t = {}",
                ontogeny::lsystem::format_number(frames[i].t)
            )],
            ..Default::default()
        })
        .collect();
    let mut progress = super::progress::Progress::new("drawing growth.gif");
    ontogeny::render::write_gif_with_progress(
        chosen.iter().map(|&i| &frames[i].creature),
        &labels,
        path,
        480,
        300,
        &[growth_frame_delay(chosen.len())],
        ontogeny::render::Framing::Still,
        &mut |f| progress.set(f),
    )
    .map_err(super::render_error(path))?;
    progress.finish();
    Ok(())
}

/// Grows the file into creatures and reports on the last one.
pub fn run(args: &GrowArgs) -> anyhow::Result<()> {
    let lsys = LSystem::from_path(&args.file)?;
    let options = derive_options(&args.development, args.seed, args.max_modules);
    let build_options = BuildOptions {
        max_parts: args.max_parts,
        ..BuildOptions::default()
    };
    let steps = discrete_steps(&lsys, &options, args.development.steps, "growing")?;
    let mut progress = super::progress::Progress::new("growing");
    let frames = grow_with_progress(&lsys, &options, steps, &build_options, &mut |f| {
        progress.set(f)
    })?;
    progress.finish();
    let last = frames.last().expect("at least the first frame");
    let summary = summarise(lsys.source().name(), last.t, frames.len(), &last.creature);
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        super::check_outputs(
            [
                "creature.json",
                "frames.jsonl",
                "creature.png",
                "growth.gif",
            ]
            .map(|f| dir.join(f)),
        )?;
        let path = dir.join("creature.json");
        ontogeny::output::write(&path, serde_json::to_string_pretty(&last.creature)?)?;
        let path = dir.join("frames.jsonl");
        ontogeny::output::write_with(&path, |out| -> anyhow::Result<()> {
            for frame in &frames {
                serde_json::to_writer(&mut *out, frame)?;
                writeln!(out).with_context(|| format!("cannot write {}", path.display()))?;
            }
            Ok(())
        })?;
        let path = dir.join("creature.png");
        ontogeny::render::write_png(&last.creature, &summary.file, &path, 960, 600)
            .map_err(super::render_error(&path))?;
        write_growth_gif(&frames, &dir.join("growth.gif"))?;
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
    use super::growth_frame_delay;

    #[test]
    fn a_growth_animation_plays_in_at_most_half_a_minute() {
        // Up to 120 frames: a quarter of a second each.
        assert_eq!(growth_frame_delay(1), 25);
        assert_eq!(growth_frame_delay(120), 25);
        // 600 frames (the most a GIF holds): 5 cs each, 30 s in all.
        assert_eq!(growth_frame_delay(600), 5);
        assert!(growth_frame_delay(300) as usize * 300 <= 3000);
        // Never under 4 cs.
        assert_eq!(growth_frame_delay(10_000), 4);
        assert_eq!(growth_frame_delay(0), 25);
    }
}
