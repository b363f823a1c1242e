//! Growing while acting: a creature whose development goes on during the walk
//! (`develop = "during"`).

use std::sync::Arc;

use ontogeny::develop::BuildOptions;
use ontogeny::lsystem::{DeriveOptions, LSystem};
use ontogeny::task::{Growing, Phase, Status, TaskKind, TaskSpec, Watch};

use crate::util::{assert_bad_input, ontogeny, scratch_dir, succeeded};

const EXAMPLE: &str = "examples/grow-while-walking.lsys";

fn example() -> Arc<LSystem> {
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    Arc::new(LSystem::from_text(EXAMPLE, &text).unwrap())
}

/// A 2 s walk.
fn short_walk() -> TaskSpec {
    let mut spec = TaskSpec::new(TaskKind::Walker);
    *spec.seconds_mut() = 2.0;
    spec
}

/// The example evaluated growing from its first valid frame at one unit of developmental
/// time per second, recorded.
fn grown_walk() -> ontogeny::task::Evaluation {
    let mut growing = Growing::start(
        example(),
        &DeriveOptions::default(),
        &BuildOptions::default(),
        1.0,
        None,
    )
    .unwrap();
    let creature = growing.creature().clone();
    short_walk()
        .evaluate_growing(
            &creature,
            Watch::uncancelled(true, &mut |_| {}),
            Some(&mut growing),
        )
        .unwrap()
}

#[test]
fn a_creature_growing_during_the_walk_gains_parts_as_it_walks() {
    let evaluation = grown_walk();
    assert_eq!(evaluation.status, Status::Ok, "{evaluation:?}");
    // Dropped as two segments, it has them at the start of the walk; a pair of legs appears
    // half a second into the walk, another a second in.
    let counts: Vec<(Option<Phase>, usize)> = evaluation
        .recording
        .iter()
        .map(|s| (s.phase, s.parts.len()))
        .collect();
    assert!(
        counts
            .iter()
            .all(|&(phase, n)| phase == Some(Phase::Measuring) || n == 2)
    );
    let walking: Vec<usize> = counts
        .iter()
        .filter(|(phase, _)| *phase == Some(Phase::Measuring))
        .map(|&(_, n)| n)
        .collect();
    assert_eq!(walking.first(), Some(&2));
    assert!(walking.contains(&4));
    assert_eq!(walking.last(), Some(&6));
    assert!(walking.windows(2).all(|w| w[0] <= w[1]));
    assert_eq!(evaluation.terms["grown_parts"], 4.0);
    assert_eq!(evaluation.terms["grown_neurons"], 4.0);
    assert_eq!(evaluation.terms["grown_links"], 4.0);
    // The size terms are the body's at the start of the walk: two parts.
    assert_eq!(evaluation.terms["N"], 2.0);
}

#[test]
fn a_creature_growing_during_the_walk_walks_the_same_twice() {
    assert_eq!(grown_walk(), grown_walk());
}

/// `ontogeny eval` of the example for a 3 s walk, with `extra` flags, as JSON.
fn eval_json(extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["eval", EXAMPLE, "--seconds", "3", "--json"];
    args.extend_from_slice(extra);
    serde_json::from_str(&succeeded(&ontogeny(&args))).unwrap()
}

#[test]
fn eval_with_develop_during_adds_parts_during_the_walk_and_gives_the_same_twice() {
    let grown = eval_json(&["--develop", "during"]);
    assert_eq!(grown["status"], "ok");
    assert_eq!(grown["terms"]["N"], 2.0);
    assert_eq!(grown["terms"]["grown_parts"], 4.0);
    assert_eq!(grown["terms"]["grown_neurons"], 4.0);
    assert_eq!(eval_json(&["--develop", "during"]), grown);
    // From the config's [task] table (a 4 s walk), the same growth.
    let args = [
        "eval",
        EXAMPLE,
        "--config",
        "examples/grow-while-walking.toml",
        "--json",
    ];
    let config: serde_json::Value = serde_json::from_str(&succeeded(&ontogeny(&args))).unwrap();
    assert_eq!(config["terms"]["grown_parts"], 4.0);
    assert_eq!(config["terms"]["N"], 2.0);
}

#[test]
fn eval_with_develop_before_is_today_s_evaluation() {
    let today = eval_json(&[]);
    assert_eq!(eval_json(&["--develop", "before"]), today);
    // The finished creature: six parts from the start, nothing grown.
    assert_eq!(today["terms"]["N"], 6.0);
    assert!(today["terms"].get("grown_parts").is_none());
}

#[test]
fn a_grammar_in_discrete_steps_cannot_grow_during_a_walk() {
    assert_bad_input(
        &["eval", "examples/quadruped.lsys", "--develop", "during"],
        "error: develop = \"during\": examples/quadruped.lsys develops in discrete steps; only \
         continuous development (a `time:` line, or --time) goes on during a walk",
    );
    assert_bad_input(
        &[
            "eval",
            EXAMPLE,
            "--develop",
            "during",
            "--develop-rate",
            "-1",
        ],
        "--develop-rate must be finite and positive, not -1",
    );
}

#[test]
fn a_run_that_would_grow_during_the_walk_is_refused() {
    let out = scratch_dir("grow_while_walking_run");
    let config = out.join("config.toml");
    std::fs::write(
        &config,
        "encoding = \"lsystem-continuous\"\n[ga]\npopulation = 4\ngenerations = 1\n\
         [task]\ntask = \"walker\"\ndevelop = \"during\"\n",
    )
    .unwrap();
    let said = assert_bad_input(
        &[
            "evolve",
            "--config",
            config.to_str().unwrap(),
            "--out",
            out.join("run").to_str().unwrap(),
        ],
        "develop must be \"before\" in a run (only `eval` grows a creature during its \
         evaluation so far), not \"during\"",
    );
    assert!(said.contains("config.toml:7:11"), "{said}");
    assert!(!out.join("run").exists());
}
