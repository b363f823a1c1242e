//! A `creature.json`, read as `ontogeny eval` and `ontogeny export` read it (serde, then
//! `Creature::check_consistency`), exported to MJCF, then built into a rapier world and
//! stepped a few control steps (where NaN and huge numbers would panic).

#![no_main]

use libfuzzer_sys::fuzz_target;
use ontogeny::creature::Creature;
use ontogeny::export::mjcf::to_mjcf;
use ontogeny::sim::{SimOptions, World};

/// More parts than this are read and checked but not simulated, to keep an execution to
/// milliseconds (libFuzzer's default inputs of at most 4 KB hold fewer anyway).
const MOST_PARTS_SIMULATED: usize = 64;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // A JSON object with `nodes` is a graph genome (the `graph_genome` target).
    if serde_json::from_str::<serde_json::Value>(text).is_ok_and(|v| v.get("nodes").is_some()) {
        return;
    }
    let creature: Creature = match serde_json::from_str(text) {
        Ok(c) => c,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    if let Err(problem) = creature.check_consistency() {
        let _ = problem.to_string();
        return;
    }
    let _ = creature.is_valid();
    let options = SimOptions::default();
    let _ = to_mjcf(&creature, &options, "fuzz");
    if creature.parts.len() > MOST_PARTS_SIMULATED {
        return;
    }
    let mut world = match World::new(&creature, &options) {
        Ok(w) => w,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    world.set_resting(true);
    for _ in 0..2 {
        if world.step(false).is_err() {
            return;
        }
    }
    world.set_resting(false);
    for _ in 0..3 {
        if world.step(true).is_err() {
            return;
        }
    }
    let _ = (
        world.lowest_point(),
        world.highest_point(),
        world.creature_mass(),
    );
    for id in world.part_ids() {
        let _ = world.part_pose(id);
    }
});
