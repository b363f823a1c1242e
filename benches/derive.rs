//! Derivation throughput: modules produced per second by one step, single thread.
//!
//! Floors (issue 2): 50 million modules/s for a non-parametric system (algae) and 5 million
//! modules/s for the parametric example of ABOP section 1.10 at about a million modules.
//! Run with `cargo bench --bench derive`.

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use ontogeny::lsystem::{DeriveOptions, LSystem, ModuleString};

/// Derives until the string holds at least `target` modules; returns it and its step.
fn grow(lsys: &LSystem, target: usize) -> (ModuleString, u64) {
    let options = DeriveOptions {
        max_modules: usize::MAX,
        ..DeriveOptions::default()
    };
    let mut d = lsys.derivation(&options).expect("starts");
    while d.current().len() < target {
        d.step().expect("derives");
    }
    (d.current().clone(), d.step_number())
}

fn bench_step(c: &mut Criterion, name: &str, lsys: &LSystem, start: &ModuleString, step: u64) {
    let options = DeriveOptions {
        max_modules: usize::MAX,
        ..DeriveOptions::default()
    };
    let produced = {
        let mut d = lsys.derivation_from(start.clone(), step, &options);
        d.step().expect("derives").len()
    };
    let mut group = c.benchmark_group("derive");
    group.throughput(Throughput::Elements(produced as u64));
    group.sample_size(20);
    group.bench_function(name, |b| {
        b.iter_batched(
            || lsys.derivation_from(start.clone(), step, &options),
            |mut d| {
                d.step().expect("derives");
                d
            },
            BatchSize::LargeInput,
        )
    });
    group.finish();
    println!(
        "{name}: one step from {} to {produced} modules",
        start.len()
    );
}

fn algae(c: &mut Criterion) {
    let lsys = LSystem::from_text("algae", "axiom: a\na --> ab\nb --> a\n").unwrap();
    let (start, step) = grow(&lsys, 1_000_000);
    bench_step(c, "algae (non-parametric)", &lsys, &start, step);
}

fn parametric(c: &mut Criterion) {
    // ABOP section 1.10's example. One copy grows by about one module every four steps, so
    // the axiom holds many copies to reach about a million modules.
    let axiom = "B(2) A(4, 4) ".repeat(250_000);
    let text = format!(
        "axiom: {axiom}
A(x, y) : y <= 3 --> A(x * 2, x + y)
A(x, y) : y > 3  --> B(x) A(x / y, 0)
B(x) : x < 1  --> C
B(x) : x >= 1 --> B(x - 1)
"
    );
    let lsys = LSystem::from_text("parametric", &text).unwrap();
    let (start, step) = grow(&lsys, 1_000_000);
    bench_step(c, "parametric (ABOP 1.10)", &lsys, &start, step);
}

criterion_group!(benches, algae, parametric);
criterion_main!(benches);
