//! What the schedule simulator replays besides a profile's own generations: the births a
//! steady-state replay is made of ([`births`]; the replay itself is the schedule module's
//! `predict_steady`), and profiles reshaped for projections to machines and
//! populations no run was recorded on: [`with_driver`] puts a given serial cost per evaluation
//! in place of the recorded time outside evaluation (rank 0's cost of breeding, developing
//! and keying one individual), and [`resampled`] draws generations of another size from the
//! profile's walks.

use rand::{RngExt, SeedableRng};

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
                fine_walk: None,
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
            fine_walk: None,
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
