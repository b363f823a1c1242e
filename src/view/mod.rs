//! The browser viewer: a small local web server and the static page it serves.
//!
//! `ontogeny view PATH` opens one of four kinds of page, told apart by what PATH is
//! ([`Target::classify`]):
//!
//! - a `.lsys` file ([`Kind::Lsys`]): the creature grown at every frame, with a
//!   developmental-time slider, its brain, and the module string of the current frame; the file
//!   is read again whenever it changes on disk (watch mode), and a syntax error is shown in the
//!   page with its line and column;
//! - a `grow --out` directory ([`Kind::Growth`]): the same page over its `frames.jsonl`;
//! - a recording directory ([`Kind::Recording`], `eval --record`): the behaviour, played;
//! - a run directory ([`Kind::Run`]): the fitness plot, the generations, and any individual
//!   opened in 3D.
//!
//! What this room owns: classifying PATH, turning each kind into the JSON the page reads, and
//! serving it with the page and its vendored JavaScript (three.js, see `vendor/three/LICENSE` at the repository root).
//! What it does not own: developing a run's genomes (the command line passes a function that
//! does, as it alone knows every encoding), nor driving a browser.

mod comparison;
mod open;
pub mod scene;
mod server;
pub mod snapshot;

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use crate::develop::{BuildOptions, build_frame};
use crate::lang::{Diagnostic, FileKind};
use crate::lsystem::{DefineOverride, DeriveOptions, LSystem, Overrides};

pub use comparison::{COMPARISON_PLOTS, comparison_data};
pub use open::{Developer, PageFlags, ignored_flags, run_developer};
pub use server::{Server, ServerError};

/// The version of three.js vendored in `vendor/three/`.
pub const THREE_VERSION: &str = "0.181.0";

/// What kind of page a path opens.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// An L-system file: grown here, and grown again when it changes.
    Lsys,
    /// A directory written by `ontogeny grow --out` (`frames.jsonl`).
    Growth,
    /// A directory written by `ontogeny eval --record` (`recording.json`).
    Recording,
    /// A run directory written by `ontogeny evolve` (`config.toml` and `run.sqlite`).
    Run,
    /// A comparison directory written by `ontogeny compare` (`compare.toml`).
    Comparison,
}

impl Kind {
    /// The kind's name as the page and `--json` output spell it.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Lsys => "lsys",
            Kind::Growth => "growth",
            Kind::Recording => "recording",
            Kind::Run => "run",
            Kind::Comparison => "comparison",
        }
    }
}

/// Errors of the viewer.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// PATH is none of the five kinds.
    #[error("{0}")]
    NotViewable(String),
    /// A file of the directory cannot be read or makes no sense.
    #[error("{0}")]
    BadFile(String),
    /// A request for data that does not say what it wants (a query number missing or out of
    /// range).
    #[error("{0}")]
    BadRequest(String),
    /// A request for data that is not there (an individual past the end of its generation).
    #[error("{0}")]
    NotFound(String),
    /// The server is doing as much of this as it does at once (evaluating walks): try again.
    #[error("{0}")]
    Busy(String),
}

/// A path and the kind of page it opens.
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    /// What it is.
    pub kind: Kind,
    /// The file or directory.
    pub path: PathBuf,
}

