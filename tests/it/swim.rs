//! The swim task in water: its fitness is the distance of the centre of mass, a creature with
//! no controller stays where it is, water is the swim task's medium alone, and a tiny
//! evolution of swimmers runs from the example config.

use crate::util::{assert_bad_input, ontogeny_ok, scratch_dir, stdout};

/// `eval ARGS --json`, parsed.
fn eval_json(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["eval"];
    all.extend_from_slice(args);
    all.push("--json");
    serde_json::from_slice(&ontogeny_ok(&all).stdout).unwrap()
}

#[test]
fn the_snake_swims_a_little_in_water_of_the_default_viscosity() {
    let e = eval_json(&["examples/snake.lsys", "--task", "swim"]);
    assert_eq!(e["status"], "ok", "{e}");
    assert_eq!(e["terms"]["viscosity"], 500.0);
    assert_eq!(e["terms"]["N"], 9.0);
    let distance = e["fitness"].as_f64().unwrap();
    assert_eq!(e["terms"]["distance"].as_f64(), Some(distance));
    assert!((distance - SNAKE_SWIMS).abs() < 1e-4, "{distance}");
}

/// How far the snake's centre of mass moves in 20 s of swimming (m).
const SNAKE_SWIMS: f64 = 0.768971;

#[test]
fn a_creature_without_a_controller_stays_where_it_is() {
    let dir = scratch_dir("swim-still");
    let file = dir.join("box.lsys");
    std::fs::write(&file, "axiom: forward(1) revolute2 forward(1)\n").unwrap();
    let e = eval_json(&[file.to_str().unwrap(), "--task", "swim", "--seconds", "2"]);
    assert_eq!(e["status"], "ok", "{e}");
    assert_eq!(e["fitness"], 0.0);
}

#[test]
fn water_is_the_swim_task_s_medium_alone_and_its_viscosity_in_range() {
    let dir = scratch_dir("swim-refused");
    let config = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let walker = config(
        "walker.toml",
        "[task]\ntask = \"walker\"\n[task.world]\nmedium = { kind = \"water\", viscosity = 500 }\n",
    );
    assert_bad_input(
        &[
            "evolve",
            "--config",
            &walker,
            "--out",
            dir.join("a").to_str().unwrap(),
        ],
        "[task.world] medium must be air for the walker task (water is the swim task's), not water",
    );
    let thick = config(
        "thick.toml",
        "[task]\ntask = \"swim\"\n[task.world]\nmedium = { kind = \"water\", viscosity = 0 }\n",
    );
    assert_bad_input(
        &[
            "evolve",
            "--config",
            &thick,
            "--out",
            dir.join("b").to_str().unwrap(),
        ],
        "[task.world.medium] viscosity must be in (0, 10000] N·s/m³, not 0",
    );
    let sloped = config(
        "sloped.toml",
        "[task]\ntask = \"swim\"\n[task.world]\nmedium = { kind = \"water\", viscosity = 500 }\n\
         slope = { degrees = 5 }\n",
    );
    assert_bad_input(
        &[
            "evolve",
            "--config",
            &sloped,
            "--out",
            dir.join("c").to_str().unwrap(),
        ],
        "[task.world] medium must be alone: water has no ground, so no slope, steps, rough, \
         obstacles, objects or friction, not water in a world with them",
    );
    assert!(!dir.join("a").exists() && !dir.join("b").exists() && !dir.join("c").exists());
}

#[test]
fn the_swim_example_evolves_a_tiny_population() {
    let out = scratch_dir("swim-evolve").join("run");
    let o = ontogeny_ok(&[
        "evolve",
        "--config",
        "examples/swim.toml",
        "--pop",
        "4",
        "--gens",
        "1",
        "--seconds",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    let said = stdout(&o);
    assert!(said.contains("swim"), "{said}");
    let best = out.join("best.lsys");
    let e = eval_json(&[best.to_str().unwrap()]);
    assert_eq!(e["task"], "swim", "{e}");
    assert_eq!(e["terms"]["viscosity"], 500.0);
}
