//! The rooms of ARCHITECTURE.md: a module imports only from the rooms before it in the
//! pipeline, so that no import cycle can form. Checked over the source text: every
//! `crate::ROOM` path outside comments, in every file of a room.

use std::path::Path;

/// The rooms in pipeline order: each may use only those before it.
const ROOMS: [&str; 16] = [
    "cancel", "lang", "lsystem", "creature", "develop", "sim", "task", "encoding", "evolve", "run",
    "study", "front", "render", "export", "view", "cli",
];

/// The rooms that `text` names as `crate::ROOM`, comments left out.
fn rooms_used(text: &str) -> Vec<&'static str> {
    let mut used = Vec::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        for (at, _) in code.match_indices("crate::") {
            let rest = &code[at + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if let Some(room) = ROOMS.iter().find(|r| **r == name) {
                used.push(*room);
            }
        }
    }
    used
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_room_imports_only_from_the_rooms_before_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut wrong = Vec::new();
    for (rank, room) in ROOMS.iter().enumerate() {
        // A room is a folder, or a single file (`src/cancel.rs`).
        let mut files = Vec::new();
        let single = src.join(format!("{room}.rs"));
        if single.is_file() {
            files.push(single);
        } else {
            rust_files(&src.join(room), &mut files);
        }
        assert!(!files.is_empty(), "no files in src/{room}(.rs)");
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            for used in rooms_used(&text) {
                let used_rank = ROOMS.iter().position(|r| *r == used).unwrap();
                if used_rank >= rank && used != *room {
                    wrong.push(format!("{} uses crate::{used}", file.display()));
                }
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the pipeline:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_room_check_sees_paths_and_skips_comments() {
    assert_eq!(
        rooms_used("use crate::sim::World; // crate::view\nlet x = crate::task::walker;"),
        ["sim", "task"]
    );
    assert!(rooms_used("//! the genetic algorithm (`crate::evolve`)").is_empty());
}

#[test]
fn the_reader_and_the_writer_beside_the_rooms_import_no_room() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = vec![src.join("input.rs"), src.join("output.rs")];
    rust_files(&src.join("output"), &mut files);
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(
            rooms_used(&text).is_empty(),
            "{} uses a room, so a room before it could not use it",
            file.display()
        );
    }
}
