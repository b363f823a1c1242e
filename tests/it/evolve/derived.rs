//! The files derived from a run's store while the run goes on: `log.txt` grows by a line a
//! generation, `fitness.svg` is redrawn every tenth generation and after the last, and what a
//! run leaves, interrupted or not, is byte for byte what a resume writes from its store.

use super::*;

use ontogeny::cancel::Cancel;
use ontogeny::front::settings::{self, RunFlags};
use ontogeny::run::RunError;
use ontogeny::run::derived::PLOT_EVERY;
use ontogeny::sim::StepSetting;

/// A new run of direct-genome walkers in `out`: population 4, `generations` generations of
/// 0.1 s walks at the fast setting, seed 3.
fn tiny_run(out: &Path, generations: usize) -> Run<DirectGenome> {
    let flags = RunFlags {
        population: Some(4),
        generations: Some(generations),
        seconds: Some(0.1),
        setting: Some(StepSetting::Fast),
        ..RunFlags::default()
    };
    let config = settings::new_run::<DirectGenome>(None, &flags, None, Some(3), true, true)
        .unwrap()
        .config;
    Run::<DirectGenome>::start(out, config, None).unwrap()
}

/// `log.txt`, `fitness.svg` and the best genome's file of the run in `dir`.
fn derived(dir: &Path) -> [Vec<u8>; 3] {
    let best = format!("best.{}", DirectGenome::TEXT_EXTENSION);
    ["log.txt", "fitness.svg", best.as_str()].map(|f| std::fs::read(dir.join(f)).unwrap())
}

/// The derived files of the run in `dir` as a resume writes them anew from its store.
fn rewritten(dir: &Path) -> [Vec<u8>; 3] {
    drop(Run::<DirectGenome>::resume(dir).unwrap());
    derived(dir)
}

#[test]
fn the_log_grows_a_line_a_generation_and_the_plot_is_redrawn_every_tenth_generation_and_after_the_last()
 {
    let dir = scratch("derived-growing");
    let out = dir.join("run");
    let mut run = tiny_run(&out, 12);
    let (log, plot) = (out.join("log.txt"), out.join("fitness.svg"));
    let mut drawn = std::fs::read(&plot).unwrap();
    let (mut redrawn, mut lines) = (Vec::new(), Vec::new());
    run.run(&mut |r| {
        let now = std::fs::read(&plot).unwrap();
        if now != drawn {
            redrawn.push(r.generation);
            drawn = now;
        }
        let text = std::fs::read_to_string(&log).unwrap();
        let last = text.lines().rfind(|l| l.starts_with("generation "));
        lines.push(last.map(|l| l.split(':').next().unwrap().to_string()));
        if r.generation == 5 {
            // Another process cuts the log short: the run writes it whole at the next line.
            std::fs::write(&log, "generation 0\n").unwrap();
        }
    })
    .unwrap();
    assert_eq!(PLOT_EVERY, 10);
    assert_eq!(redrawn, [0, 10, 11]);
    let expected: Vec<_> = (0..12).map(|g| Some(format!("generation {g}"))).collect();
    assert_eq!(lines, expected);
    drop(run);
    let left = derived(&out);
    let text = String::from_utf8(left[0].clone()).unwrap();
    assert_eq!(
        text.lines()
            .filter(|l| l.starts_with("generation "))
            .count(),
        12
    );
    assert_eq!(rewritten(&out), left);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_run_interrupted_and_resumed_leaves_the_files_its_store_gives_and_the_uninterrupted_log() {
    let dir = scratch("derived-interrupted");
    let (whole, cut) = (dir.join("whole"), dir.join("cut"));
    tiny_run(&whole, 12).run(&mut |_| {}).unwrap();
    let token = Cancel::new();
    let mut run = tiny_run(&cut, 12);
    run.set_cancel(token.clone());
    let e = run
        .run(&mut |r| {
            if r.generation == 3 {
                token.cancel();
            }
        })
        .unwrap_err();
    assert!(matches!(e, RunError::Interrupted(_)), "{e:?}");
    drop(run);
    // Stopped between two redraws, after generation 3: the plot caught up with the store.
    let stopped = derived(&cut);
    assert_eq!(rewritten(&cut), stopped);
    Run::<DirectGenome>::resume(&cut)
        .unwrap()
        .run(&mut |_| {})
        .unwrap();
    let left = derived(&cut);
    assert_eq!(rewritten(&cut), left);
    assert_eq!(contents(&cut), contents(&whole));
    assert_eq!(log_without_times(&cut), log_without_times(&whole));
    let _ = std::fs::remove_dir_all(dir);
}
