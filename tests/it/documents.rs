//! The documents cannot drift. The building commands' reference page lists exactly the
//! commands of the one command table (`ontogeny::lang::commands`). Every `ontogeny` command
//! shown in the README and the guide is run against the built binary, in order, in a scratch
//! directory that holds the repository's `examples/`, `docs/` and `tests/fixtures/`.
//!
//! A command is a line of a fenced `sh` block that starts with `ontogeny` or `cargo run
//! --release --` (continued over lines ending in `\`; text after ` # ` is a comment). A block
//! is marked by an HTML comment on the line before its fence:
//! - `<!-- slow -->`: its commands take over a minute, or need the output of one that does;
//!   `documented_slow_commands_run_cut_down_to_seconds` runs them, in order, with their sizes
//!   cut down ([`CUT_DOWN`]): the same verbs, files, flags and sequence, in seconds;
//! - `<!-- fails -->`: its commands show a refusal; each must exit with code 2;
//! - `<!-- not run -->`: shown, never run (a cluster script, a command needing a display).
//!
//! `ontogeny view` without `--snapshot` serves until stopped: it is started, must say where it
//! serves within ten seconds, and is then stopped. `ontogeny view ... --snapshot` needs
//! Chromium: it runs only in [`browser`], ignored unless asked for.
//! The fitness figures the reference quotes for shipped files are evaluated again.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// How a documented block is run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mark {
    Quick,
    Slow,
    Fails,
    NotRun,
}

/// A documented command: where it is, how it is run, and its text (the program as `ontogeny`).
#[derive(Debug)]
struct Documented {
    place: String,
    mark: Mark,
    command: String,
}

/// The documents whose commands are run: the README and every page of the guide.
fn documents() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec![root.join("README.md")];
    if let Ok(entries) = std::fs::read_dir(root.join("docs/guide")) {
        let mut pages: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "md"))
            .collect();
        pages.sort();
        files.extend(pages);
    }
    files
}

/// The commands of one Markdown text, in order.
fn commands_in(name: &str, text: &str) -> Vec<Documented> {
    let mut found = Vec::new();
    let mut mark = Mark::Quick;
    let mut in_block: Option<Mark> = None;
    let mut pending = String::new();
    let mut start_line = 0;
    for (number, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if let Some(block_mark) = in_block {
            if trimmed.starts_with("```") {
                in_block = None;
                continue;
            }
            let content = match trimmed.find(" # ") {
                Some(at) if !pending.is_empty() || !trimmed.starts_with('#') => &trimmed[..at],
                _ => trimmed,
            };
            if pending.is_empty() {
                if content.starts_with('#') {
                    continue;
                }
                start_line = number + 1;
            }
            let (content, continued) = match content.strip_suffix('\\') {
                Some(head) => (head.trim_end(), true),
                None => (content, false),
            };
            pending.push_str(content);
            pending.push(' ');
            if continued {
                continue;
            }
            let command = std::mem::take(&mut pending);
            let command = command.trim();
            let program = if let Some(rest) = command.strip_prefix("cargo run --release -- ") {
                Some(rest)
            } else {
                command.strip_prefix("ontogeny ")
            };
            if let Some(rest) = program {
                found.push(Documented {
                    place: format!("{name}:{start_line}"),
                    mark: block_mark,
                    command: format!("ontogeny {rest}"),
                });
            }
            continue;
        }
        if trimmed.starts_with("```") {
            let info = trimmed.trim_start_matches('`').trim();
            if matches!(info, "sh" | "bash" | "shell" | "console") {
                in_block = Some(mark);
            }
            mark = Mark::Quick;
            continue;
        }
        if !trimmed.is_empty() {
            mark = match trimmed {
                "<!-- slow -->" => Mark::Slow,
                "<!-- fails -->" => Mark::Fails,
                "<!-- not run -->" => Mark::NotRun,
                _ => Mark::Quick,
            };
        }
    }
    found
}