impl Target {
    /// Tells what `path` is: a `.lsys` file, or a grow, recording, run or comparison directory.
    pub fn classify(path: &Path) -> Result<Target, ViewError> {
        let shown = path.display();
        let target = |kind| {
            Ok(Target {
                kind,
                path: path.to_path_buf(),
            })
        };
        if path.is_file() {
            if path.extension().is_some_and(|e| e == "lsys") {
                return target(Kind::Lsys);
            }
            // A file view cannot show is told what it is and which command takes it.
            let kind = crate::input::read(path).map(|bytes| FileKind::of(path, &bytes));
            if let Some(kind) = kind.ok().filter(|k| *k != FileKind::Grammar) {
                return Err(ViewError::NotViewable(format!(
                    "{shown} is {}, not an .lsys file: {}",
                    kind.describe(),
                    kind.advice(path)
                )));
            }
            return Err(ViewError::NotViewable(format!(
                "{shown}: not an .lsys file (view shows an .lsys file, or a directory written \
                 by grow --out, eval --record or evolve)"
            )));
        }
        if path.exists() && !path.is_dir() {
            // A device, a pipe or a socket: nothing view can show, and not to be read.
            return Err(ViewError::NotViewable(format!(
                "{shown}: not a regular file or a directory (view shows an .lsys file, or a \
                 directory written by grow --out, eval --record or evolve)"
            )));
        }
        if !path.is_dir() {
            return Err(ViewError::NotViewable(format!(
                "{shown}: no such file or directory"
            )));
        }
        if comparison::is_comparison(path) {
            target(Kind::Comparison)
        } else if path.join("config.toml").is_file() && path.join("run.sqlite").is_file() {
            target(Kind::Run)
        } else if path.join("recording.json").is_file() {
            target(Kind::Recording)
        } else if path.join("frames.jsonl").is_file() {
            target(Kind::Growth)
        } else {
            Err(ViewError::NotViewable(format!(
                "{shown}: not a directory view can show (it has no frames.jsonl from grow \
                 --out, no recording.json from eval --record, no config.toml and \
                 run.sqlite from evolve, and no compare.toml from compare)"
            )))
        }
    }

    /// A fingerprint of the files behind the page (modification time and length): it changes
    /// when they do, and the page polls it to reload (watch mode). A run's store is in WAL
    /// mode, so its write-ahead log counts too.
    pub fn version(&self) -> String {
        match self.kind {
            Kind::Lsys => fingerprint(&self.path),
            Kind::Growth => fingerprint(&self.path.join("frames.jsonl")),
            Kind::Recording => fingerprint(&self.path.join("recording.json")),
            Kind::Run => format!(
                "{}/{}",
                fingerprint(&self.path.join("run.sqlite")),
                fingerprint(&self.path.join("run.sqlite-wal"))
            ),
            Kind::Comparison => fingerprint(&self.path.join("report.md")),
        }
    }
}

/// A file's modification time (ns) and length, or `missing`.
fn fingerprint(file: &Path) -> String {
    match std::fs::metadata(file) {
        Ok(m) => {
            let modified = m
                .modified()
                .ok()
                .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                .map(|d| d.as_nanos())
                .unwrap_or(0);
            format!("{modified}-{}", m.len())
        }
        Err(_) => "missing".to_string(),
    }
}

/// The JSON of one frame of growth: step, time, module string (when known) and creature.
fn frame_json(
    step: u64,
    t: f64,
    string: Option<String>,
    creature: &crate::creature::Creature,
) -> Value {
    json!({ "step": step, "t": t, "string": string, "creature": creature })
}

/// A diagnostic as the page shows it: the message, and the line and column when it has them.
pub fn diagnostic_json(d: &Diagnostic) -> Value {
    let location = d.location.as_ref().map(|l| {
        json!({
            "file": l.file, "line": l.line, "column": l.column,
            "line_text": l.line_text, "width": l.width,
        })
    });
    json!({ "message": d.message, "location": location, "text": d.to_string() })
}

/// A grammar's finding as the page shows it: as [`diagnostic_json`], its `text` headed
/// `warning:`.
fn finding_json(d: &Diagnostic) -> Value {
    let mut value = diagnostic_json(d);
    value["text"] = json!(d.warning());
    value
}

/// Grows an `.lsys` file and returns the page's data: `{"kind": "lsys", "file", "findings":
/// [...], "problems": [...], "frames": [{"step", "t", "string", "creature"}]}`, or `{"kind":
/// "lsys", "file", "error": {...}}` when the file does not parse or derive (the page shows it
/// with its line and column). `findings` are the grammar's ([`LSystem::findings`], shaped as
/// [`diagnostic_json`], the text headed `warning:`); `problems` are the builder's problems of
/// every frame, each once, with the number of frames it came up in. A creature of more than
/// `max_parts` parts is invalid; the page is a picture, so parts that overlap and a body in
/// pieces are warnings.
pub fn lsys_data(
    path: &Path,
    options: &DeriveOptions,
    steps: Option<u64>,
    max_parts: usize,
) -> Value {
    let file = path.display().to_string();
    let grown = LSystem::from_path_with(path, &seeded(options, &[])).and_then(|lsys| {
        let (frames, _) = grow_with_strings(&lsys, options, steps, max_parts)?;
        Ok((lsys.findings(), frames))
    });
    match grown {
        Ok((findings, frames)) => grown_json(&file, &findings, frames),
        Err(d) => json!({ "kind": "lsys", "file": file, "error": diagnostic_json(&d) }),
    }
}

