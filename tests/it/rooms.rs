//! The rooms of ARCHITECTURE.md: a module imports only from the rooms before it in the
//! pipeline, so that no import cycle can form. Checked over the source text: every `crate::`
//! path outside comments, however it is written (`crate::a::b`, `crate::{a, b::{c, d}}`, over
//! several lines, inside an expression, an exported macro by the room that defines it), in
//! every file under `src/`.

use std::path::{Path, PathBuf};

/// The rooms in pipeline order: each may use only those before it.
const ROOMS: [&str; 17] = [
    "cancel",
    "lang",
    "environment",
    "lsystem",
    "creature",
    "develop",
    "sim",
    "task",
    "encoding",
    "evolve",
    "run",
    "study",
    "front",
    "render",
    "export",
    "view",
    "cli",
];

/// The modules beside the rooms, in order: every room may use them, and each of them only
/// those before it.
const BESIDE: [&str; 3] = ["number", "input", "output"];

/// `text` without its comments (`// …` to the end of the line, `/* … */`).
fn without_comments(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while !rest.is_empty() {
        // The first comment to start: a line's (`true`) or a block (`false`).
        let first = [(rest.find("//"), true), (rest.find("/*"), false)]
            .into_iter()
            .filter_map(|(at, line)| at.map(|at| (at, line)))
            .min();
        match first {
            Some((at, true)) => {
                out.push_str(&rest[..at]);
                rest = rest[at..].find('\n').map_or("", |end| &rest[at + end..]);
            }
            Some((at, false)) => {
                out.push_str(&rest[..at]);
                rest = rest[at..]
                    .find("*/")
                    .map_or("", |end| &rest[at + end + 2..]);
            }
            None => {
                out.push_str(rest);
                rest = "";
            }
        }
    }
    out
}

/// The tokens of `code` that matter to a path: words (`$` for a macro's metavariable), `::`,
/// brackets, `,`, `;` and `!`.
fn tokens(code: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut at = 0;
    let bytes = code.as_bytes();
    while at < bytes.len() {
        let c = bytes[at];
        if c.is_ascii_alphanumeric() || c == b'_' {
            let start = at;
            while at < bytes.len() && (bytes[at].is_ascii_alphanumeric() || bytes[at] == b'_') {
                at += 1;
            }
            let word = &code[start..at];
            // A macro's metavariable (`$callback`) names no module; `$crate` is the crate.
            let metavariable = start > 0 && bytes[start - 1] == b'$' && word != "crate";
            out.push(if metavariable { "$" } else { word });
            continue;
        }
        if bytes[at..].starts_with(b"::") {
            out.push("::");
            at += 2;
            continue;
        }
        if matches!(
            c,
            b'{' | b'}' | b',' | b'!' | b';' | b'(' | b')' | b'<' | b'>'
        ) {
            out.push(&code[at..at + 1]);
        }
        at += 1;
    }
    out
}

/// The first name of every path that `text` starts with `crate::`, comments left out: one
/// for `crate::sim::World`, each one of a group (`crate::{sim, task::{a, b}}` names `sim` and
/// `task`), none for `crate::{self}`.
fn crate_names(text: &str) -> Vec<String> {
    let code = without_comments(text);
    let tokens = tokens(&code);
    let mut names = Vec::new();
    let mut i = 0;
    while i + 2 < tokens.len() {
        if tokens[i] != "crate" || tokens[i + 1] != "::" {
            i += 1;
            continue;
        }
        i += 2;
        if tokens[i] == "{" {
            // A group: the first word of each of its items.
            let mut depth = 0;
            let mut first = true;
            while i < tokens.len() {
                match tokens[i] {
                    "{" => {
                        depth += 1;
                        first = depth == 1;
                    }
                    "}" => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    "," if depth == 1 => first = true,
                    word if first && depth == 1 => {
                        if word != "self" {
                            names.push(word.to_string());
                        }
                        first = false;
                    }
                    _ => {}
                }
                i += 1;
            }
        } else if tokens[i] != "self" && tokens[i] != "$" {
            names.push(tokens[i].to_string());
        }
    }
    names
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The files of the module `name`: `src/NAME.rs` and everything under `src/NAME/`.
fn files_of(src: &Path, name: &str) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let single = src.join(format!("{name}.rs"));
    if single.is_file() {
        files.push(single);
    }
    if src.join(name).is_dir() {
        rust_files(&src.join(name), &mut files);
    }
    files
}

