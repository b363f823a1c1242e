//! A run with habitats in the viewer: `--habitat NAME` shows its individuals developed in that
//! habitat and plays their walks in its world, an unknown name is refused listing the
//! habitats, and the run page's data (and `fitness.svg`) carry the spread of each generation's
//! best over its walks — which a run without habitats lacks.

use super::server::{get_json, tiny_run};
use super::*;

/// A run of 4 direct walkers for 2 generations, in two habitats (`level`, and `hill` sloping
/// 10°), two trials each with start noise.
fn habitat_run(name: &str) -> PathBuf {
    let dir = scratch(name);
    let config = dir.join("habitats.toml");
    std::fs::write(
        &config,
        "encoding = \"direct\"\nseed = 3\n\n[ga]\npopulation = 4\ngenerations = 2\n\n\
         [task]\ntask = \"walker\"\n\n[task.walker]\nseconds = 0.5\n\n\
         [task.trials]\ncount = 2\noffset = 0.2\n\n\
         [[task.habitats]]\nname = \"level\"\n\n\
         [[task.habitats]]\nname = \"hill\"\n[task.habitats.world]\nslope = { degrees = 10 }\n",
    )
    .unwrap();
    let run = dir.join("run");
    let out = evolve_config(&config, &run);
    succeeded(&out);
    run
}

/// The stored walks of the best individual (rank 1) of `generation`: (habitat, trial,
/// fitness, parts) each.
fn best_walks(run: &Path, generation: u32) -> Vec<(String, u64, f64, u64)> {
    let store = ontogeny::run::store::RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    let individuals = store.individuals(generation).unwrap();
    let best = ontogeny::evolve::ga::ranking_by(&individuals, |i| i.fitness)[0];
    let json: serde_json::Value = serde_json::from_str(&individuals[best].genome_json).unwrap();
    json["evaluation"]["habitats"]
        .as_array()
        .unwrap()
        .iter()
        .map(|u| {
            (
                u["name"].as_str().unwrap().to_string(),
                u["trial"].as_u64().unwrap(),
                u["fitness"].as_f64().unwrap(),
                u["parts"].as_u64().unwrap(),
            )
        })
        .collect()
}

#[test]
fn view_habitat_shows_and_walks_the_runs_individuals_in_that_habitat() {
    let run = habitat_run("habitat-walk");
    let walks = best_walks(&run, 1);
    assert_eq!(walks.len(), 4, "{walks:?}");
    let first_trial = |name: &str| {
        walks
            .iter()
            .find(|w| w.0 == name && w.1 == 0)
            .unwrap()
            .clone()
    };
    let viewer = Viewer::start_with(&run, &["--habitat", "hill"]);
    let table = get_json(&viewer, "/generation.json?gen=1");
    let best = &table["individuals"][0];
    let walk = get_json(&viewer, "/walk.json?gen=1&rank=1");
    assert_eq!(walk["habitat"], "hill");
    // The walk is the hill's first trial, as the run walked it; the stored fitness is the
    // aggregate of all four.
    assert_eq!(walk["fitness"].as_f64(), Some(first_trial("hill").2));
    assert_eq!(walk["stored_fitness"], best["fitness"]);
    let index = best["index"].as_u64().unwrap();
    let one = get_json(&viewer, &format!("/individual.json?gen=1&index={index}"));
    assert_eq!(one["habitat"], "hill");
    assert_eq!(
        one["frames"][0]["creature"]["parts"]
            .as_array()
            .unwrap()
            .len() as u64,
        first_trial("hill").3
    );
    drop(viewer);
    // Without --habitat: the first habitat.
    let viewer = Viewer::start(&run);
    let walk = get_json(&viewer, "/walk.json?gen=1&rank=1");
    assert_eq!(walk["habitat"], "level");
    assert_eq!(walk["fitness"].as_f64(), Some(first_trial("level").2));
    let one = get_json(&viewer, &format!("/individual.json?gen=1&index={index}"));
    assert_eq!(one.get("habitat"), None);
}

#[test]
fn view_habitat_with_a_name_the_run_lacks_is_refused_listing_its_habitats() {
    let run = habitat_run("habitat-unknown");
    assert_bad_input(
        &["view", run.to_str().unwrap(), "--habitat", "marsh"],
        "no habitat 'marsh'; the habitats are level, hill",
    );
    // A run without habitats has none to name.
    let plain = tiny_run("habitat-plain");
    assert_bad_input(
        &["view", plain.to_str().unwrap(), "--habitat", "level"],
        "no habitat 'level': the task has no [[task.habitats]]",
    );
}

#[test]
fn the_run_page_and_plot_of_a_run_with_habitats_show_the_spread_of_the_best() {
    let run = habitat_run("habitat-spread");
    let viewer = Viewer::start(&run);
    let data = get_json(&viewer, "/data.json");
    for g in 0..2 {
        let fitnesses: Vec<f64> = best_walks(&run, g).iter().map(|w| w.2).collect();
        let low = fitnesses.iter().copied().fold(f64::INFINITY, f64::min);
        let high = fitnesses.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let shown = &data["generations"][g as usize];
        assert_eq!(
            (shown["spread_low"].as_f64(), shown["spread_high"].as_f64()),
            (Some(low), Some(high)),
            "generation {g}"
        );
    }
    let svg = std::fs::read_to_string(run.join("fitness.svg")).unwrap();
    assert!(
        svg.lines()
            .any(|l| l.trim() == ontogeny::run::plot::SPREAD_LABEL)
    );
    // A run without habitats: no spread, the plain plot.
    let plain = tiny_run("habitat-spread-plain");
    let viewer = Viewer::start(&plain);
    let data = get_json(&viewer, "/data.json");
    assert_eq!(data["generations"][0].get("spread_low"), None);
    let svg = std::fs::read_to_string(plain.join("fitness.svg")).unwrap();
    assert!(!svg.contains(ontogeny::run::plot::SPREAD_LABEL));
    assert!(svg.lines().any(|l| l.trim() == "best"));
}
