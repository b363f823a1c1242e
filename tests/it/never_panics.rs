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
    if lsys.is_continuous() {
        develop(&lsys);
        return;
    }
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

/// Develops a continuous-time grammar for at most two time units and eight frames, with a
/// small work budget; every outcome but a panic is fine.
fn develop(lsys: &LSystem) {
    let options = DeriveOptions {
        seed: Some(1),
        max_modules: 2_000,
        time: Some(lsys.time().unwrap_or(1.0).clamp(0.0, 2.0)),
        dt: Some(0.25),
        max_work: 200_000,
        ..DeriveOptions::default()
    };
    let Ok(mut dev) = lsys.development(&options) else {
        return;
    };
    for _ in 0..8 {
        match dev.advance() {
            Ok(true) => {
                let _ = lsys.interpret(dev.current(), dev.time(), &options);
            }
            Ok(false) => return,
            Err(e) => {
                let _ = e.to_string();
                return;
            }
        }
    }
}

/// Pieces of continuous-time rules: guards, rates and successors.
const CONTINUOUS: &[&str] = &[
    "x",
    "t",
    "1",
    "0",
    "-1",
    "0.5",
    "2",
    "1e308",
    "x * x",
    "1 / x",
    "x - t",
    "sqrt(x)",
    "-x",
    "uniform(0, 1)",
    "x < 1",
    "x >= 1",
    "x > 0.3 && x < 0.6",
    "t > 0.5",
    "?E(x)",
    "A(x)",
    "X(0)",
    "X(x) X(x)",
    "forward(x)",
    "mforward(x)",
    "[ X(0) ]",
    "",
    "(",
];

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
    "time:",
    "dt:",
    "timing:",
    "solve",
    "dx/dt",
    "mforward",
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

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn continuous_rule_shaped_lines_never_panic(
        timing in 0..2usize,
        lines in proptest::collection::vec(
            (0..CONTINUOUS.len(), 0..CONTINUOUS.len(), 0..CONTINUOUS.len()),
            1..5,
        )
    ) {
        let mut text = format!(
            "time: 2\ndt: 0.5\ntiming: {}\nenvironment: 0 0\naxiom: X(0) [ A(1) ] mforward(0)\n",
            ["exact", "iterative"][timing]
        );
        for (guard, rate, successor) in lines {
            text.push_str(&format!(
                "X(x) : {} --> solve dx/dt = {}\nX(x) --> {}\nA(x) : {} --> {}\n\
                 mforward(x) --> solve dx/dt = {}\n",
                CONTINUOUS[guard], CONTINUOUS[rate], CONTINUOUS[successor],
                CONTINUOUS[rate], CONTINUOUS[successor], CONTINUOUS[rate]
            ));
        }
        exercise(&text);
    }
}