/// `defines` and the seed of `options` in place of a grammar's (its `seed:` as edited to the
/// `--grammar-seed` given).
fn seeded(options: &DeriveOptions, defines: &[DefineOverride]) -> Overrides {
    Overrides {
        defines: defines.to_vec(),
        seed: options.seed,
    }
}

/// The prefix of a define's key in the page's query string: `define.GROWTH=1.5`.
pub const DEFINE_KEY: &str = "define.";

/// The query string's pairs that carry `defines` (`define.NAME=VALUE`, see [`DEFINE_KEY`]).
pub fn define_query(defines: &[DefineOverride]) -> Vec<String> {
    defines
        .iter()
        .map(|d| format!("{DEFINE_KEY}{}={}", d.name, d.value))
        .collect()
}

/// The defines a query string sets (`define.NAME=VALUE` pairs; other keys are not read); a
/// value that is not a number is a bad request.
pub fn defines_of_query(query: &str) -> Result<Vec<DefineOverride>, ViewError> {
    query
        .split('&')
        .filter_map(|pair| pair.strip_prefix(DEFINE_KEY))
        .map(|pair| {
            let pair = percent_decoded(pair);
            pair.parse::<DefineOverride>()
                .map_err(|e| ViewError::BadRequest(format!("{DEFINE_KEY}{pair}: {e}")))
        })
        .collect()
}

