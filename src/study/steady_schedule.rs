//! The schedule simulator's steady-state schedule, and the reshaped profiles it projects from.
//!
//! A steady-state algorithm has no generation barrier: births are numbered, at least a fixed
//! number of them are in flight, and birth `b` (after the first population) is bred as soon as
//! the last generation (block of births) that ended `in_flight` births before it has been
//! integrated, integration following birth order whatever order the walks finish in
//! ([`crate::evolve::steady`]). [`predict_steady`] replays a profile's walks as such births: the births of
//! each recorded generation in its individuals' order (a birth's walks together), each bred by
//! one driver (rank 0's main thread) that spends the profile's time outside evaluation, shared
//! equally among the births, on each birth before handing its walks out; every walk goes to the
//! first thread free; the run ends when its last birth is integrated.
//!
//! For projections to machines and populations no run was recorded on, a profile can be
//! reshaped: [`with_driver`] puts a given serial cost per evaluation in place of the recorded
//! time outside evaluation (rank 0's cost of breeding, developing and keying one individual),
//! and [`resampled`] draws generations of another size from the profile's walks.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use rand::{RngExt, SeedableRng};

use super::schedule::{Free, Machine, Prediction};
use crate::encoding::Rng;
use crate::evolve::timing::WalkTime;
use crate::run::profile::GenerationProfile;

/// The births a profile's generations make, in order: each generation's walked individuals in
/// their index order (each birth the seconds of its walks, in the order they were handed out),
/// then the rest of its evaluations (reused from the cache, or not walkable) as births without
/// a walk.
pub fn births(profile: &[GenerationProfile]) -> Vec<Vec<f64>> {
    let mut births = Vec::new();
    for g in profile {
        let mut walks: Vec<&WalkTime> = g.walks.iter().collect();
        walks.sort_by_key(|w| w.individual);
        let first = births.len();
        let mut last = None;
        for w in walks {
            if last != Some(w.individual) {
                births.push(Vec::new());
                last = Some(w.individual);
            }
            births.last_mut().expect("pushed above").push(w.seconds);
        }
        let walked = (births.len() - first) as u64;
        births.extend((walked..g.evaluations).map(|_| Vec::new()));
    }
    births
}

/// The prediction for `machine` of the run profiled in `profile`, had it been steady-state
/// with `in_flight` births in flight (at least 1), as `evolve --algorithm steady-state` breeds:
/// the profile's first generation is the population P, bred at once; its later generations'
/// evaluations (the first of them, C) are the blocks of births each stored generation ends;
/// birth b ≥ P is bred once the last generation that ended at or before birth b + 1 − W (W =
/// `in_flight`; the first generation when none did) is integrated.
pub fn predict_steady(
    profile: &[GenerationProfile],
    machine: Machine,
    in_flight: usize,
) -> Prediction {
    let births = births(profile);
    let outside: f64 = profile.iter().map(|g| g.outside_evaluation()).sum();
    let driver = if births.is_empty() {
        0.0
    } else {
        outside / births.len() as f64
    };
    let population = profile.first().map_or(0, |g| g.evaluations as usize);
    let children = profile
        .get(1)
        .map_or(population, |g| g.evaluations as usize)
        .max(1);
    let slots = machine.slots().max(1);
    let mut free: BinaryHeap<Reverse<Free>> = (0..slots).map(|i| Reverse(Free(0.0, i))).collect();
    let in_flight = in_flight.max(1);
    let mut integrated: Vec<f64> = Vec::with_capacity(births.len());
    let mut driver_free = 0.0_f64;
    let mut walked = 0.0;
    for (b, walks) in births.iter().enumerate() {
        // Bred from the last generation that ended at or before birth b + 1 − W: it waits
        // for that generation's last birth.
        let after = if b < population {
            0.0
        } else {
            let at = (b + 1).saturating_sub(in_flight);
            let blocks = at.saturating_sub(population) / children;
            integrated[population + blocks * children - 1]
        };
        let handed = driver_free.max(after) + driver;
        driver_free = handed;
        let mut finished = handed;
        for &seconds in walks {
            let Some(Reverse(Free(at, slot))) = free.pop() else {
                break;
            };
            let done = at.max(handed) + seconds;
            finished = finished.max(done);
            walked += seconds;
            free.push(Reverse(Free(done, slot)));
        }
        let previous = integrated.last().copied().unwrap_or(0.0);
        integrated.push(finished.max(previous));
    }
    let seconds = integrated.last().copied().unwrap_or(0.0);
    let evaluations: u64 = profile.iter().map(|g| g.evaluations).sum();
    Prediction {
        machine,
        seconds,
        walking_seconds: seconds,
        walking_share: walked / (slots as f64 * seconds),
        evaluations_per_second: evaluations as f64 / seconds,
    }
}

