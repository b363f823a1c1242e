//! A fitness written as an expression of the task's terms (`fitness = "D_w - 0.5 * drag"`):
//! its value is the one computed by hand from the same evaluation's terms, a named formula
//! keeps its meaning, a bad expression is refused when the config is read (at the value's
//! line and column, with the closest term), it joins the evaluation key, and `eval
//! --fitness`, `evolve` and the run's stored config take it.

use ontogeny::evolve::key::EvaluationKey;
use ontogeny::task::{PROTOCOL_TERMS, Status, TASKS, TaskKind, TaskSpec};

use crate::util::{evolve_config, grown, ontogeny, refused, scratch_dir, succeeded, tiny_run};

/// The walker of `seconds`, its fitness set to `fitness`.
fn walker(fitness: &str, seconds: f64) -> TaskSpec {
    let mut spec = TaskSpec::new(TaskKind::Walker);
    *spec.seconds_mut() = seconds;
    spec.set_fitness(fitness);
    spec.check().unwrap();
    spec
}

#[test]
fn an_expressions_fitness_is_its_value_over_the_terms_the_same_walk_gives() {
    let snake = grown("examples/snake.lsys");
    let e = walker("D_w - 0.5 * drag", 1.0).evaluate(&snake, false);
    assert_eq!(e.status, Status::Ok);
    let (d_w, drag) = (e.terms["D_w"], e.terms["drag"]);
    assert!(d_w > 0.0 && drag > 0.0, "{:?}", e.terms);
    assert_eq!(e.fitness, d_w - 0.5 * drag);
    // The drag is measured as Hornby & Pollack's formula measures it, and that formula
    // keeps its meaning: the same walk, displacement less drag.
    let hornby = walker("hornby-pollack", 1.0).evaluate(&snake, false);
    assert_eq!(hornby.terms, e.terms);
    assert_eq!(hornby.fitness, hornby.terms["displacement"] - drag);
    let distance = walker("distance", 1.0).evaluate(&snake, false);
    assert_eq!(distance.fitness, d_w);
    assert!(!distance.terms.contains_key("drag"));
    // Functions, comparisons and constants, as a rule's parameters write them.
    let e = walker("max(D_w, 0.5) * (N >= 9) + 0 * pi", 1.0).evaluate(&snake, false);
    assert_eq!((e.terms["N"], e.fitness), (9.0, 0.5));
}

#[test]
fn every_term_an_evaluation_gives_is_one_its_task_declares() {
    let thrower = grown("examples/thrower.lsys");
    for info in TASKS {
        let kind: TaskKind = info.name.parse().unwrap();
        let mut spec = TaskSpec::new(kind);
        if !info.throws {
            *spec.seconds_mut() = 2.0;
        }
        if kind == TaskKind::Aim {
            spec.set_fitness("D_p - D_t");
            let catapult = spec.task.get_mut::<ontogeny::task::CatapultOptions>();
            catapult.unwrap().target = Some(nalgebra::Vector3::new(3.0, 0.0, 0.0));
        }
        if kind == TaskKind::Walker {
            spec.set_fitness("D_w - drag");
        }
        spec.check().unwrap();
        let e = spec.evaluate(&thrower, false);
        assert_eq!(e.status, Status::Ok, "{}: {:?}", info.name, e.message);
        for term in e.terms.keys() {
            assert!(
                info.terms.contains(&term.as_str()) || PROTOCOL_TERMS.contains(&term.as_str()),
                "{} gives {term}, which it does not declare",
                info.name
            );
        }
    }
}

#[test]
fn a_value_that_is_not_a_number_is_a_failure_that_says_why() {
    let snake = grown("examples/snake.lsys");
    let e = walker("D_w / (N - N)", 1.0).evaluate(&snake, false);
    assert_eq!((e.status, e.fitness), (Status::Invalid, -999_999.0));
    assert_eq!(
        e.message.as_deref(),
        Some("the fitness expression \"D_w / (N - N)\": division by zero at column 1")
    );
    // The terms stay, to show why.
    assert_eq!(e.terms["N"], 9.0);
    let e = walker("ln(D_w - D_w)", 1.0).evaluate(&snake, false);
    assert_eq!(e.status, Status::Invalid);
    assert_eq!(
        e.message.as_deref(),
        Some("the fitness expression \"ln(D_w - D_w)\": expression gives infinity at column 1")
    );
    // Below the failure floor is no score.
    let e = walker("D_w - 1e9", 1.0).evaluate(&snake, false);
    assert_eq!(e.status, Status::Invalid);
    assert!(
        e.message
            .unwrap()
            .ends_with("at or below the failure floor -999999"),
        "{:?}",
        e.terms
    );
}

/// A config file setting the walker's fitness to `fitness` on its fifth line, at column 11.
fn config_with(name: &str, fitness: &str) -> std::path::PathBuf {
    let dir = scratch_dir(&format!("fitness_expression_{name}"));
    let path = dir.join("walker.toml");
    let text =
        format!("[task]\ntask = \"walker\"\n[task.walker]\nseconds = 1\nfitness = \"{fitness}\"\n");
    std::fs::write(&path, text).unwrap();
    path
}

