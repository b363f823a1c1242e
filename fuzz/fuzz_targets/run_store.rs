//! A run store (`run.sqlite`): the bytes written to a file, opened read-only as `ontogeny
//! runs show` and the viewer open it and read with every reading method, the individuals'
//! genomes read back as the run's encoding reads them (`replay`, `--resume`), then a copy
//! opened for writing as `evolve --resume` opens it (which may migrate it).

#![no_main]

use std::path::{Path, PathBuf};

use libfuzzer_sys::fuzz_target;
use ontogeny::encoding::{ContinuousGenome, DirectGenome, Genome, GraphGenome, LSystemGenome};
use ontogeny::evolve::ga::Individual;
use ontogeny::run::store::{IndividualRecord, RunStore};

/// Generations whose individuals are read (a store may list many).
const MOST_GENERATIONS_READ: usize = 4;

/// A scratch directory of this process, emptied before each input.
fn scratch() -> PathBuf {
    std::env::temp_dir().join(format!("ontogeny-fuzz-run-store-{}", std::process::id()))
}

/// The individual's genome read back as `G` and developed with the default limits, as
/// `replay` does.
fn read_genome<G: Genome>(record: &IndividualRecord) {
    if let Ok(individual) = serde_json::from_str::<Individual<G>>(&record.genome_json) {
        let _ = individual.genome.to_text();
        let _ = individual
            .genome
            .develop(&G::Limits::default(), individual.develop_seed);
    }
}

fn read_individual(encoding: &str, record: &IndividualRecord) {
    match encoding {
        n if n == LSystemGenome::NAME => read_genome::<LSystemGenome>(record),
        n if n == ContinuousGenome::NAME => read_genome::<ContinuousGenome>(record),
        n if n == DirectGenome::NAME => read_genome::<DirectGenome>(record),
        n if n == GraphGenome::NAME => read_genome::<GraphGenome>(record),
        _ => {}
    }
}

/// Every reading method of an open store.
fn read_all(store: &RunStore) {
    let _ = store.schema_version();
    let encoding = match store.run() {
        Ok(run) => run.encoding,
        Err(e) => {
            let _ = e.to_string();
            String::new()
        }
    };
    let last = store.last_generation();
    if let Ok(generations) = store.generations() {
        for g in generations.iter().take(MOST_GENERATIONS_READ) {
            if let Ok(individuals) = store.individuals(g.index) {
                let _ = individuals.len();
            }
        }
    }
    if let Ok(Some(g)) = last {
        let _ = store.individuals(g);
    }
    match store.best_individual() {
        Ok(Some(best)) => read_individual(&encoding, &best),
        Ok(None) => {}
        Err(e) => {
            let _ = e.to_string();
        }
    }
}

fn fuzz_store(dir: &Path, data: &[u8]) {
    let path = dir.join("run.sqlite");
    if std::fs::write(&path, data).is_err() {
        return;
    }
    match RunStore::open_read_only(&path) {
        Ok(store) => read_all(&store),
        Err(e) => {
            let _ = e.to_string();
        }
    }
    // The file is left as it was.
    assert_eq!(
        std::fs::read(&path).ok().as_deref(),
        Some(data),
        "open_read_only changed the file"
    );
    let copy = dir.join("copy.sqlite");
    if std::fs::write(&copy, data).is_err() {
        return;
    }
    match RunStore::open(&copy) {
        Ok(store) => read_all(&store),
        Err(e) => {
            let _ = e.to_string();
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let dir = scratch();
    let _ = std::fs::remove_dir_all(&dir);
    if std::fs::create_dir_all(&dir).is_err() {
        return;
    }
    fuzz_store(&dir, data);
    let _ = std::fs::remove_dir_all(&dir);
});