/// Every documented command, in document order.
fn documented() -> Vec<Documented> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut all = Vec::new();
    for file in documents() {
        let text = std::fs::read_to_string(&file).unwrap();
        let name = file
            .strip_prefix(root)
            .unwrap_or(&file)
            .display()
            .to_string();
        all.extend(skip_other_blocks(&name, &text));
    }
    all
}

/// [`commands_in`], with the blocks of other languages skipped whole.
fn skip_other_blocks(name: &str, text: &str) -> Vec<Documented> {
    // Blank out fenced blocks that are not shell, so that a `ontogeny` line inside a text or
    // TOML block is not taken for a command.
    let mut kept = String::new();
    let mut other = false;
    for line in text.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with("```") {
            let info = trimmed.trim_start_matches('`').trim();
            if other {
                other = false;
                kept.push('\n');
                continue;
            }
            if !info.is_empty() && !matches!(info, "sh" | "bash" | "shell" | "console") {
                other = true;
                kept.push('\n');
                continue;
            }
        }
        if !other {
            kept.push_str(line);
        }
        kept.push('\n');
    }
    commands_in(name, &kept)
}

/// A scratch directory holding the repository's examples, documents and fixtures.
fn workplace(name: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("tests")).unwrap();
    for (from, to) in [
        ("examples", "examples"),
        ("docs", "docs"),
        ("tests/fixtures", "tests/fixtures"),
    ] {
        copy_tree(&root.join(from), &dir.join(to));
    }
    dir
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// Runs one command in `dir` through `sh` (pipes and redirections as documented), the program
/// `ontogeny` being the built binary. Returns the exit code and what it printed.
fn run(dir: &Path, d: &Documented) -> (Option<i32>, String) {
    let binary = env!("CARGO_BIN_EXE_ontogeny");
    let is_view = d.command.starts_with("ontogeny view ") && !d.command.contains("--snapshot");
    let script = format!("ontogeny() {{ '{binary}' \"$@\"; }}\n{}", d.command);
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(if is_view {
            format!("exec '{binary}' {}", &d.command["ontogeny ".len()..])
        } else {
            script
        })
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    if is_view {
        // A server: it must say where it serves, then it is stopped.
        let (sender, receiver) = std::sync::mpsc::channel();
        let stdout = child.stdout.take().unwrap();
        let stderr = child.stderr.take().unwrap();
        let to_stdout = sender.clone();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                let _ = to_stdout.send(line);
            }
        });
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                let _ = sender.send(line);
            }
        });
        let deadline = Instant::now() + Duration::from_secs(10);
        let mut said = String::new();
        while Instant::now() < deadline {
            if let Ok(line) = receiver.recv_timeout(Duration::from_millis(200)) {
                said.push_str(&line);
                said.push('\n');
                if line.contains("http://") {
                    let _ = child.kill();
                    let _ = child.wait();
                    return (Some(0), said);
                }
            }
            if let Ok(Some(status)) = child.try_wait() {
                return (status.code(), said);
            }
        }
        let _ = child.kill();
        let _ = child.wait();
        return (None, format!("{said}(no address within 10 s)"));
    }
    let output = child.wait_with_output().unwrap();
    let mut said = String::from_utf8_lossy(&output.stdout).into_owned();
    said.push_str(&String::from_utf8_lossy(&output.stderr));
    (output.status.code(), said)
}

/// Whether a documented command needs a browser: `ontogeny view ... --snapshot`.
fn needs_browser(d: &Documented) -> bool {
    d.command.starts_with("ontogeny view ") && d.command.contains("--snapshot")
}

