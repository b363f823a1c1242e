//! Continuous development throughput: 10,000 simultaneously growing modules developed over
//! 10 time units with dt = 0.1 (the floor: under one second on one core), and the 1000 random
//! `lsystem-continuous` genomes of seeds 0–999 developed one after another (the genomes whose
//! walker-ready fraction `tests/it/genome_continuous.rs` asserts).
//! Run with `cargo bench --bench develop`.

use criterion::{Criterion, criterion_group, criterion_main};
use ontogeny::encoding::{ContinuousGenome, ContinuousLimits, Genome, Rng};
use ontogeny::lsystem::{DeriveOptions, LSystem};
use rand::SeedableRng;

/// 10,000 modules that grow linearly; each reaching length 1 lays down a segment `F` and
/// starts again, so every time unit brings an event that rewrites all of them.
fn growing_modules(count: usize) -> LSystem {
    let axiom = "A(0) ".repeat(count);
    let text = format!(
        "time: 10\ndt: 0.1\naxiom: {axiom}\n\
         A(x) : x < 1 --> solve dx/dt = 1\n\
         A(x) : x >= 1 --> F A(0)\n"
    );
    LSystem::from_text("bench", &text).expect("compiles")
}

fn develop(c: &mut Criterion) {
    let lsys = growing_modules(10_000);
    let options = DeriveOptions::default();
    let mut group = c.benchmark_group("develop");
    group.sample_size(10);
    group.bench_function("10k growing modules, t = 0..10, dt = 0.1", |b| {
        b.iter(|| {
            let mut dev = lsys.development(&options).expect("starts");
            while dev.advance().expect("develops") {}
            assert_eq!(dev.current().len(), 110_000);
            dev
        })
    });
    group.finish();
}

fn random_genomes(c: &mut Criterion) {
    let limits = ContinuousLimits::default();
    let genomes: Vec<ContinuousGenome> = (0..1000u64)
        .map(|seed| ContinuousGenome::random(&limits, &mut Rng::seed_from_u64(seed)))
        .collect();
    let mut group = c.benchmark_group("develop");
    group.sample_size(10);
    group.bench_function("1000 random lsystem-continuous genomes, seeds 0-999", |b| {
        b.iter(|| {
            genomes
                .iter()
                .filter(|g| g.develop(&limits, 0).is_ok())
                .count()
        })
    });
    group.finish();
}

criterion_group!(benches, develop, random_genomes);
criterion_main!(benches);