/// `ontogeny eval FILE ARGS`, whatever its exit code.
fn eval(file: &str, args: &[&str]) -> std::process::Output {
    ontogeny(&[&["eval", file], args].concat())
}

/// Evaluating the snake with `config` (from [`config_with`]) is refused with `message`,
/// pointed at the fitness on its fifth line, column 11.
fn refused_at_the_fitness(config: &std::path::Path, message: &str) {
    let o = eval(
        "examples/snake.lsys",
        &["--config", config.to_str().unwrap()],
    );
    let said = refused(&o, message);
    assert!(
        said.contains(&format!("--> {}:5:11", config.display())),
        "{said}"
    );
}

#[test]
fn an_unknown_term_is_refused_at_its_line_and_column_with_the_closest_term() {
    let config = config_with("unknown", "D_x - 0.5 * drag");
    refused_at_the_fitness(
        &config,
        "error: [task.walker] fitness reads D_x, which is not a term of the walker task (did \
         you mean D_w?); its terms are D_w, C_l, C_s, C_v, N, kappa, settled_at, \
         iterative_move, mass, measured_from, displacement, drag, joint_gap",
    );
    // As an evolution's config, before anything is written.
    let out = config.with_file_name("run");
    let o = evolve_config(&config, &out);
    refused(
        &o,
        "fitness reads D_x, which is not a term of the walker task",
    );
    assert!(!out.exists());
}

#[test]
fn an_expression_that_does_not_parse_is_refused_with_what_was_expected() {
    let config = config_with("syntax", "D_w - * drag");
    refused_at_the_fitness(
        &config,
        "error: [task.walker] fitness \"D_w - * drag\" is not an expression of the walker \
         task's terms: expected a value, found '*' at column 7",
    );
    // A misspelt formula is told the formula it was meant to be.
    let o = eval("examples/snake.lsys", &["--fitness", "hornby-polack"]);
    refused(
        &o,
        "error: --fitness \"hornby-polack\" is not one of the walker task's formulas (did you \
         mean hornby-pollack?) nor an expression of its terms",
    );
}

#[test]
fn eval_fitness_takes_an_expression_for_every_task() {
    let thrower = grown("examples/thrower.lsys");
    let o = eval(
        "examples/thrower.lsys",
        &[
            "--task",
            "jump",
            "--seconds",
            "1",
            "--fitness",
            "2 * height",
            "--json",
        ],
    );
    let printed: serde_json::Value = serde_json::from_str(&succeeded(&o)).unwrap();
    let mut spec = TaskSpec::new(TaskKind::Jump);
    *spec.seconds_mut() = 1.0;
    spec.set_fitness("2 * height");
    let e = spec.evaluate(&thrower, false);
    assert_eq!(e.fitness, 2.0 * e.terms["height"]);
    assert_eq!(printed["fitness"], serde_json::to_value(e.fitness).unwrap());
    assert_eq!(printed["terms"], serde_json::to_value(&e.terms).unwrap());
    // The catapult's terms are not the aim task's.
    let o = eval(
        "examples/thrower.lsys",
        &["--task", "catapult", "--fitness", "D_p - D_t"],
    );
    refused(
        &o,
        "error: --fitness reads D_t, which is not a term of the catapult task (did you mean \
         D_p?)",
    );
}

#[test]
fn two_expressions_give_two_keys_and_an_expression_is_not_its_formula() {
    let snake = grown("examples/snake.lsys");
    let key = |fitness: Option<&str>, kind: TaskKind| {
        let mut spec = TaskSpec::new(kind);
        if let Some(fitness) = fitness {
            spec.set_fitness(fitness);
        }
        EvaluationKey::of(&snake, &spec).to_hex()
    };
    let walker = TaskKind::Walker;
    let keys = [
        key(None, walker),
        key(Some("normalised"), walker),
        key(Some("D_w - 0.5 * drag"), walker),
        key(Some("D_w - 0.25 * drag"), walker),
    ];
    assert_eq!(keys[0], keys[1]);
    assert_ne!(keys[1], keys[2]);
    assert_ne!(keys[2], keys[3]);
    assert_ne!(
        key(None, TaskKind::Jump),
        key(Some("height"), TaskKind::Jump)
    );
    // The keys of specifications without an expression are pinned in `key.rs`.
}

#[test]
fn a_runs_stored_config_keeps_its_expression_and_its_plots_name_it() {
    let dir = scratch_dir("fitness_expression_run");
    let out = dir.join("run");
    let o = tiny_run("direct", &out, &["--fitness", "D_w - 0.5 * drag"]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(said.contains("walker, D_w - 0.5 * drag"), "{said}");
    let config = std::fs::read_to_string(out.join("config.toml")).unwrap();
    assert!(
        config.contains("fitness = \"D_w - 0.5 * drag\""),
        "{config}"
    );
    let _ = std::fs::remove_dir_all(dir);
}
