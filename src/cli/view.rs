//! `ontogeny view`: a page served in the browser, or rendered to a PNG.

use std::path::PathBuf;

use clap::Args;
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, LSystem, Overrides};
use ontogeny::view::snapshot::{self, SnapshotError};
use ontogeny::view::{Developer, Kind, PageFlags, Server, Target, ignored_flags, run_developer};

use super::bad;

use super::derive::{DevelopmentArgs, derive_options};

/// The port `view` listens on when `--port` is not given (and not snapshotting).
const DEFAULT_PORT: u16 = 8750;

/// Show a creature in the browser: an `.lsys` file growing (reloaded when saved), a
/// recording playing, or a run's fitness and individuals; or render it to a PNG.
#[derive(Args)]
pub struct ViewArgs {
    /// An `.lsys` file, or a directory written by `grow --out`, `eval --record` (or `replay`),
    /// `evolve` or `compare`.
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
    #[arg(long, value_parser = snapshot::parse_size)]
    size: Option<(u32, u32)>,
    /// The browser `--snapshot` runs (default: $ONTOGENY_BROWSER, else the first of chromium,
    /// chromium-browser, google-chrome on the PATH).
    #[arg(long)]
    browser: Option<PathBuf>,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// For an `.lsys` file: a creature with more parts than this is invalid (default 200;
    /// raise it for plants of thousands of parts).
    #[arg(long, value_parser = super::parse_part_count)]
    max_parts: Option<usize>,
    /// For a run with `[[task.habitats]]`: show its individuals developed in the habitat named
    /// NAME, and play their walks in its world (its first trial) [default: the first habitat].
    #[arg(long, value_name = "NAME")]
    habitat: Option<String>,
}

/// Serves the page (or renders it with `--snapshot`).
pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    let max_parts = args
        .max_parts
        .unwrap_or(ontogeny::develop::BuildOptions::default().max_parts);
    let target = Target::classify(&args.path).map_err(|e| bad(e.to_string()))?;
    let options = derive_options(&args.development, DEFAULT_MAX_MODULES);
    // A page that cannot be made at all is bad input; a grammar with an error is shown in the
    // page (watch mode lets the user fix it), and reported here too.
    let mut grammar_error = None;
    let mut developer = None;
    // How many frames the page has (None: not known, or a run page, which has none).
    let mut frames = None;
    match target.kind {
        Kind::Lsys => {
            // --dt and --timing are refused for a discrete file, as by every verb that grows.
            let overrides = args.development.defines.overrides(options.seed);
            let seeded = Overrides {
                seed: options.seed,
                ..Overrides::default()
            };
            if let Ok(lsys) = LSystem::from_path_with(&target.path, &seeded) {
                ontogeny::lsystem::print::check_continuous_options(&lsys, &options)?;
                // A grammar that reads but not with the --define values given: the flags
                // are wrong, not the file.
                LSystem::from_path_with(&target.path, &overrides)?;
            }
            match LSystem::from_path_with(&target.path, &overrides).and_then(|lsys| {
                ontogeny::develop::grow(
                    &lsys,
                    &options,
                    args.development.steps,
                    &ontogeny::develop::BuildOptions {
                        max_parts,
                        for_picture: true,
                        ..Default::default()
                    },
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
                tell!(
                    "note: {}: {reason}; the page shows the creature as built",
                    target.path.display()
                );
            }
        }
        Kind::Comparison => {
            ontogeny::view::comparison_data(&target.path).map_err(|e| bad(e.to_string()))?;
        }
        Kind::Run => {
            let data = ontogeny::view::run_data(&target.path).map_err(|e| bad(e.to_string()))?;
            let encoding = data["encoding"].as_str().unwrap_or_default().to_string();
            let dir = target.path.clone();
            let habitat = match &args.habitat {
                Some(name) => {
                    let task =
                        ontogeny::run::store::RunStore::open_read_only(&dir.join("run.sqlite"))
                            .and_then(|store| store.run())
                            .ok()
                            .and_then(|run| run.task_spec())
                            .ok_or_else(|| {
                                bad(format!("{}: cannot read the run's task", dir.display()))
                            })?;
                    let index = task
                        .habitat_named(name)
                        .map_err(|e| bad(format!("{}: {e}", dir.display())))?;
                    Some((index, name.clone()))
                }
                None => None,
            };
            let developer_of: anyhow::Result<Developer> = with_genome!(
                encoding.as_str(),
                G => Ok(run_developer::<G>(dir, habitat)),
                |other| Err(bad(format!(
                    "{}: unknown encoding '{other}'",
                    target.path.display()
                )))
            );
            developer = Some(developer_of?);
        }
    }
    let mut growth = args.development.given();
    if args.max_parts.is_some() {
        growth.push("--max-parts");
    }
    let flags = PageFlags {
        growth,
        size: args.size.is_some(),
        snapshot: args.snapshot.is_some(),
        frame: args.frame,
        habitat: args.habitat.clone(),
    };
    for warning in ignored_flags(&flags, &target, frames) {
        tell!("warning: {warning}");
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
    .map_err(|e| bad(e.to_string()))?
    .with_max_parts(max_parts);
    let mut query = Vec::new();
    if let Some(f) = args.frame {
        query.push(format!("frame={f}"));
    }
    // The page's URL carries the defines' values, as its sliders set them.
    if target.kind == Kind::Lsys {
        query.extend(ontogeny::view::define_query(
            &args.development.defines.defines,
        ));
    }
    if let Some(out) = &args.snapshot {
        query.push("still=1".to_string());
        let url = format!("{}?{}", server.url(), query.join("&"));
        std::thread::spawn(move || server.run());
        let size = args.size.unwrap_or(snapshot::DEFAULT_SIZE);
        snapshot::snapshot(args.browser.as_deref(), size, &url, out).map_err(|e| match e {
            SnapshotError::NoBrowser => bad(e.to_string()),
            SnapshotError::Output(e) => anyhow::Error::new(e),
            e => anyhow::Error::new(e),
        })?;
        tell!("{}", ontogeny::output::wrote(&[out]));
        if let Some(d) = grammar_error {
            // The picture shows the error; the exit code says it too.
            return Err(anyhow::Error::new(d));
        }
        return Ok(());
    }
    if let Some(d) = &grammar_error {
        tell!("{d}");
        tell!("(the page shows this error until the file is fixed and saved)");
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
