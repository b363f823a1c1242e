//! `ontogeny replay`

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use ontogeny::creature::Creature;
use ontogeny::lang::{Diagnostic, DiagnosticKind};
use ontogeny::task::RecordedFrame;

/// Flags of `ontogeny replay`.
#[derive(Args)]
pub struct ReplayArgs {
    /// A directory written by `ontogeny eval --record DIR`, or a run directory written by
    /// `ontogeny evolve`.
    dir: PathBuf,
    /// Frames per second of the animation, in (0, 50]; each frame shows the recording at
    /// k / fps seconds, and plays back in real time.
    #[arg(long, default_value_t = 10.0)]
    fps: f64,
    /// For a run: the generation (default: the last complete one).
    #[arg(long = "gen", value_name = "G")]
    generation: Option<u32>,
    /// For a run: the individual's rank in its generation, 1 for the best.
    #[arg(long, default_value_t = 1)]
    rank: usize,
}

#[derive(serde::Deserialize)]
struct Recording {
    creature: Creature,
    frames: Vec<RecordedFrame>,
    /// The aim task's target (absent or null for other tasks).
    #[serde(default)]
    target: Option<[f64; 3]>,
}

/// Re-renders `DIR/recording.json` into `DIR/behaviour.gif`.
pub fn run(args: &ReplayArgs) -> anyhow::Result<()> {
    if !(args.fps > 0.0 && args.fps <= super::eval::MAX_FPS) {
        anyhow::bail!(Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!(
                "--fps must be in (0, {}], not {} (GIF frames last whole centiseconds)",
                super::eval::MAX_FPS,
                args.fps
            ),
        ));
    }
    if args.dir.join("config.toml").exists() {
        return super::evolve::replay_run(&args.dir, args.generation, args.rank, args.fps);
    }
    let path = args.dir.join("recording.json");
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let recording: Recording = serde_json::from_str(&text).map_err(|e| {
        anyhow::Error::new(Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!("{}: not a recording: {e}", path.display()),
        ))
    })?;
    recording.creature.check_consistency().map_err(|problem| {
        anyhow::Error::new(Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!("{}: not a usable creature: {problem}", path.display()),
        ))
    })?;
    let gif = args.dir.join("behaviour.gif");
    super::check_outputs([&gif])?;
    let target = recording
        .target
        .map(|[x, y, z]| nalgebra::Vector3::new(x, y, z));
    super::eval::render_recording(
        &recording.creature,
        &recording.frames,
        target,
        &gif,
        args.fps,
    )?;
    let (shown, _, fps) = super::eval::animation_frames(&recording.frames, args.fps);
    say!(
        "wrote {} ({} frames at {} frames/s, of {} recorded)",
        gif.display(),
        shown.len(),
        ontogeny::lsystem::format_number(fps),
        recording.frames.len()
    );
    Ok(())
}
