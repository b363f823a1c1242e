//! A damaged record is never used: every row carries a checksum verified when it is read,
//! every generation the count of its individuals; a flipped bit anywhere in a stored genome
//! is refused naming the record, a flip anywhere else in the file is refused or changes
//! nothing read; a resume from a damaged store exits 2 and writes nothing; a run is not
//! resumed under another evaluator version unless asked to, and then the store records
//! where the version changes.

use std::process::Output;

use ontogeny::evolve::evaluator_version::EVALUATOR_VERSION;
use rand::{RngExt, SeedableRng};

use super::*;
use crate::util::{ontogeny_command, refused, succeeded, tiny_run};

/// Everything the store's reads give (what a resume, `replay`, the viewer and Python's `Run`
/// read), as one comparable text; the first error instead, if a read fails.
fn everything(store: &RunStore) -> Result<String, StoreError> {
    let generations = store.generations()?;
    let mut out = format!(
        "{:?}\n{generations:?}\n{:?}\n",
        store.run()?,
        store.evaluators()?
    );
    for g in &generations {
        out.push_str(&format!("{:?}\n", store.individuals(g.index)?));
    }
    out.push_str(&format!(
        "{:?}\n{:?}\n{:?}\n{:?}\n{:?}\n{:?}\n",
        store.last_generation()?,
        store.best_individual()?,
        store.keys()?,
        store.evaluations_by_key()?,
        store.reused_by_generation()?,
        store.individuals_made_by("mutation")?,
    ));
    Ok(out)
}

/// [`everything`] of the store at `path`, opened read-only.
fn read_all(path: &Path) -> Result<String, StoreError> {
    everything(&RunStore::open_read_only(path)?)
}

/// A tiny finished run in `dir/run` (direct walkers, 6 individuals, 2 generations), its
/// store folded into one file.
fn finished_run(dir: &Path) -> PathBuf {
    let run = dir.join("run");
    tiny_run("direct", &run, &[]);
    assert!(!run.join("run.sqlite-wal").exists());
    run
}

/// Where, in `bytes`, individual 2 of generation 1's genome names its development seed:
/// the offset of the text `"develop_seed":` and of the digits after it.
fn develop_seed_at(path: &Path, bytes: &[u8]) -> (usize, usize) {
    let store = RunStore::open_read_only(path).unwrap();
    let json = store.individuals(1).unwrap()[2].genome_json.clone();
    let at = json.find("\"develop_seed\":").unwrap();
    let end = json[at + 15..].find(|c: char| !c.is_ascii_digit()).unwrap() + at + 15;
    let needle = &json.as_bytes()[at..end];
    let offset = bytes
        .windows(needle.len())
        .position(|w| w == needle)
        .expect("the genome is stored as it is");
    (offset, offset + needle.len())
}

#[test]
fn every_bit_flipped_in_a_stored_genome_is_refused_naming_the_record() {
    let dir = scratch("flip-genome");
    let run = finished_run(&dir);
    let path = run.join("run.sqlite");
    let clean = fs::read(&path).unwrap();
    let (start, end) = develop_seed_at(&path, &clean);
    let copy = dir.join("copy.sqlite");
    for byte in start..end {
        for bit in 0..8 {
            let mut bytes = clean.clone();
            bytes[byte] ^= 1 << bit;
            fs::write(&copy, &bytes).unwrap();
            let err = read_all(&copy).unwrap_err();
            let message = err.to_string();
            assert!(
                matches!(err, StoreError::Damaged { .. }),
                "byte {byte} bit {bit}: {err:?}"
            );
            assert!(
                message.contains("the record of individual 2 of generation 1 is damaged"),
                "{message}"
            );
            // Opened to be written (a resume), it is refused before anything is written.
            let err = RunStore::open(&copy).unwrap_err();
            assert!(matches!(err, StoreError::Damaged { .. }), "{err:?}");
            assert_eq!(fs::read(&copy).unwrap(), bytes, "byte {byte} bit {bit}");
        }
    }
    let _ = fs::remove_dir_all(dir);
}

#[test]
fn two_hundred_bits_flipped_anywhere_in_the_file_are_refused_or_change_nothing_read() {
    let dir = scratch("flip-anywhere");
    let run = finished_run(&dir);
    let path = run.join("run.sqlite");
    let clean = fs::read(&path).unwrap();
    let expected = read_all(&path).unwrap();
    let copy = dir.join("copy.sqlite");
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2024);
    let (mut refused, mut unchanged) = (0, 0);
    for _ in 0..200 {
        let mut bytes = clean.clone();
        let byte = rng.random_range(0..bytes.len());
        let bit = rng.random_range(0..8);
        bytes[byte] ^= 1 << bit;
        fs::write(&copy, &bytes).unwrap();
        match read_all(&copy) {
            Err(_) => refused += 1,
            Ok(read) => {
                assert_eq!(read, expected, "byte {byte} bit {bit} was read as data");
                unchanged += 1;
            }
        }
        // A resume's open either refuses it or reads exactly the clean records.
        if let Ok(store) = RunStore::open(&copy) {
            assert_eq!(
                everything(&store).unwrap(),
                expected,
                "byte {byte} bit {bit}"
            );
        }
    }
    assert_eq!(refused + unchanged, 200);
    let _ = fs::remove_dir_all(dir);
}

