//! A graph genome's JSON (a graph run's `best.json`), read as `ontogeny genome show`,
//! `eval` and `export` read it (`GraphGenome::from_text` with the default limits), described,
//! developed, written back as text, and its creature built into a rapier world and stepped.

#![no_main]

use libfuzzer_sys::fuzz_target;
use ontogeny::encoding::{Genome, GraphGenome, GraphLimits};
use ontogeny::sim::{SimOptions, World};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let limits = GraphLimits::default();
    let genome = match GraphGenome::from_text(text, &limits) {
        Ok(g) => g,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    let _ = genome.describe();
    let creature = genome.creature(limits.max_parts);
    let _ = creature.is_valid();
    match genome.develop(&limits, 0) {
        Ok(developed) => assert_eq!(developed.parts.len(), creature.parts.len()),
        Err(e) => panic!("a checked genome does not develop: {e}"),
    }
    // The text form reads back as the same genome.
    let written = genome.to_text();
    let again = GraphGenome::from_text(&written, &limits).expect("to_text reads back");
    assert_eq!(again.to_text(), written);
    if creature.check_consistency().is_err() {
        return;
    }
    let options = SimOptions::default();
    let Ok(mut world) = World::new(&creature, &options) else {
        return;
    };
    for _ in 0..3 {
        if world.step(true).is_err() {
            return;
        }
    }
});
