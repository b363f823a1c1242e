//! Property tests: no input, however malformed, makes parsing or deriving panic.

use ontogeny::lsystem::{DeriveOptions, LSystem};
use proptest::prelude::*;

/// Parses, checks and derives a few small steps; every outcome but a panic is fine.
fn exercise(text: &str) {
    let Ok(lsys) = LSystem::from_text("prop.lsys", text) else {
        return;
    };
    let _ = lsys.check();
    let options = DeriveOptions {
        seed: Some(1),
        max_modules: 2_000,
        ..DeriveOptions::default()
    };
    let Ok(mut d) = lsys.derivation(&options) else {
        return;
    };
    for _ in 0..4 {
        if let Err(e) = d.step() {
            let _ = e.to_string();
            return;
        }
    }
    let _ = lsys.interpret(d.current(), 4.0, &options);
}

const TOKENS: &[&str] = &[
    "axiom:",
    "derivation length:",
    "define",
    "module",
    "ignore:",
    "seed:",
    "interpretation:",
    "productions:",
    "-->",
    "<",
    ">",
    ":",
    "(",
    ")",
    "[",
    "]",
    ",",
    "\n",
    " ",
    "A",
    "B",
    "F",
    "x",
    "y",
    "t",
    "1",
    "0",
    "2.5",
    "+",
    "-",
    "*",
    "/",
    "^",
    "%",
    "&&",
    "||",
    "!",
    "==",
    "<=",
    "sqrt(",
    "min(",
    "uniform(",
    "normal(",
    "pi",
    "e",
    "?E",
    "{",
    "}",
    "#",
    "forward",
    "=",
    "1e308",
    "0.5",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        exercise(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn token_soup_never_panics(picks in proptest::collection::vec(0..TOKENS.len(), 0..80)) {
        let text: String = picks.iter().map(|&i| TOKENS[i]).collect::<Vec<_>>().join("");
        exercise(&text);
    }

    #[test]
    fn rule_shaped_lines_never_panic(
        lines in proptest::collection::vec(
            (0..TOKENS.len(), 0..TOKENS.len(), 0..TOKENS.len(), 0..TOKENS.len()),
            0..8,
        )
    ) {
        let mut text = String::from("axiom: A(1) B F[+F]\n");
        for (a, b, c, d) in lines {
            text.push_str(&format!(
                "A(x) {} B --> {}({}) {}\n",
                TOKENS[a], TOKENS[b], TOKENS[c], TOKENS[d]
            ));
        }
        exercise(&text);
    }
}