/// `text` with its `%XX` escapes decoded (a define's name and number need no others).
fn percent_decoded(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(byte)) => {
                out.push(byte);
                i += 3;
            }
            (byte, _) => {
                out.push(byte);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Like [`lsys_data`], with `defines` in place of the values of the grammar's defines, and
/// the defines as sliders (`"defines": [{"name", "value", "min", "max", "step", "note",
/// "set"}]`, ranges from the file's own values, see [`LSystem::sliders`]; `set`: named in
/// `defines`). A define the grammar does not have is a bad request that lists the ones it has.
pub fn lsys_data_with(
    path: &Path,
    options: &DeriveOptions,
    steps: Option<u64>,
    max_parts: usize,
    defines: &[DefineOverride],
) -> Result<Value, ViewError> {
    let Ok(plain) = LSystem::from_path_with(path, &seeded(options, &[])) else {
        return Ok(lsys_data(path, options, steps, max_parts));
    };
    if let Some(unknown) = defines
        .iter()
        .find(|d| !plain.constants().any(|(name, _)| name == d.name))
    {
        let error = crate::lsystem::defines::unknown_define(
            plain.source(),
            &unknown.name,
            &plain.file().defines,
        );
        return Err(ViewError::BadRequest(error.message));
    }
    let file = path.display().to_string();
    let grown = LSystem::from_path_with(path, &seeded(options, defines)).and_then(|lsys| {
        let (frames, values) = grow_with_strings(&lsys, options, steps, max_parts)?;
        Ok((lsys.findings(), frames, values))
    });
    let (mut data, grown) = match grown {
        Ok((findings, frames, values)) => (grown_json(&file, &findings, frames), values),
        Err(d) => (
            json!({ "kind": "lsys", "file": file, "error": diagnostic_json(&d) }),
            Vec::new(),
        ),
    };
    let sliders: Vec<Value> = plain
        .sliders()
        .into_iter()
        .map(|mut slider| {
            let given = crate::lsystem::defines::override_of(defines, &slider.name);
            if let Some(&(_, v)) = grown.iter().find(|(n, _)| *n == slider.name) {
                slider.value = v;
            } else if let Some(v) = given {
                slider.value = v;
            }
            slider.min = slider.min.min(slider.value);
            slider.max = slider.max.max(slider.value);
            let mut value = json!(slider);
            value["set"] = json!(given.is_some());
            value
        })
        .collect();
    data["defines"] = json!(sliders);
    Ok(data)
}

/// The values of a grammar's defines, by name, in file order.
type DefineValues = Vec<(String, f64)>;

/// The builder's problems over all `frames` (frame JSON, as [`frame_json`] makes), each once
/// in the order they first arose, with the number of frames it came up in and the first
/// frame's time: `{"severity", "message", "module", "frames", "t", "text"}`, `text` as the
/// page shows it (`warning: ']' with nothing to pop: ignored []] (at 40 frames, from t =
/// 1)`).
fn problems_json(frames: &[Value]) -> Vec<Value> {
    use crate::creature::repeats::counted;
    let key = |p: &Value| [&p["severity"], &p["message"], &p["module"]].map(Value::to_string);
    let mut first = std::collections::HashMap::new();
    let each = frames.iter().flat_map(|frame| {
        let problems = frame["creature"]["problems"]
            .as_array()
            .into_iter()
            .flatten();
        // A problem said several times in one frame counts once for it.
        counted(problems.map(|p| {
            first.entry(key(p)).or_insert_with(|| p.clone());
            key(p)
        }))
        .into_iter()
        .map(|(k, _)| k)
        .collect::<Vec<_>>()
    });
    let counts = counted(each.collect::<Vec<_>>());
    counts
        .into_iter()
        .map(|(k, n)| (first[&k].clone(), n))
        .map(|(p, n)| {
            let mut text = format!(
                "{}: {}",
                p["severity"].as_str().unwrap_or("warning"),
                p["message"].as_str().unwrap_or_default()
            );
            if let Some(module) = p["module"].as_str() {
                text.push_str(&format!(" [{module}]"));
            }
            let at = match (n, p["t"].as_f64()) {
                (1, Some(t)) => format!(" at t = {t}"),
                (1, None) => String::new(),
                (n, Some(t)) => format!(" (at {n} frames, from t = {t})"),
                (n, None) => format!(" (at {n} frames)"),
            };
            text.push_str(&at);
            json!({
                "severity": p["severity"], "message": p["message"], "module": p["module"],
                "frames": n, "t": p["t"], "text": text,
            })
        })
        .collect()
}

/// The page's data for a grown `.lsys` file: its `findings` ([`LSystem::findings`], shaped as
/// [`finding_json`]), the builder's `problems` over all frames ([`problems_json`]) and the
/// `frames`.
fn grown_json(file: &str, findings: &[Diagnostic], frames: Vec<Value>) -> Value {
    json!({
        "kind": "lsys",
        "file": file,
        "findings": findings.iter().map(finding_json).collect::<Vec<_>>(),
        "problems": problems_json(&frames),
        "frames": frames,
    })
}

/// Like [`crate::develop::grow`], keeping each frame's module string (as derived, before the
/// interpretation rules); with the values of the grammar's defines.
fn grow_with_strings(
    lsys: &LSystem,
    options: &DeriveOptions,
    steps: Option<u64>,
    max_parts: usize,
) -> Result<(Vec<Value>, DefineValues), Diagnostic> {
    // The page holds every frame: refused at once when there are too many.
    crate::develop::kept_frame_plan(lsys, options, steps)?;
    let build_options = BuildOptions {
        max_parts,
        for_picture: true,
        ..BuildOptions::default()
    }
    .with_headers(lsys);
    let mut frames = Vec::new();
    lsys.for_each_frame(options, steps, |frame| {
        let creature = build_frame(lsys, &frame, options, &build_options)?;
        frames.push(frame_json(
            frame.step,
            frame.t,
            Some(frame.string.display(lsys.symbols())),
            &creature,
        ));
        Ok::<(), Diagnostic>(())
    })?;
    let values = lsys.constants().map(|(n, v)| (n.to_string(), v)).collect();
    Ok((frames, values))
}

/// Reads a `grow --out` directory's `frames.jsonl` into the page's data (the same shape as
/// [`lsys_data`]; the module strings are not stored there, so `string` is null).
pub fn growth_data(dir: &Path) -> Result<Value, ViewError> {
    let path = dir.join("frames.jsonl");
    let text = crate::input::read_to_string(&path)
        .map_err(|e| ViewError::BadFile(format!("cannot read {}: {e}", path.display())))?;
    let mut frames = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        if frames.len() as u64 == crate::develop::MAX_KEPT_FRAMES {
            return Err(ViewError::BadFile(format!(
                "{}: more than {} frames, the most the page holds",
                path.display(),
                crate::develop::MAX_KEPT_FRAMES
            )));
        }
        let frame: crate::develop::GrowthFrame = serde_json::from_str(line).map_err(|e| {
            ViewError::BadFile(format!(
                "{}:{}: not a frame of growth: {e}",
                path.display(),
                i + 1
            ))
        })?;
        frames.push(frame_json(frame.step, frame.t, None, &frame.creature));
    }
    if frames.is_empty() {
        return Err(ViewError::BadFile(format!("{}: no frames", path.display())));
    }
    Ok(json!({ "kind": "growth", "file": dir.display().to_string(), "frames": frames }))
}