/// The exported macros (`#[macro_export] macro_rules! NAME`) of each room, by name: a use of
/// `crate::NAME!` is a use of the room that defines it.
fn exported_macros(src: &Path) -> Vec<(String, &'static str)> {
    let mut macros = Vec::new();
    for room in ROOMS {
        for file in files_of(src, room) {
            let text = std::fs::read_to_string(&file).unwrap();
            for (at, _) in text.match_indices("#[macro_export]") {
                let after = &text[at..];
                if let Some(m) = after.find("macro_rules!") {
                    let name: String = after[m + "macro_rules!".len()..]
                        .trim_start()
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    macros.push((name, room));
                }
            }
        }
    }
    macros
}

/// What is wrong with the `crate::` paths of module `name`'s files, when the modules it may use
/// are `allowed`.
fn misuses(src: &Path, name: &str, allowed: &[&str], macros: &[(String, &str)]) -> Vec<String> {
    let mut wrong = Vec::new();
    let files = files_of(src, name);
    assert!(!files.is_empty(), "no files in src/{name}(.rs)");
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for used in crate_names(&text) {
            let module = macros
                .iter()
                .find(|(m, _)| *m == used)
                .map_or(used.as_str(), |(_, room)| room);
            if module != name && !allowed.contains(&module) {
                wrong.push(format!("{} uses crate::{used}", file.display()));
            }
        }
    }
    wrong
}

#[test]
fn every_room_imports_only_from_the_rooms_before_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let macros = exported_macros(&src);
    let mut wrong = Vec::new();
    for (rank, room) in ROOMS.iter().enumerate() {
        let allowed: Vec<&str> = ROOMS[..rank].iter().chain(&BESIDE).copied().collect();
        wrong.extend(misuses(&src, room, &allowed, &macros));
    }
    assert!(
        wrong.is_empty(),
        "imports against the pipeline:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_modules_beside_the_rooms_import_no_room() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut wrong = Vec::new();
    for (rank, module) in BESIDE.iter().enumerate() {
        wrong.extend(misuses(&src, module, &BESIDE[..rank], &[]));
    }
    assert!(
        wrong.is_empty(),
        "a module beside the rooms uses a room, so a room before it could not use it:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn every_module_of_the_crate_is_a_room_or_beside_them() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = std::fs::read_to_string(src.join("lib.rs")).unwrap();
    let mut unplaced = Vec::new();
    for line in lib.lines() {
        if let Some(name) = line.strip_prefix("pub mod ").or(line.strip_prefix("mod ")) {
            let name = name.trim_end_matches(';');
            if !ROOMS.contains(&name) && !BESIDE.contains(&name) {
                unplaced.push(name.to_string());
            }
        }
    }
    assert!(unplaced.is_empty(), "modules in no room: {unplaced:?}");
}

#[test]
fn the_room_check_sees_every_way_of_writing_a_path_and_skips_comments() {
    assert_eq!(
        crate_names("use crate::sim::World; // crate::view\nlet x = crate::task::walker;"),
        ["sim", "task"]
    );
    assert!(crate_names("//! the genetic algorithm (`crate::evolve`)").is_empty());
    assert!(crate_names("/* crate::view */ let a = 1;").is_empty());
    assert_eq!(
        crate_names("use crate::{\n    self,\n    sim::{World, options::{A, B}},\n    task,\n};"),
        ["sim", "task"]
    );
    assert_eq!(
        crate_names("let n = crate :: number::format_number(x) + crate::\n    lang::f();"),
        ["number", "lang"]
    );
    assert_eq!(
        crate_names("crate::with_genome!(name, G => f::<G>())"),
        ["with_genome"]
    );
}

/// Every path of `code`'s tokens that starts with `crate`, `super` or `self`, as its words,
/// groups expanded (`super::{a, b::{c, d}}` is `super::a`, `super::b::c`, `super::b::d`).
fn paths(tokens: &[&str]) -> Vec<Vec<String>> {
    /// The paths from `tokens[*at]` on, after `prefix`: one word after another, or a group.
    fn read(tokens: &[&str], at: &mut usize, prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
        let mut path = prefix;
        loop {
            match tokens.get(*at) {
                Some(&"{") => {
                    *at += 1;
                    while *at < tokens.len() && tokens[*at] != "}" {
                        if tokens[*at] == "," {
                            *at += 1;
                            continue;
                        }
                        read(tokens, at, path.clone(), out);
                    }
                    *at += 1;
                    return;
                }
                Some(word) if word.chars().all(|c| c.is_alphanumeric() || c == '_') => {
                    path.push(word.to_string());
                    *at += 1;
                    if tokens.get(*at) == Some(&"::") {
                        *at += 1;
                        continue;
                    }
                    out.push(path);
                    return;
                }
                _ => {
                    out.push(path);
                    return;
                }
            }
        }
    }
    let mut out = Vec::new();
    let mut at = 0;
    while at + 1 < tokens.len() {
        let starts = matches!(tokens[at], "crate" | "super" | "self")
            && tokens[at + 1] == "::"
            && (at == 0 || tokens[at - 1] != "::");
        if starts {
            read(tokens, &mut at, Vec::new(), &mut out);
        } else {
            at += 1;
        }
    }
    out
}

/// The module path of a file under `src` (`src/run/store/error.rs` is `run::store::error`,
/// `src/run/store/mod.rs` is `run::store`).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let relative = file.strip_prefix(src).unwrap().with_extension("");
    let mut path: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if path.last().is_some_and(|last| last == "mod") {
        path.pop();
    }
    path
}

