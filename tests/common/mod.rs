//! Helpers shared by the integration tests.
#![allow(dead_code)]

use ontogeny::creature::Creature;
use ontogeny::develop::{BuildOptions, grow};
use ontogeny::lsystem::{DeriveOptions, LSystem};

/// Compiles `text`, panicking with the rendered diagnostic on failure.
pub fn lsystem(text: &str) -> LSystem {
    LSystem::from_text("test.lsys", text).unwrap_or_else(|e| panic!("{e}"))
}

/// The readable strings of steps 0..=steps, with spaces removed.
pub fn derive(text: &str, steps: usize) -> Vec<String> {
    derive_with(text, steps, &DeriveOptions::default())
}

/// As [`derive`], with options.
pub fn derive_with(text: &str, steps: usize, options: &DeriveOptions) -> Vec<String> {
    let lsys = lsystem(text);
    let mut d = lsys.derivation(options).unwrap_or_else(|e| panic!("{e}"));
    let mut out = vec![squash(&lsys.display(d.current()))];
    for _ in 0..steps {
        let s = d.step().unwrap_or_else(|e| panic!("{e}"));
        out.push(squash(&lsys.display(s)));
    }
    out
}

/// Removes white space, so that expected strings can be written either way.
pub fn squash(s: &str) -> String {
    s.chars().filter(|c| !c.is_whitespace()).collect()
}

/// The creature a shipped example grows into (its last frame).
pub fn grown(path: &str) -> Creature {
    let lsys = LSystem::from_path(std::path::Path::new(path)).unwrap();
    let frames = grow(
        &lsys,
        &DeriveOptions::default(),
        None,
        &BuildOptions::default(),
    )
    .unwrap();
    frames.into_iter().last().unwrap().creature
}

/// The last creature `develop::grow` makes from `text` with a module and a part cap (what
/// `ontogeny grow --max-modules --max-parts` does).
pub fn grown_with_caps(text: &str, max_modules: usize, max_parts: usize) -> Creature {
    let lsys = lsystem(text);
    let options = DeriveOptions {
        max_modules,
        ..DeriveOptions::default()
    };
    let build = BuildOptions {
        max_parts,
        ..BuildOptions::default()
    };
    grow(&lsys, &options, None, &build)
        .unwrap_or_else(|e| panic!("{e}"))
        .pop()
        .expect("a frame")
        .creature
}
