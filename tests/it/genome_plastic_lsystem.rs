//! Plastic `lsystem` genomes (Hornby & Pollack's): productions that read the chemical array
//! and branch on the value read, the operators that make and remove them, the promise that
//! without them nothing changes, and `genome show --habitats`.

use ontogeny::encoding::{Genome, LSystemGenome, LSystemLimits, Rng};
use rand::SeedableRng;
use sha2::{Digest, Sha256};

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

/// The SHA-256, in hex, of the texts and JSON of genomes drawn, mutated and crossed over
/// from seeds 0 to 19 under `limits`.
fn operators_fingerprint(limits: &LSystemLimits) -> String {
    let mut hasher = Sha256::new();
    for seed in 0..20 {
        let mut r = rng(seed);
        let mut a = LSystemGenome::random(limits, &mut r);
        let b = LSystemGenome::random(limits, &mut r);
        for _ in 0..20 {
            a = a.mutate(limits, 0.3, &mut r);
            a = a.crossover(&b, limits, &mut r).unwrap();
            hasher.update(a.to_text().as_bytes());
            hasher.update(serde_json::to_string(&a).unwrap().as_bytes());
        }
    }
    hasher
        .finalize()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

#[test]
fn without_environment_reads_the_operators_draw_what_they_drew_before_reads_existed() {
    // The fingerprint of the operators as they were before genomes could read their
    // environment: the default must reproduce it to the bit.
    assert_eq!(
        operators_fingerprint(&LSystemLimits::default()),
        "f2d30153db4574827ef54bd535a1688a75ec4565a6c90df0f77fb8492e96337a"
    );
}