/// The absolute module path that `path`, in the file of module `module`, names: `crate::`
/// taken away, each `super` one level up, `self` the module.
fn absolute(path: &[String], module: &[String]) -> Vec<String> {
    let mut base: Vec<String> = Vec::new();
    let mut words = path.iter().peekable();
    match words.peek().map(|w| w.as_str()) {
        Some("crate") => {
            words.next();
        }
        Some("self") => {
            words.next();
            base = module.to_vec();
        }
        Some("super") => {
            // A file's module is itself (a `mod.rs`, its folder's): `super` is the one above.
            base = module.to_vec();
            while words.peek().is_some_and(|w| *w == "super") {
                words.next();
                base.pop();
            }
        }
        _ => {}
    }
    base.extend(words.cloned());
    base
}

#[test]
fn no_two_files_of_a_room_import_each_other() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    // Each file's module, and the modules of other files that it names.
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let modules: Vec<Vec<String>> = files.iter().map(|f| module_of(&src, f)).collect();
    let mut uses: Vec<Vec<usize>> = Vec::new();
    for (file, module) in files.iter().zip(&modules) {
        let text = std::fs::read_to_string(file).unwrap();
        let code = without_comments(&text);
        let mut named = Vec::new();
        for path in paths(&tokens(&code)) {
            let target = absolute(&path, module);
            // The file of the longest prefix of the path that is a module of its own.
            let found = (1..=target.len())
                .rev()
                .find_map(|n| modules.iter().position(|m| *m == target[..n]));
            if let Some(other) = found {
                named.push(other);
            }
        }
        uses.push(named);
    }
    // A folder's module and the files in it may use each other; two files side by side
    // may not.
    let inside = |a: &[String], b: &[String]| a.len() < b.len() && b.starts_with(a);
    let mut circles = Vec::new();
    for (a, used) in uses.iter().enumerate() {
        for &b in used {
            if a < b
                && uses[b].contains(&a)
                && !inside(&modules[a], &modules[b])
                && !inside(&modules[b], &modules[a])
            {
                circles.push(format!(
                    "{} <-> {}",
                    modules[a].join("::"),
                    modules[b].join("::")
                ));
            }
        }
    }
    circles.sort();
    circles.dedup();
    assert_eq!(
        circles,
        Vec::<String>::new(),
        "files of a room that import each other"
    );
}

#[test]
fn the_circle_check_reads_groups_and_relative_paths() {
    let code = "use super::{a, b::{c, d}};\nlet x = self::e::f(1);\nuse crate::g::h;";
    let found = paths(&tokens(code));
    let words: Vec<String> = found.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        words,
        [
            "super::a",
            "super::b::c",
            "super::b::d",
            "self::e::f",
            "crate::g::h"
        ]
    );
    let module: Vec<String> = ["run", "store", "error"].map(String::from).to_vec();
    let from_error = |p: &str| {
        let path: Vec<String> = p.split("::").map(String::from).collect();
        absolute(&path, &module).join("::")
    };
    assert_eq!(from_error("super::schema::X"), "run::store::schema::X");
    assert_eq!(from_error("super::super::lock"), "run::lock");
    assert_eq!(from_error("crate::evolve::ga"), "evolve::ga");
}
