//! `ontogeny view`

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::Context;
use clap::Args;
use ontogeny::encoding::Genome;
use ontogeny::evolve::run::Run;
use ontogeny::lang::{Diagnostic, DiagnosticKind};
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, LSystem};
use ontogeny::view::{Developer, Kind, Server, Target};

use super::derive::{DevelopmentArgs, derive_options};

/// The port `view` listens on when `--port` is not given (and not snapshotting).
const DEFAULT_PORT: u16 = 8750;

/// The size of a snapshot when `--size` is not given.
const DEFAULT_SIZE: (u32, u32) = (1280, 800);

/// Flags of `ontogeny view`.
#[derive(Args)]
pub struct ViewArgs {
    /// An `.lsys` file, or a directory written by `grow --out`, `eval --record` (or `replay`)
    /// or `evolve`.
    path: PathBuf,
    /// The port to listen on at 127.0.0.1 (0: any free port). Default 8750; with --snapshot,
    /// any free port.
    #[arg(long)]
    port: Option<u16>,
    /// Render the page in headless Chromium to this PNG file and exit, instead of serving.
    #[arg(long, value_name = "OUT.png")]
    snapshot: Option<PathBuf>,
    /// The frame to show first (0 the first, -1 the last; default: the last frame of growth,
    /// the first of a recording).
    #[arg(long, allow_negative_numbers = true)]
    frame: Option<i64>,
    /// The size of the snapshot in pixels, WIDTHxHEIGHT (default 1280x800; only with
    /// --snapshot).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// The browser `--snapshot` runs (default: $ONTOGENY_BROWSER, else the first of chromium,
    /// chromium-browser, google-chrome on the PATH).
    #[arg(long)]
    browser: Option<PathBuf>,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// For an `.lsys` file: the seed of stochastic rules (default: the file's `seed:`, else 0).
    #[arg(long)]
    seed: Option<u64>,
}

fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{text}' is not WIDTHxHEIGHT (e.g. 1280x800)");
    let (w, h) = text.split_once('x').ok_or_else(bad)?;
    let (w, h): (u32, u32) = (w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?);
    if !(64..=8192).contains(&w) || !(64..=8192).contains(&h) {
        return Err(format!(
            "{text}: width and height must be 64 to 8192 pixels"
        ));
    }
    Ok((w, h))
}

fn bad(message: impl Into<String>) -> anyhow::Error {
    anyhow::Error::new(Diagnostic::without_location(
        DiagnosticKind::Semantic,
        message.into(),
    ))
}

/// Serves the page (or renders it with `--snapshot`).
pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    let target = Target::classify(&args.path).map_err(|e| bad(e.to_string()))?;
    let options = derive_options(&args.development, args.seed, DEFAULT_MAX_MODULES);
    // A page that cannot be made at all is bad input; a grammar with an error is shown in the
    // page (watch mode lets the user fix it), and reported here too.
    let mut grammar_error = None;
    let mut developer = None;
    // How many frames the page has (None: not known, or a run page, which has none).
    let mut frames = None;
    match target.kind {
        Kind::Lsys => {
            // --dt and --timing are refused for a discrete file, as by every verb that grows.
            if let Ok(lsys) = LSystem::from_path(&target.path) {
                ontogeny::lsystem::print::check_continuous_options(&lsys, &options)?;
            }
            match LSystem::from_path(&target.path).and_then(|lsys| {
                ontogeny::develop::grow(
                    &lsys,
                    &options,
                    args.development.steps,
                    &ontogeny::develop::BuildOptions::default(),
                )
            }) {
                Ok(grown) => frames = Some(grown.len()),
                Err(d) => grammar_error = Some(d),
            }
        }
        Kind::Growth => {
            let data = ontogeny::view::growth_data(&target.path).map_err(|e| bad(e.to_string()))?;
            frames = data["frames"].as_array().map(Vec::len);
        }
        Kind::Recording => {
            let data =
                ontogeny::view::recording_data(&target.path).map_err(|e| bad(e.to_string()))?;
            frames = data["frames"].as_array().map(Vec::len);
            if let Some(reason) = data["no_frames"].as_str() {
                eprintln!(
                    "note: {}: {reason}; the page shows the creature as built",
                    target.path.display()
                );
            }
        }
        Kind::Run => {
            let data = ontogeny::view::run_data(&target.path).map_err(|e| bad(e.to_string()))?;
            let encoding = data["encoding"].as_str().unwrap_or_default().to_string();
            let dir = target.path.clone();
            let developer_of: anyhow::Result<Developer> = with_genome!(
                encoding.as_str(),
                G => Ok(developer_for::<G>(dir)),
                |other| Err(bad(format!(
                    "{}: unknown encoding '{other}'",
                    target.path.display()
                )))
            );
            developer = Some(developer_of?);
        }
    }
    for warning in ignored_flags(args, &target, frames) {
        eprintln!("warning: {warning}");
    }
    let port = args.port.unwrap_or(if args.snapshot.is_some() {
        0
    } else {
        DEFAULT_PORT
    });
    let server = Server::bind(
        target.clone(),
        port,
        options,
        args.development.steps,
        developer,
    )
    .map_err(|e| bad(e.to_string()))?;
    let mut query = Vec::new();
    if let Some(f) = args.frame {
        query.push(format!("frame={f}"));
    }
    if let Some(out) = &args.snapshot {
        query.push("still=1".to_string());
        let url = format!("{}?{}", server.url(), query.join("&"));
        std::thread::spawn(move || server.run());
        snapshot(args, &url, out)?;
        say!("wrote {}", out.display());
        if let Some(d) = grammar_error {
            // The picture shows the error; the exit code says it too.
            return Err(anyhow::Error::new(d));
        }
        return Ok(());
    }
    if let Some(d) = &grammar_error {
        eprintln!("{d}");
        eprintln!("(the page shows this error until the file is fixed and saved)");
    }
    let url = if query.is_empty() {
        server.url()
    } else {
        format!("{}?{}", server.url(), query.join("&"))
    };
    say!("ontogeny view: {} at {url}", target.path.display());
    say!("press Ctrl-C to stop");
    server.run();
    Ok(())
}

