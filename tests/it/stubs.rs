//! The Python package's type stubs (`python/ontogeny/__init__.pyi`) against the library:
//! the task names and the walker's fitness formulas they spell are the registry's.

use ontogeny::task::{TASKS, Task, WalkerFitness, WalkerTask};

/// The stubs' text.
fn stubs() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/python/ontogeny/__init__.pyi"
    ))
    .unwrap()
}

/// The quoted names of the stubs' `ALIAS = Literal[...]`.
fn literal(stubs: &str, alias: &str) -> Vec<String> {
    let start = stubs
        .find(&format!("\n{alias} = Literal["))
        .unwrap_or_else(|| panic!("no {alias} = Literal[...] in the stubs"));
    let body = &stubs[start..];
    let body = &body[body.find('[').unwrap() + 1..body.find(']').unwrap()];
    body.split(',')
        .map(|name| name.trim().trim_matches('"').to_string())
        .filter(|name| !name.is_empty())
        .collect()
}

#[test]
fn the_stubs_name_the_registrys_tasks_and_the_walkers_formulas() {
    let stubs = stubs();
    let tasks: Vec<&str> = TASKS.iter().map(|t| t.name).collect();
    assert_eq!(literal(&stubs, "_Task"), tasks);
    assert_eq!(literal(&stubs, "_Fitness"), WalkerTask::FITNESS_VARIANTS);
    assert_eq!(
        WalkerFitness::ALL.map(WalkerFitness::name),
        WalkerTask::FITNESS_VARIANTS
    );
    // `evaluate` and `evaluate_many` take a task and a formula of those.
    assert_eq!(stubs.matches("    task: _Task = \"walker\",").count(), 2);
    assert_eq!(
        stubs
            .matches("    fitness: Optional[_Fitness] = None,")
            .count(),
        2
    );
    assert!(stubs.contains("\nTASKS: Dict[str, str]\n"));
}
