//! `ontogeny replay`

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use ontogeny::lang::{Diagnostic, DiagnosticKind};
use ontogeny::render::MAX_FPS;
use ontogeny::task::Recording;

/// Flags of `ontogeny replay`.
#[derive(Args)]
pub struct ReplayArgs {
    /// A directory written by `ontogeny eval --record DIR`, or a run directory written by
    /// `ontogeny evolve`.
    dir: PathBuf,
    /// Frames per second of the animation, in (0, 50]; image k shows the recording at
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

/// Re-renders `DIR/recording.json` into `DIR/behaviour.gif`.
pub fn run(args: &ReplayArgs) -> anyhow::Result<()> {
    if !(args.fps > 0.0 && args.fps <= MAX_FPS) {
        anyhow::bail!(Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!(
                "--fps must be in (0, {}], not {} (GIF frames last whole centiseconds)",
                MAX_FPS, args.fps
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
    let playback = super::eval::draw_recording(
        &recording,
        &gif,
        args.fps,
        "the evaluation was refused before simulating",
    )?;
    say!(
        "wrote {} ({} frames at {} frames/s, of {} recorded)",
        gif.display(),
        playback.shown.len(),
        ontogeny::lsystem::format_number(playback.fps),
        recording.samples.len()
    );
    Ok(())
}
