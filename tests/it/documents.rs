//! The documents cannot drift. The building commands' reference page lists exactly the
//! commands of the one command table (`ontogeny::lang::commands`). Every `ontogeny` command
//! shown in the README and the guide is run against the built binary, in order, in a scratch directory that holds the repository's
//! `examples/`, `docs/` and `tests/fixtures/`.
//!
//! A command is a line of a fenced `sh` block that starts with `ontogeny` or `cargo run
//! --release --` (continued over lines ending in `\`; text after ` # ` is a comment). A block
//! is marked by an HTML comment on the line before its fence:
//! - `<!-- slow -->`: its commands take over a minute, or need the output of one that does;
//!   they run only in
//!   `documented_slow_commands_run`, which is ignored (`cargo test --release -- --ignored`);
//! - `<!-- fails -->`: its commands show a refusal; each must exit with code 2;
//! - `<!-- not run -->`: shown, never run (a cluster script, a command needing a display).
//!
//! `ontogeny view` without `--snapshot` serves until stopped: it is started, must say where it
//! serves within ten seconds, and is then stopped.

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

/// Runs the documented commands of the given marks, in order, in one scratch directory;
/// panics listing every command that did not do what its mark says.
fn run_documented(name: &str, marks: &[Mark]) {
    let dir = workplace(name);
    let mut failures = Vec::new();
    let mut count = 0;
    for d in documented() {
        if d.mark == Mark::NotRun {
            continue;
        }
        // A command that needs the output of a slow one is marked slow too.
        if !marks.contains(&d.mark) {
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
    run_documented("doc-commands", &[Mark::Quick, Mark::Fails]);
}

#[test]
#[ignore = "runs the documents' commands that take over a minute (about N minutes)"]
fn documented_slow_commands_run() {
    run_documented("doc-commands-slow", &[Mark::Quick, Mark::Fails, Mark::Slow]);
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
    // The rows of the page's table: `| `name` | argument | meaning |`.
    let rows: Vec<(String, String)> = text
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            Some((name.to_string(), cells.get(2)?.to_string()))
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