/// Runs the documented commands that `chosen` picks, in order, in one scratch directory;
/// panics listing every command that did not do what its mark says.
fn run_documented(name: &str, chosen: impl Fn(&Documented) -> bool) {
    let dir = workplace(name);
    let mut failures = Vec::new();
    let mut count = 0;
    for d in documented() {
        if d.mark == Mark::NotRun || !chosen(&d) {
            continue;
        }
        count += 1;
        let (code, said) = run(&dir, &d);
        let expected = if d.mark == Mark::Fails { 2 } else { 0 };
        if code != Some(expected) {
            failures.push(format!(
                "{} `{}`: exit {code:?}, expected {expected}\n{}",
                d.place,
                d.command,
                said.lines().take(8).collect::<Vec<_>>().join("\n")
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(count > 0, "no documented commands found");
    assert!(
        failures.is_empty(),
        "{} of {count} documented commands failed:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

#[test]
fn documented_commands_run() {
    // A command that needs the output of a slow one is marked slow too.
    run_documented("doc-commands", |d| {
        matches!(d.mark, Mark::Quick | Mark::Fails) && !needs_browser(d)
    });
}

/// A rule of [`CUT_DOWN`]: the start of the commands it cuts down, the sizes it replaces
/// (from, to) and the flags it adds (flag, value).
type CutDown = (
    &'static str,
    &'static [(&'static str, &'static str)],
    &'static [(&'static str, &'static str)],
);

/// How the slow commands are cut down to seconds: a command that starts with the first text
/// has each size of the second that it gives replaced, and gets each flag of the third that it
/// does not give already. Walks of 0.2 s, populations of 4 and small budgets; the generations
/// are kept, so that resuming, extending and replaying a generation run as documented.
const CUT_DOWN: &[CutDown] = &[
    (
        "ontogeny evolve --config ",
        &[("--walks 3000", "--walks 40")],
        &[("--pop", "4"), ("--seconds", "0.2")],
    ),
    (
        "ontogeny evolve --encoding ",
        &[("--pop 60", "--pop 4")],
        &[("--seconds", "0.2")],
    ),
    (
        "ontogeny compare --encodings ",
        &[
            ("--replicates 10", "--replicates 2"),
            ("--replicates 29", "--replicates 2"),
            ("--evaluations 8100", "--evaluations 8"),
            ("--evaluations 3940", "--evaluations 8"),
            ("--pop 100", "--pop 4"),
        ],
        &[("--seconds", "0.2")],
    ),
    (
        "ontogeny compare --condition ",
        &[
            ("--replicates 10", "--replicates 2"),
            ("--evaluations 1500", "--evaluations 8"),
            ("--evaluations 2592", "--evaluations 32"),
            ("--evaluations 160", "--evaluations 32"),
        ],
        &[("--pop", "4"), ("--seconds", "0.2")],
    ),
    ("ontogeny runs plasticity ", &[], &[]),
    ("ontogeny runs growth ", &[], &[]),
    ("ontogeny runs schedule ", &[], &[]),
    ("ontogeny runs show ", &[], &[]),
    (
        "ontogeny runs canalization ",
        &[("--samples 20", "--samples 4")],
        &[],
    ),
    (
        "ontogeny bench",
        &[("--fidelity 40", "--fidelity 2 --runs 1")],
        &[("--evaluations", "1"), ("--seconds", "0.2")],
    ),
];

/// `command` cut down by its rule of [`CUT_DOWN`], with what of the table it used (the
/// rule's start and the sizes it replaced); the command as it is, using nothing, when it only
/// goes on from what an earlier one made (`--resume`, `--merge`, `replay`); an error for a
/// slow command that no rule cuts down.
fn cut_down(command: &str) -> Result<(String, Vec<&'static str>), String> {
    let goes_on = command.starts_with("ontogeny replay ")
        || command.contains(" --resume ")
        || command.contains(" --merge ");
    if goes_on {
        return Ok((command.to_string(), Vec::new()));
    }
    let (start, sizes, flags) = CUT_DOWN
        .iter()
        .find(|(start, _, _)| command.starts_with(start))
        .ok_or_else(|| format!("no rule of CUT_DOWN cuts down the slow command `{command}`"))?;
    let mut used = vec![*start];
    let mut cut = command.to_string();
    for (from, to) in *sizes {
        if cut.contains(from) {
            cut = cut.replace(from, to);
            used.push(from);
        }
    }
    for (flag, value) in *flags {
        if !cut.split_whitespace().any(|word| word == *flag) {
            cut = format!("{cut} {flag} {value}");
        }
    }
    Ok((cut, used))
}

#[test]
fn documented_slow_commands_run_cut_down_to_seconds() {
    // Each document's in a scratch directory of its own, as a reader following it has (the
    // README and the guide both evolve `runs/walker`).
    let mut dir = PathBuf::new();
    let mut document = String::new();
    let mut used = Vec::new();
    let mut failures = Vec::new();
    let mut count = 0;
    for d in documented().into_iter().filter(|d| d.mark == Mark::Slow) {
        let (command, uses) = cut_down(&d.command).unwrap_or_else(|e| panic!("{}: {e}", d.place));
        let file = d.place.rsplit_once(':').map_or("", |(file, _)| file);
        if file != document {
            document = file.to_string();
            dir = workplace("doc-commands-slow");
        }
        used.extend(uses);
        count += 1;
        let cut = Documented { command, ..d };
        let (code, said) = run(&dir, &cut);
        if code != Some(0) {
            failures.push(format!(
                "{} `{}`: exit {code:?}\n{}",
                cut.place,
                cut.command,
                said.lines().take(8).collect::<Vec<_>>().join("\n")
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(count > 0, "no slow documented commands found");
    assert!(
        failures.is_empty(),
        "{} of {count} slow documented commands failed:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
    // Every rule and size of the table still cuts down some command.
    let stale: Vec<&str> = CUT_DOWN
        .iter()
        .flat_map(|(start, sizes, _)| std::iter::once(*start).chain(sizes.iter().map(|s| s.0)))
        .filter(|text| !used.contains(text))
        .collect();
    assert!(
        stale.is_empty(),
        "CUT_DOWN cuts down no command with {stale:?}"
    );
}

#[test]
fn a_slow_command_is_cut_down_by_its_rule_and_one_that_goes_on_is_run_as_it_is() {
    assert_eq!(
        cut_down("ontogeny bench --evaluations 1 --fidelity 40"),
        Ok((
            "ontogeny bench --evaluations 1 --fidelity 2 --runs 1 --seconds 0.2".to_string(),
            vec!["ontogeny bench", "--fidelity 40"]
        ))
    );
    assert_eq!(
        cut_down("ontogeny bench"),
        Ok((
            "ontogeny bench --evaluations 1 --seconds 0.2".to_string(),
            vec!["ontogeny bench"]
        ))
    );
    assert_eq!(
        cut_down("ontogeny evolve --resume runs/walker --gens 60"),
        Ok((
            "ontogeny evolve --resume runs/walker --gens 60".to_string(),
            vec![]
        ))
    );
    assert_eq!(
        cut_down("ontogeny eval x.lsys"),
        Err("no rule of CUT_DOWN cuts down the slow command `ontogeny eval x.lsys`".to_string())
    );
}

/// The documented commands that need Chromium.
mod browser {
    use super::*;

    #[test]
    #[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
    fn the_documented_snapshot_commands_write_their_pictures() {
        // `view --snapshot` is given the browser the test found.
        let chromium = crate::view::browser::chromium();
        let pictures: Vec<String> = documented()
            .into_iter()
            .filter(needs_browser)
            .filter_map(|d| {
                let words: Vec<&str> = d.command.split_whitespace().collect();
                let at = words.iter().position(|w| *w == "--snapshot")?;
                words.get(at + 1).map(|w| w.to_string())
            })
            .collect();
        assert!(!pictures.is_empty(), "no documented --snapshot command");
        let dir = workplace("doc-commands-browser");
        let mut failures = Vec::new();
        for d in documented().into_iter().filter(needs_browser) {
            let place = d.place.clone();
            let command = format!("{} --browser '{}'", d.command, chromium.display());
            let (code, said) = run(&dir, &Documented { command, ..d });
            if code != Some(0) {
                failures.push(format!("{place}: exit {code:?}\n{said}"));
            }
        }
        for picture in &pictures {
            let png = tiny_skia::Pixmap::load_png(dir.join(picture));
            assert!(png.is_ok(), "{picture} is no picture: {png:?}");
        }
        let _ = std::fs::remove_dir_all(&dir);
        assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    }
}

#[test]
fn commands_are_found_in_shell_blocks_only_and_marks_apply_to_one_block() {
    let text = "intro\n\
        ```sh\n\
        ontogeny derive examples/algae.lsys --steps 3   # a comment\n\
        cargo run --release -- grow examples/snake.lsys \\\n    --out out/snake\n\
        # a comment line\n\
        ls out\n\
        ```\n\
        ```toml\n\
        ontogeny = \"not a command\"\n\
        ```\n\
        <!-- slow -->\n\
        ```sh\n\
        ontogeny evolve --out runs/x\n\
        ```\n\
        ```sh\n\
        ontogeny runs show runs/x\n\
        ```\n";
    let found = skip_other_blocks("t.md", text);
    let seen: Vec<(&str, Mark)> = found.iter().map(|d| (d.command.as_str(), d.mark)).collect();
    assert_eq!(
        seen,
        vec![
            ("ontogeny derive examples/algae.lsys --steps 3", Mark::Quick),
            (
                "ontogeny grow examples/snake.lsys --out out/snake",
                Mark::Quick
            ),
            ("ontogeny evolve --out runs/x", Mark::Slow),
            ("ontogeny runs show runs/x", Mark::Quick),
        ]
    );
    assert_eq!(found[1].place, "t.md:4");
}

#[test]
fn the_commands_reference_lists_the_command_table() {
    use ontogeny::lang::commands::Command;
    let page = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/reference/commands.md");
    let text = std::fs::read_to_string(page).unwrap();
    // The rows of the page's table: `| `name` | argument | meaning |` (a `|` in a cell is
    // written `\|`, as tables need).
    let rows: Vec<(String, String)> = text
        .lines()
        .filter_map(|line| {
            let line = line.replace("\\|", "\u{1}");
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            Some((name.replace('\u{1}', "|"), cells.get(2)?.to_string()))
        })
        .collect();
    let listed: Vec<&str> = rows.iter().map(|(name, _)| name.as_str()).collect();
    let table: Vec<&str> = Command::EVERY.iter().map(|c| c.name()).collect();
    assert_eq!(
        listed, table,
        "docs/reference/commands.md against the table, in order"
    );
    for ((name, argument), command) in rows.iter().zip(Command::EVERY) {
        assert_eq!(
            argument != "—",
            command.has_argument(),
            "`{name}`: the page's argument column ({argument}) against the table"
        );
    }
}

/// Every fitness the reference documents, the evolution results (each shipped champion at its
/// recorded evaluation and at the fine reference) and the examples' own comments quote for a
/// shipped file, evaluated again: the quoted text is in the document, and `eval` with the
/// flags gives that number at the quoted precision.
#[test]
fn the_fitness_figures_the_documents_quote_for_shipped_files_are_what_eval_gives() {
    let no_flags: &[&str] = &[];
    let fine: &[&str] = &["--setting", "fine"];
    let figures: [(&str, &str, &str, &[&str], usize); 19] = [
        (
            "docs/reference/genomes.md",
            "gives it 0.002242",
            "examples/hornby-walker.lsys",
            no_flags,
            6,
        ),
        (
            "docs/reference/genomes.md",
            "the quadruped 0.318288",
            "examples/quadruped.lsys",
            no_flags,
            6,
        ),
        (
            "docs/reference/genomes.md",
            "`quadruped.lsys` gets 0.318288",
            "examples/quadruped.lsys",
            no_flags,
            6,
        ),
        (
            "docs/reference/genomes.md",
            "walker fitness 0.002964",
            "examples/continuous-walker.lsys",
            no_flags,
            6,
        ),
        (
            "examples/quadruped.lsys",
            "D_w = 5.38 m",
            "examples/quadruped.lsys",
            &["--fitness", "distance"],
            2,
        ),
        (
            "docs/results/evolution.md",
            "**D_w = 12.92 m**",
            "docs/evolve/continuous-best.lsys",
            no_flags,
            2,
        ),
        (
            "docs/results/evolution.md",
            "**7.23 m** at the fine reference",
            "docs/evolve/continuous-best.lsys",
            fine,
            2,
        ),
        (
            "docs/results/evolution.md",
            "`ontogeny eval docs/evolve/continuous-best.lsys` gives 12.921048",
            "docs/evolve/continuous-best.lsys",
            no_flags,
            6,
        ),
        (
            "docs/results/evolution.md",
            "**D_w = 20.56 m**",
            "docs/evolve/direct-best.lsys",
            no_flags,
            2,
        ),
        (
            "docs/results/evolution.md",
            "**20.40 m** at the fine",
            "docs/evolve/direct-best.lsys",
            fine,
            2,
        ),
        (
            "docs/results/evolution.md",
            "**D_w = 28.33 m**",
            "docs/evolve/graph-walker-best.json",
            no_flags,
            2,
        ),
        (
            "docs/results/evolution.md",
            "**4.08 m** at the fine reference",
            "docs/evolve/graph-walker-best.json",
            fine,
            2,
        ),
        (
            "docs/results/evolution.md",
            "`ontogeny eval docs/evolve/graph-catapult-best.json` gives 197.438616",
            "docs/evolve/graph-catapult-best.json",
            no_flags,
            6,
        ),
        (
            "docs/results/evolution.md",
            "**118.8 m** (60%) at the fine reference",
            "docs/evolve/graph-catapult-best.json",
            fine,
            1,
        ),
        (
            "docs/results/evolution.md",
            "`ontogeny eval docs/evolve/graph-projectile-best.json` gives 139.722968",
            "docs/evolve/graph-projectile-best.json",
            no_flags,
            6,
        ),
        (
            "docs/results/evolution.md",
            "**0.75 m** at the fine reference",
            "docs/evolve/graph-projectile-best.json",
            fine,
            2,
        ),
        (
            "docs/results/evolution.md",
            "`ontogeny eval docs/evolve/graph-aim-best.json` gives 152.148642",
            "docs/evolve/graph-aim-best.json",
            no_flags,
            6,
        ),
        (
            "docs/results/evolution.md",
            "and **93.2** at the fine reference",
            "docs/evolve/graph-aim-best.json",
            fine,
            1,
        ),
        (
            "docs/results/evolution.md",
            "scoring the same\n152.148642",
            "docs/evolve/graph-aim-blind-best.json",
            no_flags,
            6,
        ),
    ];
    for (document, quoted, file, flags, digits) in figures {
        let text = std::fs::read_to_string(document).unwrap();
        assert!(
            text.contains(quoted),
            "{document} no longer says '{quoted}'"
        );
        let o = crate::util::ontogeny_ok(&[&["eval", file, "--json"][..], flags].concat());
        let value: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let fitness = value["fitness"].as_f64().unwrap();
        let shown = format!("{fitness:.digits$}");
        assert!(
            quoted.contains(&shown),
            "{document} quotes '{quoted}' for {file}; eval gives {fitness}"
        );
    }
}

#[test]
fn the_configuration_reference_lists_the_table_of_knobs() {
    let page = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/reference/configuration.md");
    let text = std::fs::read_to_string(page).unwrap();
    let table = ontogeny::sim::knobs::reference_table();
    assert!(
        text.contains(&table),
        "docs/reference/configuration.md must hold the table of knobs as it is today:\n{table}"
    );
}
