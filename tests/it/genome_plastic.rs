//! Plastic `lsystem-continuous` genomes: environment reads that make development depend on
//! the chemical array, the operators that make and remove them, and the promise that without
//! them nothing changes.

use ontogeny::encoding::{ContinuousGenome, ContinuousLimits, Genome, Rng};
use rand::SeedableRng;
use sha2::{Digest, Sha256};

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

/// The SHA-256, in hex, of the texts of genomes drawn, mutated and crossed over from seeds
/// 0 to 19 under `limits`.
fn operators_fingerprint(limits: &ContinuousLimits) -> String {
    let mut hasher = Sha256::new();
    for seed in 0..20 {
        let mut r = rng(seed);
        let mut a = ContinuousGenome::random(limits, &mut r);
        let b = ContinuousGenome::random(limits, &mut r);
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
        operators_fingerprint(&ContinuousLimits::default()),
        "8c6812bf4e08c68c7f27a45735c41399cca998f94d7e3d1e5888f692c0b96e60"
    );
}