/// Reads a recording directory's `recording.json` ([`crate::task::Recording`], written by
/// `eval --record`) into the page's data: the recording's keys, with `kind`, `file` and, for a
/// recording without samples (an evaluation refused before simulating), `no_frames`: why
/// nothing was recorded ([`no_samples_reason`]); the page then shows the creature as built.
pub fn recording_data(dir: &Path) -> Result<Value, ViewError> {
    let path = dir.join("recording.json");
    let text = crate::input::read_to_string(&path)
        .map_err(|e| ViewError::BadFile(format!("cannot read {}: {e}", path.display())))?;
    let recording: crate::task::Recording = serde_json::from_str(&text).map_err(|e| {
        let what = if e.is_syntax() || e.is_eof() {
            "not JSON"
        } else {
            "not a recording"
        };
        ViewError::BadFile(format!("{}: {what}: {e}", path.display()))
    })?;
    recording_value(&recording, &dir.display().to_string())
        .map_err(|e| ViewError::BadFile(format!("{}: {e}", path.display())))
}

/// The page's data for `recording`, titled `file`: the recording's keys, with `kind`
/// (`recording`), `file`, the geometry of a world that is not flat (`scene`, see
/// [`scene::scene`]), for a body that grows during the recording `body` (the body at the last
/// sample, every part that appeared, in the creature's first axes: the page makes a mesh for
/// each and shows those each sample poses, at the sizes its `growth` gives them) and, for a
/// recording without samples, `no_frames` (see [`recording_data`]); or why its samples do not
/// fit its creature or its growth.
fn recording_value(recording: &crate::task::Recording, file: &str) -> Result<Value, String> {
    recording.check_growth()?;
    let mut bodies = recording.bodies();
    for (i, sample) in recording.samples.iter().enumerate() {
        let parts = bodies.at(i).parts.len();
        if sample.parts.len() != parts {
            return Err(format!(
                "frame {i} has {} part poses for a creature of {parts} parts",
                sample.parts.len(),
            ));
        }
    }
    // Through the recording's own text (not `serde_json::to_value`, which would widen its f32
    // poses back to f64 digits).
    let written = serde_json::to_string(recording).map_err(|e| e.to_string())?;
    let mut value: Value = serde_json::from_str(&written).map_err(|e| e.to_string())?;
    value["kind"] = json!("recording");
    value["file"] = json!(file);
    if !recording.world.is_flat() {
        value["scene"] = scene::scene(&recording.world);
    }
    if let Some(reason) = no_samples_reason(recording) {
        value["no_frames"] = json!(reason);
    }
    if recording.grows() {
        let last = recording.samples.len() - 1;
        value["body"] = serde_json::to_value(bodies.at(last)).map_err(|e| e.to_string())?;
    }
    Ok(value)
}

/// Why a recording has no samples, or `None` when it has some: the evaluation's status and
/// message when the file holds them (files written before they were recorded do not).
pub fn no_samples_reason(recording: &crate::task::Recording) -> Option<String> {
    if !recording.samples.is_empty() {
        return None;
    }
    Some(
        match (recording.status_name(), recording.message.as_deref()) {
            (Some(s), Some(m)) => format!("no frames recorded: {s}: {m}"),
            (Some(s), None) => format!("no frames recorded: {s}"),
            (None, Some(m)) => format!("no frames recorded: {m}"),
            (None, None) => {
                "no frames recorded (the evaluation was refused before simulating)".to_string()
            }
        },
    )
}

