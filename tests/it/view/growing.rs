//! A recording of a body that grows during the walk, served to the page: the frames with
//! their growth, and the body with every part that appears, for which the page makes meshes.

use super::Viewer;
use super::server::get_json;
use crate::growing_shown::{growing_recording, old_recording};

#[test]
fn the_served_recording_of_a_growing_walk_carries_the_parts_that_appear() {
    let rec = growing_recording("view");
    let viewer = Viewer::start(&rec);
    let data = get_json(&viewer, "/data.json");
    assert_eq!(data["kind"], "recording");
    // Dropped as three parts; the body has the fifteen there are at the end, each jointed.
    assert_eq!(data["creature"]["parts"].as_array().unwrap().len(), 3);
    assert_eq!(data["body"]["parts"].as_array().unwrap().len(), 15);
    assert_eq!(data["body"]["joints"].as_array().unwrap().len(), 14);
    let frames = data["frames"].as_array().unwrap();
    let appears: Vec<(usize, u64)> = frames
        .iter()
        .enumerate()
        .flat_map(|(i, f)| {
            f["growth"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(move |c| Some((i, c["appears"]["part"].as_u64()?)))
        })
        .collect();
    assert_eq!(
        appears.iter().map(|&(_, p)| p).collect::<Vec<_>>(),
        (3..15).collect::<Vec<u64>>()
    );
    for (i, part) in appears {
        // The frame a part appears in is the first to pose it.
        let posed = |i: usize| frames[i]["parts"].as_array().unwrap().len() as u64;
        assert!(
            posed(i) > part && posed(i - 1) <= part,
            "part {part}, frame {i}"
        );
    }
    // A recording of a body that does not grow is served as before: no body.
    let old = Viewer::start(&old_recording("view"));
    let data = get_json(&old, "/data.json");
    assert!(data.get("body").is_none());
    assert_eq!(data["frames"].as_array().unwrap().len(), 72);
}

#[test]
fn the_walk_of_a_run_s_individual_growing_in_habitats_is_its_stored_walk_growing() {
    let dir = super::scratch("growing-habitats");
    let config = crate::grow_while_walking::growing_habitats_config(&dir);
    let run = dir.join("run");
    crate::util::evolve(&config, &run, &[]);
    let store = ontogeny::run::store::RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    let individuals = store.individuals(1).unwrap();
    let best = ontogeny::evolve::ga::ranking_by(&individuals, |i| i.fitness)[0];
    let json: serde_json::Value = serde_json::from_str(&individuals[best].genome_json).unwrap();
    let stored = json["evaluation"]["habitats"]
        .as_array()
        .unwrap()
        .iter()
        .find(|u| u["name"] == "rich" && u["trial"] == 0)
        .unwrap()
        .clone();
    let viewer = Viewer::start_with(&run, &["--habitat", "rich"]);
    let walk = get_json(&viewer, "/walk.json?gen=1&rank=1");
    assert_eq!(walk["habitat"], "rich");
    // The rich habitat's first trial, as the run walked it: growing, on the run's draws.
    assert_eq!(walk["fitness"], stored["fitness"]);
    let grown = stored["terms"]["grown_parts"].as_f64().unwrap() as usize;
    let parts = |key: &str| walk[key]["parts"].as_array().unwrap().len();
    assert_eq!(parts("body"), parts("creature") + grown, "{walk}");
}