/// What the flags given do not do for this page, one warning each: growth flags with a
/// directory (its creatures are already grown), `--size` without `--snapshot`, `--frame` on
/// a run page or past the page's `frames` frames.
fn ignored_flags(args: &ViewArgs, target: &Target, frames: Option<usize>) -> Vec<String> {
    let mut warnings = Vec::new();
    if target.kind != Kind::Lsys {
        let mut flags = args.development.given();
        if args.seed.is_some() {
            flags.push("--seed");
        }
        if !flags.is_empty() {
            warnings.push(format!(
                "{} grow a creature from a grammar; {} is not an .lsys file: ignored",
                flags.join(", "),
                target.path.display()
            ));
        }
    }
    if args.size.is_some() && args.snapshot.is_none() {
        warnings.push("--size sets the size of a --snapshot picture: ignored".to_string());
    }
    if let Some(k) = args.frame {
        if target.kind == Kind::Run {
            warnings.push(format!(
                "--frame {k}: a run page has no frames (open an individual with ?gen=G&index=I \
                 in its address): ignored"
            ));
        } else if let Some(n) = frames {
            let n = n as i64;
            if n == 0 {
                warnings.push(format!("--frame {k}: the recording has no frames: ignored"));
            } else if k >= n || k < -n {
                warnings.push(format!(
                    "--frame {k}: there are {n} frames (0 to {}, or -{n} to -1): showing the {}",
                    n - 1,
                    if k >= n { "last" } else { "first" }
                ));
            }
        }
    }
    warnings
}

/// A function that develops a run's individual `(generation, index)`.
fn developer_for<G: Genome + 'static>(dir: PathBuf) -> Developer {
    Box::new(move |generation, index| {
        // Read-only: the viewer never changes a run's files.
        let run = Run::<G>::open_read_only(&dir).map_err(|e| e.to_string())?;
        let population = run.population(generation).map_err(|e| e.to_string())?;
        let individual = population.get(index as usize).ok_or_else(|| {
            format!(
                "generation {generation} has {} individual(s); there is no individual {index}",
                population.len()
            )
        })?;
        individual
            .genome
            .develop(&run.config().limits, individual.develop_seed)
            .map_err(|e| format!("the genome does not develop: {e}"))
    })
}

/// The browser to run: `--browser`, `$ONTOGENY_BROWSER`, or a Chromium on the PATH.
pub fn find_browser(given: Option<&Path>) -> Option<PathBuf> {
    if let Some(path) = given {
        return Some(path.to_path_buf());
    }
    if let Some(path) = std::env::var_os("ONTOGENY_BROWSER").filter(|p| !p.is_empty()) {
        return Some(PathBuf::from(path));
    }
    let dirs = std::env::var_os("PATH")?;
    [
        "chromium",
        "chromium-browser",
        "google-chrome",
        "google-chrome-stable",
    ]
    .iter()
    .flat_map(|name| std::env::split_paths(&dirs).map(move |d| d.join(name)))
    .find(|p| p.is_file())
}

/// Renders `url` with headless Chromium into `out`. Chromium runs with a fresh private profile
/// and writes its screenshot there; the picture is then put in place whole
/// ([`ontogeny::output`]), and a target that is not a regular file is refused before
/// Chromium starts.
fn snapshot(args: &ViewArgs, url: &str, out: &Path) -> anyhow::Result<()> {
    let browser = find_browser(args.browser.as_deref()).ok_or_else(|| {
        bad(
            "--snapshot needs Chromium: install it (e.g. apt-get install chromium), or name \
             a browser with --browser or $ONTOGENY_BROWSER",
        )
    })?;
    let out = std::path::absolute(out).with_context(|| format!("bad path {}", out.display()))?;
    if let Some(parent) = out.parent() {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("cannot create {}", parent.display()))?;
    }
    ontogeny::output::check_target(&out)?;
    // Removed, with everything Chromium put in it, when dropped.
    let scratch = tempfile::Builder::new()
        .prefix("ontogeny-view-")
        .tempdir()
        .context("cannot make a temporary directory for the browser")?;
    let profile = scratch.path().join("profile");
    let screenshot = scratch.path().join("snapshot.png");
    let (w, h) = args.size.unwrap_or(DEFAULT_SIZE);
    let output = Command::new(&browser)
        .args(chromium_flags())
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={w},{h}"))
        .arg(format!("--screenshot={}", screenshot.display()))
        .arg(url)
        .stdin(std::process::Stdio::null())
        .output()
        .with_context(|| format!("cannot run {}", browser.display()))?;
    if !screenshot.is_file() {
        anyhow::bail!(
            "{} did not write {} (exit status {}):\n{}",
            browser.display(),
            out.display(),
            output.status,
            String::from_utf8_lossy(&output.stderr)
        );
    }
    ontogeny::output::copy_into_place(&screenshot, &out)?;
    Ok(())
}

/// The flags `--snapshot` gives Chromium: headless, WebGL through SwiftShader (a CPU
/// renderer, so no GPU is needed), and virtual time so the page finishes loading and drawing
/// before the picture is taken.
pub fn chromium_flags() -> Vec<String> {
    [
        "--headless=new",
        "--no-sandbox",
        "--use-gl=angle",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--hide-scrollbars",
        "--no-first-run",
        "--no-default-browser-check",
        "--disable-extensions",
        "--virtual-time-budget=8000",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}