/// Reads a run directory's store into the page's data: `{"kind": "run", "file", "encoding",
/// "task", "fitness" (what the fitness measures and its unit, as `fitness.svg`'s y axis says,
/// `"fitness: distance (m)"`), "generations": [{"index", "best", "mean", "median", "sd",
/// "valid_fraction", "evaluations", "best_fine" (the best re-walked at the fine reference, or
/// null)}]}`; for a run with habitats or trials, each generation also has "spread_low" and
/// "spread_high", the lowest and highest fitness of its best's walks
/// ([`crate::run::spread`]); "algorithm": `null` for the generational GA, else
/// `{"name": "steady-state", "in_flight": W}` (each stored generation then a block of births).
pub fn run_data(dir: &Path) -> Result<Value, ViewError> {
    let store = crate::run::store::RunStore::open_read_only(&dir.join("run.sqlite"))
        .map_err(|e| ViewError::BadFile(e.to_string()))?;
    let run = store.run().map_err(|e| ViewError::BadFile(e.to_string()))?;
    let spec = run.task_spec();
    // The best's walks are in its record: read only for a run that has some.
    let spreads = match &spec {
        Some(spec) if !spec.is_plain() => crate::run::spread::stored_spreads(&store)
            .map_err(|e| ViewError::BadFile(e.to_string()))?,
        _ => Vec::new(),
    };
    let generations: Vec<Value> = store
        .generations()
        .map_err(|e| ViewError::BadFile(e.to_string()))?
        .iter()
        .map(|g| {
            let mut value = json!({
                "index": g.index, "best": finite(g.best), "mean": finite(g.mean),
                "median": finite(g.median), "sd": finite(g.sd),
                "valid_fraction": finite(g.valid_fraction), "evaluations": g.evaluations,
                "best_fine": g.best_fine.as_ref().map_or(Value::Null, |f| finite(f.fitness)),
            });
            if !spreads.is_empty() {
                let spread = spreads.iter().find(|s| s.generation == g.index);
                value["spread_low"] = spread.map_or(Value::Null, |s| finite(s.low));
                value["spread_high"] = spread.map_or(Value::Null, |s| finite(s.high));
            }
            value
        })
        .collect();
    Ok(json!({
        "kind": "run",
        "file": dir.display().to_string(),
        "encoding": run.encoding,
        "task": run.task,
        "seed": run.seed,
        "algorithm": algorithm_data(&run.config),
        "fitness": spec.map(|spec| format!("fitness: {}", spec.fitness_measure())),
        "generations": generations,
    }))
}

/// The run's algorithm as [`run_data`] gives it: `null` for the generational GA (also when its
/// settings cannot be read), else its name and births in flight.
fn algorithm_data(config: &str) -> Value {
    let settings: Option<crate::evolve::settings::GaSettings> =
        crate::run::config::parse_table(config)
            .ok()
            .and_then(|table| table.get("ga")?.clone().try_into().ok());
    match settings {
        Some(ga) if !ga.algorithm.is_generational() => {
            let in_flight = ga
                .in_flight
                .unwrap_or(crate::evolve::settings::DEFAULT_IN_FLIGHT);
            json!({ "name": ga.algorithm.name(), "in_flight": in_flight })
        }
        _ => Value::Null,
    }
}

/// A generation's individuals, best first in the GA's order ([`crate::evolve::ga::ranking`],
/// the ranks of `ontogeny replay --rank`): `[{"rank", "index", "fitness", "status",
/// "operator", "parts", "joints", "neurons"}]`.
pub fn run_generation_data(dir: &Path, generation: u32) -> Result<Value, ViewError> {
    let store = crate::run::store::RunStore::open_read_only(&dir.join("run.sqlite"))
        .map_err(|e| ViewError::BadFile(e.to_string()))?;
    // In index order, so their ranks are those of the GA and of `replay --rank`.
    let individuals = store
        .individuals(generation)
        .map_err(|e| ViewError::BadFile(e.to_string()))?;
    let rows: Vec<Value> = crate::evolve::ga::ranking_by(&individuals, |i| i.fitness)
        .into_iter()
        .map(|k| &individuals[k])
        .enumerate()
        .map(|(rank, i)| {
            json!({
                "rank": rank + 1, "index": i.index, "fitness": finite(i.fitness),
                "status": i.status, "operator": i.operator,
                "parts": i.parts, "joints": i.joints, "neurons": i.neurons,
            })
        })
        .collect();
    Ok(json!({ "generation": generation, "individuals": rows }))
}

