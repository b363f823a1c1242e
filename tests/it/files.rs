//! What the user's files and folders get: an output folder is used only when it is new,
//! empty or Ontogeny's own for the same verb; an output file is replaced only when it is a
//! regular file, and a link that points nowhere is refused in words; every input is read with
//! a cap on its size (`ONTOGENY_MAX_INPUT`), without its byte-order mark, and a folder or a
//! dangling link given as an input is refused in words.

use std::path::{Path, PathBuf};

use ontogeny::output::FolderKind;

use crate::util::{ontogeny, ontogeny_command, ontogeny_ok, refused, scratch_dir, stderr, stdout};

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("files-{name}"))
}

/// A path as an argument.
fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A file of the repository, as an absolute path (for commands run in another directory).
fn repository_file(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(name)
        .display()
        .to_string()
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A folder `dir/name` holding the user's file `file` ("mine").
fn users_folder(dir: &Path, name: &str, file: &str) -> PathBuf {
    let folder = dir.join(name);
    std::fs::create_dir(&folder).unwrap();
    std::fs::write(folder.join(file), "mine").unwrap();
    folder
}

/// Asserts that `folder` still holds only the user's `file`, as it was.
fn untouched(folder: &Path, file: &str) {
    assert_eq!(names(folder), [file]);
    assert_eq!(std::fs::read_to_string(folder.join(file)).unwrap(), "mine");
}

/// The refusal of a folder of the user's that holds `found`, by the command `verb`.
fn not_ours(folder: &Path, verb: &str, found: &str) -> String {
    format!(
        "{} already holds files that {verb} did not write there ({found}); refusing to write \
         into it: choose a new or empty folder",
        folder.display()
    )
}

#[test]
fn evolve_out_into_a_folder_of_the_users_files_is_refused_and_left_untouched() {
    let dir = scratch("evolve-users-folder");
    let folder = users_folder(&dir, "d", "log.txt");
    let said = refused(
        &ontogeny(&[
            "evolve",
            "--task",
            "walker",
            "--pop",
            "6",
            "--gens",
            "1",
            "--seconds",
            "1",
            "--out",
            arg(&folder),
        ]),
        &not_ours(&folder, "`ontogeny evolve`", "log.txt"),
    );
    assert!(
        said.contains(&format!(
            "(or, if it holds a run, go on with it: `ontogeny evolve --resume {}`)",
            folder.display()
        )),
        "{said}"
    );
    untouched(&folder, "log.txt");
}

#[test]
fn compare_out_into_a_folder_holding_a_report_of_the_users_is_refused_and_left_untouched() {
    let dir = scratch("compare-users-folder");
    let folder = users_folder(&dir, "c", "report.md");
    let said = refused(
        &ontogeny(&[
            "compare",
            "--encodings",
            "lsystem,direct",
            "--task",
            "walker",
            "--replicates",
            "1",
            "--evaluations",
            "12",
            "--pop",
            "6",
            "--seconds",
            "1",
            "--out",
            arg(&folder),
        ]),
        &not_ours(&folder, "`ontogeny compare`", "report.md"),
    );
    assert!(said.contains("`ontogeny compare --resume "), "{said}");
    untouched(&folder, "report.md");
}

#[test]
fn grow_out_writes_again_into_its_own_folder_and_never_into_the_users() {
    let dir = scratch("grow-own-folder");
    let out = dir.join("g");
    for _ in 0..2 {
        ontogeny_ok(&["grow", "examples/snake.lsys", "--out", arg(&out)]);
    }
    assert_eq!(
        names(&out),
        [
            ".ontogeny-growth",
            "creature.json",
            "creature.png",
            "frames.jsonl",
            "growth.gif"
        ]
    );
    // An empty folder is used, and becomes the growth's.
    let empty = dir.join("empty");
    std::fs::create_dir(&empty).unwrap();
    ontogeny_ok(&["grow", "examples/snake.lsys", "--out", arg(&empty)]);
    assert!(empty.join(FolderKind::Growth.mark()).is_file());
    // The user's own creature.json is never replaced, nor is the folder a recording made.
    let folder = users_folder(&dir, "mine", "creature.json");
    let o = ontogeny(&["grow", "examples/snake.lsys", "--out", arg(&folder)]);
    refused(
        &o,
        &not_ours(&folder, "`ontogeny grow --out`", "creature.json"),
    );
    assert!(
        stdout(&o).is_empty(),
        "refused before growing: {}",
        stdout(&o)
    );
    untouched(&folder, "creature.json");
    let recording = dir.join("recording");
    ontogeny::output::prepare_folder(&recording, FolderKind::Recording).unwrap();
    refused(
        &ontogeny(&["grow", "examples/snake.lsys", "--out", arg(&recording)]),
        &not_ours(&recording, "`ontogeny grow --out`", ".ontogeny-recording"),
    );
}

#[test]
fn eval_record_writes_again_into_its_own_folder_and_refuses_the_users_before_evaluating() {
    let dir = scratch("record-own-folder");
    let record = dir.join("r");
    let eval = |record: &Path| {
        ontogeny(&[
            "eval",
            "examples/snake.lsys",
            "--task",
            "walker",
            "--seconds",
            "0.2",
            "--record",
            arg(record),
        ])
    };
    for _ in 0..2 {
        crate::util::succeeded(&eval(&record));
    }
    assert_eq!(
        names(&record),
        [".ontogeny-recording", "behaviour.gif", "recording.json"]
    );
    let folder = users_folder(&dir, "mine", "behaviour.gif");
    let o = eval(&folder);
    refused(
        &o,
        &not_ours(&folder, "`ontogeny eval --record`", "behaviour.gif"),
    );
    assert!(
        stdout(&o).is_empty(),
        "refused before evaluating: {}",
        stdout(&o)
    );
    untouched(&folder, "behaviour.gif");
}

#[test]
fn out_dot_and_out_root_are_refused_when_they_hold_anything() {
    let dir = scratch("out-dot");
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    let snake = repository_file("examples/snake.lsys");
    for (args, folder, verb) in [
        (
            vec!["grow", snake.as_str(), "--out", "."],
            ".",
            "`ontogeny grow --out`",
        ),
        (
            vec![
                "evolve", "--task", "walker", "--pop", "6", "--gens", "1", "--out", ".",
            ],
            ".",
            "`ontogeny evolve`",
        ),
        (
            vec!["grow", snake.as_str(), "--out", "/"],
            "/",
            "`ontogeny grow --out`",
        ),
        (
            vec!["eval", snake.as_str(), "--task", "walker", "--record", "/"],
            "/",
            "`ontogeny eval --record`",
        ),
    ] {
        let o = ontogeny_command()
            .current_dir(&dir)
            .args(&args)
            .output()
            .unwrap();
        let said = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {said}");
        assert!(
            said.starts_with(&format!(
                "error: {folder} already holds files that {verb} did not write there ("
            )),
            "{args:?}: {said}"
        );
    }
    untouched(&dir, "notes.txt");
}

#[test]
fn an_output_folder_that_is_a_file_or_a_dangling_link_is_refused_in_words() {
    let dir = scratch("folder-not-folder");
    let file = dir.join("taken");
    std::fs::write(&file, "mine").unwrap();
    refused(
        &ontogeny(&["grow", "examples/snake.lsys", "--out", arg(&file)]),
        &format!(
            "{} exists and is not a folder; refusing to write into it: choose a new or empty \
             folder",
            file.display()
        ),
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    #[cfg(unix)]
    {
        let link = dir.join("link");
        std::os::unix::fs::symlink("nowhere", &link).unwrap();
        for args in [
            &["grow", "examples/snake.lsys", "--out", arg(&link)][..],
            &[
                "evolve",
                "--task",
                "walker",
                "--pop",
                "6",
                "--gens",
                "1",
                "--out",
                arg(&link),
            ],
        ] {
            let said = refused(
                &ontogeny(args),
                &format!(
                    "{} is a symbolic link to nowhere, which does not exist; refusing to write \
                     through it: remove the link, or choose another path",
                    link.display()
                ),
            );
            assert!(!said.contains("os error"), "{said}");
        }
        assert!(!dir.join("nowhere").exists());
    }
}

#[cfg(unix)]
#[test]
fn an_output_file_is_replaced_when_regular_and_never_through_a_link_or_onto_a_device() {
    let dir = scratch("output-file");
    let out = |target: &Path| ontogeny(&["export", "examples/snake.lsys", "--out", arg(target)]);
    // A regular file: replaced, as an edit and a re-run expects.
    let model = dir.join("model.xml");
    std::fs::write(&model, "old").unwrap();
    crate::util::succeeded(&out(&model));
    assert!(std::fs::read_to_string(&model).unwrap().contains("<mujoco"));
    // A link to a file of the user's: refused, and neither the link nor the file changes.
    let mine = dir.join("mine.xml");
    std::fs::write(&mine, "mine").unwrap();
    let link = dir.join("link.xml");
    std::os::unix::fs::symlink(&mine, &link).unwrap();
    refused(
        &out(&link),
        &format!(
            "{} exists and is not a regular file; refusing to replace it",
            link.display()
        ),
    );
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "mine");
    assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
    // A link that points nowhere: said in words, not "File exists".
    let dangling = dir.join("dangling.xml");
    std::os::unix::fs::symlink("gone/model.xml", &dangling).unwrap();
    let said = refused(
        &out(&dangling),
        &format!(
            "{} is a symbolic link to gone/model.xml, which does not exist; refusing to write \
             through it: remove the link, or choose another path",
            dangling.display()
        ),
    );
    assert!(!said.contains("os error"), "{said}");
    assert!(!dir.join("gone").exists());
    // A device.
    refused(
        &out(Path::new("/dev/null")),
        "/dev/null exists and is not a regular file; refusing to replace it",
    );
}

/// The refusal of an endless stream at the default cap.
const ENDLESS: &str = "more than 64 MiB came from it without an end; the most an input may be \
                       is 64 MiB (set ONTOGENY_MAX_INPUT, a size in bytes or with a suffix K, M \
                       or G, to raise it)";

#[cfg(unix)]
#[test]
fn endless_streams_are_refused_at_the_cap_by_every_verb_that_reads() {
    let dir = scratch("endless");
    let out = dir.join("run");
    let out = arg(&out);
    for (args, stream) in [
        (&["derive", "/dev/zero"][..], "/dev/zero"),
        (&["check", "/dev/urandom"], "/dev/urandom"),
        (&["grow", "/dev/zero"], "/dev/zero"),
        (&["eval", "/dev/zero", "--task", "walker"], "/dev/zero"),
        (&["genome", "show", "/dev/zero"], "/dev/zero"),
        (
            &[
                "evolve",
                "--init",
                "/dev/zero",
                "--task",
                "walker",
                "--out",
                out,
            ],
            "/dev/zero",
        ),
        (
            &["evolve", "--config", "/dev/zero", "--out", out],
            "/dev/zero",
        ),
        (
            &[
                "compare",
                "--encodings",
                "direct",
                "--evaluations",
                "12",
                "--config",
                "/dev/zero",
                "--out",
                out,
            ],
            "/dev/zero",
        ),
    ] {
        let said = refused(&ontogeny(args), &format!("cannot read {stream}: {ENDLESS}"));
        assert!(!said.contains("panicked"), "{args:?}: {said}");
    }
    assert!(!dir.join("run").exists(), "a refused input wrote the run");
    // `view` reads no stream: it says what the path is and starts no server or browser.
    let snapshot = dir.join("view.png");
    refused(
        &ontogeny(&["view", "/dev/zero", "--snapshot", arg(&snapshot)]),
        "/dev/zero: not a regular file or a directory",
    );
    assert!(!snapshot.exists());
}

#[test]
fn standard_input_is_read_to_the_cap_and_no_further() {
    let o = crate::util::ontogeny_reading(&["derive", "-"], &vec![b' '; (64 << 20) + 1]);
    refused(&o, &format!("cannot read -: {ENDLESS}"));
}

#[test]
fn a_regular_file_over_the_cap_is_refused_before_it_is_read() {
    let dir = scratch("sparse");
    let path = dir.join("huge.lsys");
    let file = std::fs::File::create(&path).unwrap();
    // Sparse: 65 MiB long, no block written.
    file.set_len(65 << 20).unwrap();
    let size = "it is 65 MiB; the most an input may be is 64 MiB (set ONTOGENY_MAX_INPUT, a \
                size in bytes or with a suffix K, M or G, to raise it)";
    refused(
        &ontogeny(&["check", arg(&path)]),
        &format!("cannot read {}: {size}", path.display()),
    );
    // The library's loader, which the Python package's `load` calls, refuses it too.
    let json = dir.join("huge.json");
    std::fs::File::create(&json)
        .unwrap()
        .set_len(65 << 20)
        .unwrap();
    let error = ontogeny::encoding::load_creature(
        &json,
        &ontogeny::encoding::LoadOptions::default(),
        &mut |_| {},
    )
    .unwrap_err();
    assert_eq!(
        error.to_string(),
        format!("cannot read {}: {size}", json.display())
    );
}

#[test]
fn the_environment_variable_sets_the_cap_and_a_file_under_it_is_read() {
    let dir = scratch("cap-variable");
    let path = dir.join("padded.lsys");
    // 2 KiB: a grammar and a comment.
    let mut text = String::from("axiom: A\nA --> A B\n# ");
    text.push_str(&"x".repeat(2048 - text.len() - 1));
    text.push('\n');
    assert_eq!(text.len(), 2048);
    std::fs::write(&path, &text).unwrap();
    let check = |cap: Option<&str>| {
        let mut command = ontogeny_command();
        command.args(["derive", arg(&path), "--steps", "2"]);
        match cap {
            Some(cap) => command.env("ONTOGENY_MAX_INPUT", cap),
            None => command.env_remove("ONTOGENY_MAX_INPUT"),
        };
        command.output().unwrap()
    };
    assert_eq!(
        crate::util::succeeded(&check(None)),
        "0: A\n1: AB\n2: ABB\n",
        "under the default cap"
    );
    refused(
        &check(Some("1K")),
        &format!(
            "cannot read {}: it is 2 KiB; the most an input may be is 1 KiB",
            path.display()
        ),
    );
    assert_eq!(
        crate::util::succeeded(&check(Some("2048"))),
        "0: A\n1: AB\n2: ABB\n"
    );
    assert_eq!(
        crate::util::succeeded(&check(Some(""))),
        "0: A\n1: AB\n2: ABB\n",
        "set to nothing, the variable counts as unset"
    );
    refused(
        &check(Some("lots")),
        "ONTOGENY_MAX_INPUT must be a size in bytes, above 0 (e.g. 200000000, or 512M; \
         suffixes K, M and G), not 'lots'",
    );
}

#[test]
fn a_folder_or_a_dangling_link_given_as_an_input_is_refused_in_words() {
    let dir = scratch("input-not-file");
    for args in [
        &["derive", arg(&dir)][..],
        &["genome", "show", arg(&dir)],
        &["eval", arg(&dir), "--task", "walker"],
    ] {
        refused(
            &ontogeny(args),
            &format!("cannot read {}: a directory, not a file", dir.display()),
        );
    }
    #[cfg(unix)]
    {
        let link = dir.join("link.lsys");
        std::os::unix::fs::symlink("gone.lsys", &link).unwrap();
        refused(
            &ontogeny(&["check", arg(&link)]),
            &format!(
                "cannot read {}: it is a symbolic link to gone.lsys, which does not exist",
                link.display()
            ),
        );
    }
}

/// `text` with UTF-8's byte-order mark before it.
fn marked(text: &[u8]) -> Vec<u8> {
    [b"\xEF\xBB\xBF", text].concat()
}

#[test]
fn a_byte_order_mark_is_read_as_if_it_had_none() {
    let dir = scratch("byte-order-mark");
    // A grammar.
    let grammar = std::fs::read("examples/algae.lsys").unwrap();
    let path = dir.join("algae.lsys");
    std::fs::write(&path, marked(&grammar)).unwrap();
    assert_eq!(
        stdout(&ontogeny_ok(&["derive", arg(&path)])),
        stdout(&ontogeny_ok(&["derive", "examples/algae.lsys"]))
    );
    // A genome's JSON.
    let genome = std::fs::read("docs/evolve/graph-walker-best.json").unwrap();
    let path = dir.join("best.json");
    std::fs::write(&path, marked(&genome)).unwrap();
    let shown = stdout(&ontogeny_ok(&["genome", "show", arg(&path)]));
    assert!(
        shown.starts_with(&format!("{}: graph genome (", path.display())),
        "{shown}"
    );
    // A creature's JSON: exported as the unmarked one is.
    let grown = dir.join("grown");
    ontogeny_ok(&["grow", "examples/snake.lsys", "--out", arg(&grown)]);
    let creature = std::fs::read(grown.join("creature.json")).unwrap();
    let path = dir.join("creature.json");
    std::fs::write(&path, marked(&creature)).unwrap();
    assert_eq!(
        stdout(&ontogeny_ok(&["export", arg(&path)])),
        stdout(&ontogeny_ok(&["export", arg(&grown.join("creature.json"))]))
    );
    // A configuration.
    let config = std::fs::read("examples/compare-walker.toml").unwrap();
    let path = dir.join("compare.toml");
    std::fs::write(&path, marked(&config)).unwrap();
    let planned = dir.join("planned");
    ontogeny_ok(&[
        "compare",
        "--encodings",
        "lsystem,direct",
        "--replicates",
        "1",
        "--evaluations",
        "100",
        "--config",
        arg(&path),
        "--plan",
        "--out",
        arg(&planned),
    ]);
    assert!(planned.join("compare.toml").is_file());
}