/// Every file of `dir` but its lock, each named with its length and a digest of its bytes.
fn files(dir: &Path) -> Vec<String> {
    use sha2::{Digest, Sha256};
    let mut out: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().unwrap() != ".lock")
        .map(|p| {
            let bytes = fs::read(&p).unwrap();
            let digest = Sha256::digest(&bytes);
            format!("{}: {} bytes, {digest:x}", p.display(), bytes.len())
        })
        .collect();
    out.sort();
    out
}

/// `ontogeny evolve --resume DIR --gens GENS EXTRA...`.
fn extend(dir: &Path, gens: &str, extra: &[&str]) -> Output {
    ontogeny_command()
        .args(["evolve", "--gens", gens])
        .args(extra)
        .arg("--resume")
        .arg(dir)
        .output()
        .unwrap()
}

#[test]
fn a_resume_from_a_damaged_genome_exits_2_naming_the_record_and_writes_nothing() {
    let dir = scratch("damaged-resume");
    let run = finished_run(&dir);
    let path = run.join("run.sqlite");
    let mut bytes = fs::read(&path).unwrap();
    // One digit of the development seed, one bit away: still a number, still JSON.
    let (_, end) = develop_seed_at(&path, &bytes);
    bytes[end - 1] ^= 1;
    assert!(bytes[end - 1].is_ascii_digit());
    fs::write(&path, &bytes).unwrap();
    let before = files(&run);
    let said = refused(
        &extend(&run, "3", &[]),
        "run.sqlite: the record of individual 2 of generation 1 is damaged (it does not match the checksum stored with it)",
    );
    assert!(said.contains("nothing was used or written"), "{said}");
    assert_eq!(files(&run), before);
    // Reading it is refused the same way: the replay of its last generation's best.
    let replay = ontogeny_command()
        .args(["replay", "--gen", "1"])
        .arg(&run)
        .output()
        .unwrap();
    refused(&replay, "individual 2 of generation 1 is damaged");
    assert_eq!(files(&run), before);
    let _ = fs::remove_dir_all(dir);
}

#[test]
fn a_generation_that_lost_an_individual_or_whose_record_was_edited_is_refused() {
    let dir = scratch("lost-row");
    let path = finished_store(&dir);
    {
        let conn = rusqlite::Connection::open(&path).unwrap();
        conn.execute_batch("DELETE FROM individual WHERE generation = 1 AND individual = 3")
            .unwrap();
    }
    let store = RunStore::open_read_only(&path).unwrap();
    let err = store.individuals(1).unwrap_err().to_string();
    assert!(
        err.ends_with(
            "run.sqlite: the record of generation 1 is damaged (it holds 3 individuals where its record says 4); nothing was used or written: the run cannot go on from it (a copy made before the damage can)"
        ),
        "{err}"
    );
    assert_eq!(store.individuals(0).unwrap().len(), 4);
    drop(store);
    assert!(matches!(
        RunStore::open(&path),
        Err(StoreError::Damaged { .. })
    ));
    // A value changed by hand, without its checksum: the run row, a generation's.
    for (edit, what) in [
        ("UPDATE run SET config = config || '#'", "the run"),
        (
            "UPDATE generation SET best = 99 WHERE generation = 0",
            "generation 0",
        ),
    ] {
        let path = finished_store(&scratch(&format!("edited-{what}")));
        rusqlite::Connection::open(&path)
            .unwrap()
            .execute_batch(edit)
            .unwrap();
        let err = read_all(&path).unwrap_err().to_string();
        assert!(
            err.contains(&format!("the record of {what} is damaged")),
            "{err}"
        );
    }
    let _ = fs::remove_dir_all(dir);
}

#[test]
fn a_run_made_by_another_evaluator_version_resumes_only_when_allowed_and_records_the_change() {
    let dir = scratch("evaluator");
    let run = dir.join("run");
    let output = crate::util::evolve_walkers("direct", "6")
        .args(["--gens", "1", "--seconds", "1", "--out"])
        .arg(&run)
        .output()
        .unwrap();
    succeeded(&output);
    // Generation 1 as another evaluator version would have stored it.
    let newer = EVALUATOR_VERSION + 1;
    {
        let mut store = RunStore::open(&run.join("run.sqlite")).unwrap();
        store.set_evaluator_version(newer);
        let g0 = store.generations().unwrap().remove(0);
        let is: Vec<IndividualRecord> = store
            .individuals(0)
            .unwrap()
            .into_iter()
            .map(|i| IndividualRecord { generation: 1, ..i })
            .collect();
        store
            .write_generation(&GenerationRecord { index: 1, ..g0 }, &is)
            .unwrap();
    }
    let before = files(&run);
    let said = refused(
        &extend(&run, "3", &[]),
        &format!(
            "its last generation (1) was evaluated by evaluator version {newer}, and this ontogeny evaluates with version {EVALUATOR_VERSION}"
        ),
    );
    assert!(said.contains("--allow-evaluator-change"), "{said}");
    assert_eq!(files(&run), before);
    succeeded(&extend(&run, "3", &["--allow-evaluator-change"]));
    let store = RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    assert_eq!(
        store.evaluators().unwrap(),
        [(0, EVALUATOR_VERSION), (1, newer), (2, EVALUATOR_VERSION)]
    );
    // The flag belongs to a resume: a new run refuses it, before anything is made.
    let alone = crate::util::evolve_walkers("direct", "6")
        .args([
            "--gens",
            "1",
            "--seconds",
            "1",
            "--allow-evaluator-change",
            "--out",
        ])
        .arg(dir.join("new"))
        .output()
        .unwrap();
    refused(&alone, "--allow-evaluator-change goes with --resume");
    assert!(!dir.join("new").exists());
    let _ = fs::remove_dir_all(dir);
}