/// How many individuals a run's generation `generation` has (0 for a generation not stored).
pub fn run_population_size(dir: &Path, generation: u32) -> Result<usize, ViewError> {
    let store = crate::run::store::RunStore::open_read_only(&dir.join("run.sqlite"))
        .map_err(|e| ViewError::BadFile(e.to_string()))?;
    Ok(store
        .individuals(generation)
        .map_err(|e| ViewError::BadFile(e.to_string()))?
        .len())
}

/// JSON has no NaN or infinity: those become null.
fn finite(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

/// The page's data for one creature shown alone (a run's individual): one frame.
pub fn creature_data(title: &str, creature: &crate::creature::Creature) -> Value {
    json!({ "kind": "creature", "file": title, "frames": [frame_json(0, 0.0, None, creature)] })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh private directory for test `name`, removed when the first is dropped, and its
    /// path.
    fn scratch(name: &str) -> (tempfile::TempDir, std::path::PathBuf) {
        let dir = tempfile::Builder::new()
            .prefix(&format!("ontogeny-view-unit-{name}-"))
            .tempdir()
            .unwrap();
        let path = dir.path().to_path_buf();
        (dir, path)
    }

    #[test]
    fn paths_are_classified_by_what_they_hold() {
        let (_scratch, dir) = scratch("classify");
        let lsys = dir.join("a.lsys");
        std::fs::write(&lsys, "axiom: forward(1)\n").unwrap();
        assert_eq!(Target::classify(&lsys).unwrap().kind, Kind::Lsys);
        let grown = dir.join("grown");
        std::fs::create_dir_all(&grown).unwrap();
        std::fs::write(grown.join("frames.jsonl"), "").unwrap();
        assert_eq!(Target::classify(&grown).unwrap().kind, Kind::Growth);
        // A recording made by `replay` inside a run directory is a recording.
        std::fs::write(grown.join("recording.json"), "{}").unwrap();
        assert_eq!(Target::classify(&grown).unwrap().kind, Kind::Recording);
        std::fs::write(grown.join("config.toml"), "").unwrap();
        assert_eq!(Target::classify(&grown).unwrap().kind, Kind::Recording);
        std::fs::write(grown.join("run.sqlite"), "").unwrap();
        assert_eq!(Target::classify(&grown).unwrap().kind, Kind::Run);
        let other = dir.join("notes.txt");
        std::fs::write(&other, "").unwrap();
        for bad in [other, dir.join("missing"), dir.clone()] {
            assert!(matches!(
                Target::classify(&bad),
                Err(ViewError::NotViewable(_))
            ));
        }
    }

    #[test]
    fn a_runs_version_changes_with_its_write_ahead_log() {
        let (_scratch, dir) = scratch("version");
        std::fs::write(dir.join("config.toml"), "").unwrap();
        std::fs::write(dir.join("run.sqlite"), "db").unwrap();
        let run = Target::classify(&dir).unwrap();
        let before = run.version();
        assert!(before.ends_with("/missing"), "{before}");
        std::fs::write(dir.join("run.sqlite-wal"), "one generation").unwrap();
        let during = run.version();
        assert_ne!(during, before);
        std::fs::write(dir.join("run.sqlite-wal"), "two generations").unwrap();
        assert_ne!(run.version(), during);
    }

    #[test]
    fn an_lsys_page_has_one_frame_per_step_with_its_string() {
        let (_scratch, dir) = scratch("lsys");
        let file = dir.join("two.lsys");
        std::fs::write(
            &file,
            "axiom: A\nderivation length: 2\nA --> forward(1) B\nB --> forward(0.5)\n",
        )
        .unwrap();
        let data = lsys_data(&file, &DeriveOptions::default(), None, 200);
        let frames = data["frames"].as_array().unwrap();
        let strings: Vec<&str> = frames
            .iter()
            .map(|f| f["string"].as_str().unwrap())
            .collect();
        assert_eq!(strings, ["A", "forward(1) B", "forward(1) forward(0.5)"]);
        let lengths: Vec<f64> = frames[2]["creature"]["parts"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p["size"][0].as_f64().unwrap())
            .collect();
        assert_eq!(lengths, [1.0, 0.5]);
        // --steps overrides the file's derivation length.
        let one = lsys_data(&file, &DeriveOptions::default(), Some(1), 200);
        assert_eq!(one["frames"].as_array().unwrap().len(), 2);
    }

    #[test]
    fn an_lsys_error_carries_its_line_and_column() {
        let (_scratch, dir) = scratch("error");
        let file = dir.join("bad.lsys");
        std::fs::write(&file, "axiom: A\nA --> forward(1\n").unwrap();
        let data = lsys_data(&file, &DeriveOptions::default(), None, 200);
        assert!(data.get("frames").is_none());
        let error = &data["error"];
        assert_eq!(error["location"]["line"], 2);
        assert_eq!(error["location"]["column"], 16);
        assert_eq!(error["location"]["line_text"], "A --> forward(1");
        assert!(error["text"].as_str().unwrap().contains("bad.lsys:2:16"));
    }

    #[test]
    fn bad_directories_say_which_file_and_line() {
        let (_scratch, dir) = scratch("bad-dirs");
        std::fs::write(dir.join("frames.jsonl"), "{\"step\": 0}\n").unwrap();
        let err = growth_data(&dir).unwrap_err().to_string();
        assert!(
            err.contains("frames.jsonl:1: not a frame of growth"),
            "{err}"
        );
        std::fs::write(dir.join("frames.jsonl"), "\n").unwrap();
        assert!(
            growth_data(&dir)
                .unwrap_err()
                .to_string()
                .contains("no frames")
        );

        // A recording with one part pose for a creature of two parts.
        let creature = crate::develop::creature_from_commands("forward(1) forward(1)").unwrap();
        assert_eq!(creature.parts.len(), 2);
        let pose = json!([[0.5, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);
        std::fs::write(
            dir.join("recording.json"),
            json!({"creature": creature, "frames": [{"t": 0.0, "parts": [pose]}]}).to_string(),
        )
        .unwrap();
        let err = recording_data(&dir).unwrap_err().to_string();
        assert!(
            err.contains("frame 0 has 1 part poses for a creature of 2 parts"),
            "{err}"
        );
    }

    #[test]
    fn a_recording_without_frames_is_shown_with_the_reason() {
        let (_scratch, dir) = scratch("no-frames");
        let creature = crate::develop::creature_from_commands("forward(1) forward(1)").unwrap();
        // The viewer's data for `recording.json` holding `recording`.
        let shown = |recording: serde_json::Value| {
            std::fs::write(dir.join("recording.json"), recording.to_string()).unwrap();
            recording_data(&dir).unwrap()
        };
        let data = shown(
            json!({"creature": creature, "task": "walker", "status": "self-intersecting",
                   "message": "parts 0 and 1 interpenetrate", "frames": []}),
        );
        assert_eq!(data["frames"], json!([]));
        assert_eq!(
            data["no_frames"],
            "no frames recorded: self-intersecting: parts 0 and 1 interpenetrate"
        );
        // A file written before the status was recorded, without frames at all.
        let data = shown(json!({"creature": creature}));
        assert_eq!(data["frames"], json!([]));
        assert_eq!(
            data["no_frames"],
            "no frames recorded (the evaluation was refused before simulating)"
        );
        // With frames there is no reason.
        let pose = json!([[0.5, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);
        let data =
            shown(json!({"creature": creature, "frames": [{"t": 0.0, "parts": [pose, pose]}]}));
        assert!(data.get("no_frames").is_none());
    }

    #[test]
    fn a_recording_in_a_world_sends_its_geometry_and_a_flat_one_none() {
        let (_scratch, dir) = scratch("world");
        let creature = crate::develop::creature_from_commands("forward(1)").unwrap();
        let pose = json!([[0.5, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);
        let ball = json!([[2.0, 0.1, 0.0], [0.0, 0.0, 0.0, 1.0]]);
        let write = |world: Value| {
            let mut recording = json!({"creature": creature,
                "frames": [{"t": 0.0, "parts": [pose], "objects": [ball]}]});
            if !world.is_null() {
                recording["world"] = world;
            }
            std::fs::write(dir.join("recording.json"), recording.to_string()).unwrap();
            recording_data(&dir).unwrap()
        };
        let data = write(json!({"slope": {"degrees": 10},
            "objects": [{"shape": "ball", "size": 0.1, "mass": 1, "position": [2, 0.1, 0]}]}));
        assert_eq!(data["scene"]["ground"], "slope");
        assert_eq!(data["scene"]["objects"][0]["shape"], "ball");
        assert_eq!(data["frames"][0]["objects"], json!([ball]));
        assert!(write(Value::Null).get("scene").is_none());
    }
}
