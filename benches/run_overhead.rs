//! A run's cost per generation outside evaluation (storing the generation, advancing
//! `log.txt`, `best.*` and `fitness.svg`), early and late in a run: at generation 10 and at
//! generation 1,000 of a tiny run (direct-genome walkers, population 10, 0.1 s walks at the
//! fast setting, seed 1), each figure the mean over [`PLOT_EVERY`] generations from there, so
//! that it holds one redraw of the plot. The two should be within 1.5× of each other: the cost
//! of a generation must not grow with the generations before it.
//!
//! Run with `cargo bench --bench run_overhead` (about ten minutes on a loaded machine; the run
//! goes to a temporary folder, removed at the end).

use ontogeny::encoding::DirectGenome;
use ontogeny::front::settings::{self, RunFlags};
use ontogeny::run::derived::PLOT_EVERY;
use ontogeny::run::{GenerationReport, Run};
use ontogeny::sim::StepSetting;

/// The generations whose overhead is compared.
const EARLY: u32 = 10;
const LATE: u32 = 1000;

fn main() {
    let flags = RunFlags {
        population: Some(10),
        generations: Some((LATE + PLOT_EVERY) as usize),
        seconds: Some(0.1),
        setting: Some(StepSetting::Fast),
        ..RunFlags::default()
    };
    let config = settings::new_run::<DirectGenome>(None, &flags, None, Some(1), true, true)
        .expect("the bench's settings are valid")
        .config;
    let folder = tempfile::tempdir().expect("a temporary folder");
    let dir = folder.path().join("run");
    let mut run = Run::<DirectGenome>::start(&dir, config, None).expect("the run starts");
    // Seconds outside evaluation, by generation.
    let mut overhead = Vec::new();
    let mut evaluation = Vec::new();
    run.run(&mut |r: &GenerationReport| {
        overhead.push(r.wall_seconds - r.evaluation_seconds);
        evaluation.push(r.evaluation_seconds);
    })
    .expect("the run completes");
    let mean = |from: u32, of: &[f64]| {
        let window = &of[from as usize..(from + PLOT_EVERY) as usize];
        window.iter().sum::<f64>() / window.len() as f64
    };
    let (early, late) = (mean(EARLY, &overhead), mean(LATE, &overhead));
    println!(
        "overhead per generation (outside evaluation), mean of generations {EARLY}-{}: {:.3} ms (evaluation {:.1} ms)",
        EARLY + PLOT_EVERY - 1,
        early * 1e3,
        mean(EARLY, &evaluation) * 1e3
    );
    println!(
        "overhead per generation (outside evaluation), mean of generations {LATE}-{}: {:.3} ms (evaluation {:.1} ms)",
        LATE + PLOT_EVERY - 1,
        late * 1e3,
        mean(LATE, &evaluation) * 1e3
    );
    println!(
        "ratio (generation {LATE} / generation {EARLY}): {:.2} (floor: at most 1.5)",
        late / early
    );
}