/// `profile` with `seconds` of serial work per evaluation in place of each generation's
/// recorded time outside evaluation but the fine re-walk (recorded as breeding; developing,
/// keying, writing and the rest 0).
pub fn with_driver(profile: &[GenerationProfile], seconds: f64) -> Vec<GenerationProfile> {
    profile
        .iter()
        .map(|g| {
            let breeding = seconds * g.evaluations as f64;
            GenerationProfile {
                breeding,
                developing: 0.0,
                keying: 0.0,
                writing: 0.0,
                other: 0.0,
                total: g.evaluating + g.fine + breeding,
                ..g.clone()
            }
        })
        .collect()
}

/// `generations` generations of `population` evaluations of one walk each, the walks drawn at
/// random (with replacement, from `seed`) from all of `profile`'s walks with their parts; each
/// generation's time outside evaluation is the profile's per evaluation (the mean fine re-walk
/// included) times `population`, recorded as breeding, and its fine re-walk the profile's mean.
/// Empty when the profile has no walk.
pub fn resampled(
    profile: &[GenerationProfile],
    population: usize,
    generations: usize,
    seed: u64,
) -> Vec<GenerationProfile> {
    let pool: Vec<&WalkTime> = profile.iter().flat_map(|g| &g.walks).collect();
    if pool.is_empty() {
        return Vec::new();
    }
    let evaluations: u64 = profile.iter().map(|g| g.evaluations).sum();
    let outside: f64 = profile.iter().map(|g| g.outside_evaluation()).sum();
    let fine = profile.iter().map(|g| g.fine).sum::<f64>() / profile.len() as f64;
    let per_evaluation = (outside - fine * profile.len() as f64).max(0.0) / evaluations as f64;
    let mut rng = Rng::seed_from_u64(seed);
    (0..generations)
        .map(|generation| {
            let walks: Vec<WalkTime> = (0..population)
                .map(|i| WalkTime {
                    individual: i as u32,
                    thread: 0,
                    rank: 0,
                    ..*pool[rng.random_range(0..pool.len())]
                })
                .collect();
            let evaluating = walks.iter().map(|w| w.seconds).sum::<f64>();
            let breeding = per_evaluation * population as f64;
            GenerationProfile {
                generation: generation as u32,
                threads: 1,
                ranks: 1,
                evaluations: population as u64,
                breeding,
                developing: 0.0,
                keying: 0.0,
                evaluating,
                fine,
                writing: 0.0,
                other: 0.0,
                total: breeding + evaluating + fine,
                walks,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn generation(walks: &[(u32, f64)], outside: f64, evaluations: u64) -> GenerationProfile {
        let evaluating = walks.iter().map(|w| w.1).sum::<f64>();
        GenerationProfile {
            generation: 0,
            threads: 1,
            ranks: 1,
            evaluations,
            breeding: outside,
            developing: 0.0,
            keying: 0.0,
            evaluating,
            fine: 0.0,
            writing: 0.0,
            other: 0.0,
            total: outside + evaluating,
            walks: walks
                .iter()
                .map(|&(individual, seconds)| WalkTime {
                    individual,
                    seconds,
                    thread: 0,
                    rank: 0,
                    parts: 3,
                })
                .collect(),
        }
    }

    const TWO: Machine = Machine {
        ranks: 1,
        threads: 2,
    };

    #[test]
    fn births_group_an_individual_s_walks_and_count_the_unwalked() {
        // Individual 1's two walks were handed out apart; individual 3 was reused.
        let g = generation(&[(1, 1.0), (0, 2.0), (1, 3.0), (2, 4.0)], 0.0, 4);
        assert_eq!(
            births(&[g]),
            vec![vec![2.0], vec![1.0, 3.0], vec![4.0], vec![]]
        );
    }

    #[test]
    fn a_steady_state_replay_gives_the_hand_computed_times() {
        // A population of 2 (walks of 3 and 1 s), then generations of one birth (1 s each):
        // P = 2, C = 1; no time outside.
        let profile = [
            generation(&[(0, 3.0), (1, 1.0)], 0.0, 2),
            generation(&[(0, 1.0)], 0.0, 1),
            generation(&[(0, 1.0)], 0.0, 1),
            generation(&[(0, 1.0)], 0.0, 1),
        ];
        // One in flight, 2 threads: births 0 and 1 at once (0-3, 0-1), integrated at 3. Birth
        // 2 is bred from generation 0 (ended at birth 2 = 2 + 1 − 1): 3-4; birth 3 from
        // generation 1 (its birth 2 integrated at 4): 4-5; birth 4 from generation 2: 5-6.
        let p = predict_steady(&profile, TWO, 1);
        assert_eq!(p.seconds, 6.0);
        assert_eq!(p.evaluations_per_second, 5.0 / 6.0);
        assert_eq!(p.walking_share, 7.0 / 12.0);
        // Two in flight: births 2 and 3 from generation 0 (3-4 each, on both threads); birth
        // 4 from generation 1 (ended at birth 3 = 4 + 1 − 2, integrated at 4): 4-5.
        assert_eq!(predict_steady(&profile, TWO, 2).seconds, 5.0);
        // Generationally: 3, then 1, 1, 1.
        let generational = super::super::schedule::predict(&profile, TWO, Default::default());
        assert_eq!(generational.seconds, 6.0);
        // Blocks of 2 (P = C = 2): birth 3 is bred from generation 0 like birth 2, even with
        // one in flight: 3-4 on both threads.
        let pairs = [
            generation(&[(0, 3.0), (1, 1.0)], 0.0, 2),
            generation(&[(0, 1.0), (1, 1.0)], 0.0, 2),
        ];
        assert_eq!(predict_steady(&pairs, TWO, 1).seconds, 4.0);
    }

    #[test]
    fn the_driver_s_time_is_serial_before_each_birth_is_handed_out() {
        // 4 births of one 1-s walk; 0.8 s outside in all: 0.2 s a birth on the driver.
        let profile = [generation(
            &[(0, 1.0), (1, 1.0), (2, 1.0), (3, 1.0)],
            0.8,
            4,
        )];
        // 4 threads, all births of the first population: handed at 0.2, 0.4, 0.6, 0.8, the
        // last ends at 1.8.
        let four = Machine {
            ranks: 1,
            threads: 4,
        };
        assert!((predict_steady(&profile, four, 4).seconds - 1.8).abs() < 1e-12);
        // Generational: 0.8 outside + 1 s walking.
        assert!(
            (super::super::schedule::predict(&profile, four, Default::default()).seconds - 1.8)
                .abs()
                < 1e-12
        );
        // A driver of 0.05 s an evaluation in place of the recorded time.
        let cheap = with_driver(&profile, 0.05);
        assert!((cheap[0].outside_evaluation() - 0.2).abs() < 1e-12);
        assert!((predict_steady(&cheap, four, 4).seconds - 1.2).abs() < 1e-12);
    }

    #[test]
    fn resampling_draws_the_profile_s_walks_deterministically() {
        let profile = [generation(&[(0, 1.0), (1, 2.0), (2, 3.0)], 0.3, 3)];
        let a = resampled(&profile, 50, 2, 7);
        assert_eq!(a, resampled(&profile, 50, 2, 7));
        assert_eq!(a.len(), 2);
        for g in &a {
            assert_eq!((g.evaluations, g.walks.len()), (50, 50));
            assert!(g.walks.iter().all(|w| [1.0, 2.0, 3.0].contains(&w.seconds)));
            // 0.1 s outside an evaluation, times 50.
            assert!((g.outside_evaluation() - 5.0).abs() < 1e-9);
        }
        // Every recorded walk is drawn among 100.
        for s in [1.0, 2.0, 3.0] {
            assert!(a.iter().flat_map(|g| &g.walks).any(|w| w.seconds == s));
        }
        assert!(resampled(&[generation(&[], 1.0, 1)], 5, 1, 1).is_empty());
    }
}
