//! The schedule simulator: from a run's profile ([`crate::run::profile`]), the evaluations per
//! second that another number of threads (or of MPI ranks × threads) would reach under the
//! run's own generational schedule.
//!
//! Each generation is replayed: its walks, in the order the evaluator was handed them, go each
//! to the first thread to fall free (greedy list scheduling, as the evaluator hands walks out
//! to its threads and the MPI dispatcher from its one queue); the generation waits for its
//! last walk (the barrier); and the time the generation spent outside the evaluator's batch
//! (breeding, developing, keying, the fine re-walk, writing and the rest) is added as it was
//! recorded.
//! R ranks × T threads are R·T threads, with no cost for messages. The walks keep the times
//! they had when recorded, so a prediction holds for a machine whose cores walk as fast as the
//! recording's did (as many real cores as threads, no other load).
//!
//! Two levers can be modelled on a profile recorded without them ([`Levers`]): the walks
//! handed out longest-first (by their creatures' parts, as the genetic algorithm's
//! [`crate::evolve::ga::WalkOrder::LongestFirst`] orders them), and the fine re-walk of each
//! generation's best run as one more walk at the head of the next generation's batch instead
//! of alone before its generation is stored.
//!
//! [`predict_steady`] replays the same births under a steady-state schedule instead (no
//! barrier; see [`crate::evolve::steady`]); [`super::steady_schedule`] makes its births and
//! reshapes profiles for projections.

use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

use super::steady_schedule::births;
use crate::number::format_number;
use crate::run::profile::GenerationProfile;

/// The most threads, and the most ranks, a prediction is made for.
pub const MAX_THREADS: u32 = 1024;

/// The thread counts predicted when none are asked for: 1, 2, 4, ..., 1,024.
pub fn default_threads() -> Vec<u32> {
    (0..=10).map(|k| 1 << k).collect()
}

/// A machine to predict for: `ranks` processes of `threads` threads each.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Machine {
    /// MPI ranks (1 without MPI).
    pub ranks: u32,
    /// Threads per rank.
    pub threads: u32,
}

impl Machine {
    /// Its threads in all, each of which walks.
    pub fn slots(self) -> usize {
        self.ranks as usize * self.threads as usize
    }

    /// Checks that both counts are 1 to [`MAX_THREADS`]; the error names the flag.
    pub fn check(self) -> Result<(), String> {
        for (flag, n) in [("--threads", self.threads), ("--ranks", self.ranks)] {
            if !(1..=MAX_THREADS).contains(&n) {
                return Err(format!("{flag} must be 1 to {MAX_THREADS}, not {n}"));
            }
        }
        Ok(())
    }
}

/// A time at which a thread falls free, ordered by time, then by the thread's index.
#[derive(PartialEq)]
struct Free(f64, usize);

impl Eq for Free {}

impl PartialOrd for Free {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Free {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0).then(self.1.cmp(&other.1))
    }
}

/// The time from the first walk's start to the last one's end when `walks` (seconds, in the
/// order handed out) go each to the first of `slots` threads to fall free (the lowest-numbered
/// among those free at once): greedy list scheduling. 0 for no walk; `slots` of 0 counts as 1.
pub fn makespan(walks: &[f64], slots: usize) -> f64 {
    let slots = slots.clamp(1, walks.len().max(1));
    let mut free: BinaryHeap<Reverse<Free>> = (0..slots).map(|i| Reverse(Free(0.0, i))).collect();
    let mut end: f64 = 0.0;
    for &seconds in walks {
        let Some(Reverse(Free(at, slot))) = free.pop() else {
            break;
        };
        let done = at + seconds;
        end = end.max(done);
        free.push(Reverse(Free(done, slot)));
    }
    end
}

/// What a profile says of the run it was recorded from.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Recorded {
    /// Generations profiled.
    pub generations: usize,
    /// Individuals evaluated, as the run counts them.
    pub evaluations: u64,
    /// Walks simulated, with their times.
    pub walks: usize,
    /// Seconds of walking, summed over threads.
    pub walk_seconds: f64,
    /// Wall-clock seconds of the generations, in all.
    pub seconds: f64,
    /// Of which outside the evaluator's batches.
    pub outside_seconds: f64,
    /// The threads of each rank and the ranks, as the first generation ran (a profile of a
    /// resumed run may mix several).
    pub machine: Machine,
    /// `evaluations / seconds`: the speed measured.
    pub evaluations_per_second: f64,
}

/// The profile's own figures.
pub fn recorded(profile: &[GenerationProfile]) -> Recorded {
    let evaluations: u64 = profile.iter().map(|g| g.evaluations).sum();
    let seconds: f64 = profile.iter().map(|g| g.total).sum();
    let first = profile.first();
    Recorded {
        generations: profile.len(),
        evaluations,
        walks: profile.iter().map(|g| g.walks.len()).sum(),
        walk_seconds: profile
            .iter()
            .flat_map(|g| &g.walks)
            .map(|w| w.seconds)
            .sum(),
        seconds,
        outside_seconds: profile.iter().map(|g| g.outside_evaluation()).sum(),
        machine: Machine {
            ranks: first.map_or(1, |g| g.ranks),
            threads: first.map_or(1, |g| g.threads),
        },
        evaluations_per_second: evaluations as f64 / seconds,
    }
}

/// The changes to the run's schedule a prediction models, beyond what the profile recorded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Levers {
    /// Each generation's walks handed out by their creatures' parts, most first, ties in the
    /// recorded order (a stable sort: on a profile recorded in the individuals' order, the
    /// order [`crate::evolve::ga::WalkOrder::LongestFirst`] hands them out in).
    pub longest_first: bool,
    /// Each generation's fine re-walk (its recorded `fine` seconds) taken out of its time
    /// outside evaluation and walked first in the next generation's batch, beside its walks;
    /// the last generation's stays where it was, as there is no next batch.
    pub fine_beside: bool,
}

/// Each generation's walks (seconds) as the levers hand them out, and its seconds outside
/// evaluation.
pub fn replayed(profile: &[GenerationProfile], levers: Levers) -> Vec<(Vec<f64>, f64)> {
    profile
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let mut walks: Vec<(u32, f64)> = g.walks.iter().map(|w| (w.parts, w.seconds)).collect();
            if levers.longest_first {
                walks.sort_by_key(|&(parts, _)| Reverse(parts));
            }
            let mut seconds: Vec<f64> = walks.into_iter().map(|(_, s)| s).collect();
            let mut outside = g.outside_evaluation();
            if levers.fine_beside {
                if i + 1 < profile.len() {
                    outside = (outside - g.fine).max(0.0);
                }
                if let Some(previous) = i.checked_sub(1).map(|p| profile[p].fine)
                    && previous > 0.0
                {
                    seconds.insert(0, previous);
                }
            }
            (seconds, outside)
        })
        .collect()
}

/// The simulator's prediction for one machine.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Prediction {
    /// The machine.
    pub machine: Machine,
    /// Wall-clock seconds of every generation: its makespan and its time outside evaluation.
    pub seconds: f64,
    /// Of which walking (the generations' makespans).
    pub walking_seconds: f64,
    /// The share of the threads' time spent walking while the generations walk: walk seconds
    /// / (threads × walking seconds); what the barriers leave idle is the rest. NaN (`null` in
    /// JSON) for a profile without walks.
    pub walking_share: f64,
    /// Evaluations (as the run counts them) per second.
    pub evaluations_per_second: f64,
}

/// The prediction for `machine` of the run profiled in `profile`, with `levers`.
pub fn predict(profile: &[GenerationProfile], machine: Machine, levers: Levers) -> Prediction {
    let slots = machine.slots();
    let mut walking = 0.0;
    let mut outside = 0.0;
    let mut walked = 0.0;
    for (walks, out) in replayed(profile, levers) {
        walking += makespan(&walks, slots);
        walked += walks.iter().sum::<f64>();
        outside += out;
    }
    let seconds = walking + outside;
    let evaluations: u64 = profile.iter().map(|g| g.evaluations).sum();
    Prediction {
        machine,
        seconds,
        walking_seconds: walking,
        walking_share: walked / (slots as f64 * walking),
        evaluations_per_second: evaluations as f64 / seconds,
    }
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

/// The schedule a prediction replays a profile under.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Schedule {
    /// The generational algorithm's, with the levers modelled ([`predict`]).
    Generational(Levers),
    /// A steady-state algorithm's, with this many births in flight, the profile's first
    /// generation as its population and its second's evaluations as its blocks
    /// ([`predict_steady`]).
    SteadyState {
        /// Births in flight, at least 1.
        in_flight: usize,
    },
}

impl Schedule {
    /// The prediction for `machine` of the run profiled in `profile` under this schedule.
    pub fn predict(self, profile: &[GenerationProfile], machine: Machine) -> Prediction {
        match self {
            Schedule::Generational(levers) => predict(profile, machine, levers),
            Schedule::SteadyState { in_flight } => predict_steady(profile, machine, in_flight),
        }
    }

    /// How the prediction replays the profile, in words.
    pub fn describe(self) -> String {
        match self {
            Schedule::Generational(levers) => format!(
                "each generation's walks {}, each to the first thread free, a barrier at each generation's end, the time outside evaluation as recorded{}",
                if levers.longest_first {
                    "by their creatures' parts, most first (ties in their recorded order)"
                } else {
                    "in their recorded order"
                },
                if levers.fine_beside {
                    " but for the fine re-walk of each generation's best, walked first in the next generation's batch (the last one's as recorded)"
                } else {
                    ""
                },
            ),
            Schedule::SteadyState { in_flight } => format!(
                "steady-state, {in_flight} birth{} in flight: the recorded individuals as births in order, the first generation bred at once, each later birth once the last generation that ended {in_flight} births before it is integrated, the time outside evaluation shared equally among the births and spent on one driver before each birth, each walk to the first thread free, births integrated in order",
                if in_flight == 1 { "" } else { "s" },
            ),
        }
    }
}

/// The ceiling's speed per thread: the generational schedule's on one thread, as one of as
/// many independent one-thread runs as there are threads would go.
pub fn ceiling_per_thread(profile: &[GenerationProfile]) -> f64 {
    let one = Machine {
        ranks: 1,
        threads: 1,
    };
    predict(profile, one, Levers::default()).evaluations_per_second
}

/// The predictions as a table for people: what was recorded, then a row per machine with its
/// evaluations per second, the speed-up over the same schedule on one thread (`one`), the
/// share of the ceiling (its speed over `ceiling` per thread: as many independent one-thread
/// runs of the generational schedule would reach 1) and the walking share, and how they were
/// predicted (under `schedule`).
pub fn table(
    name: &str,
    recorded: &Recorded,
    (one, ceiling): (&Prediction, f64),
    rows: &[Prediction],
    schedule: Schedule,
) -> String {
    let mut out = format!(
        "{name}: {} generation{}, {} evaluations, {} walks ({} s of walking, {} s outside evaluation), recorded on {} rank{} × {} thread{}: {} evaluations/s measured\n",
        recorded.generations,
        plural(recorded.generations),
        recorded.evaluations,
        recorded.walks,
        round(recorded.walk_seconds, 1),
        round(recorded.outside_seconds, 2),
        recorded.machine.ranks,
        plural(recorded.machine.ranks),
        recorded.machine.threads,
        plural(recorded.machine.threads),
        round(recorded.evaluations_per_second, 2),
    );
    if recorded.walks == 0 && recorded.evaluations > 0 {
        out.push_str(
            "note: the profile holds no walk times (a run over MPI ranks does not record them): the predictions count only the time outside evaluation\n",
        );
    }
    out.push_str("ranks  threads  evaluations/s  speed-up  of ceiling  walking share\n");
    for p in rows {
        let speed_up = p.evaluations_per_second / one.evaluations_per_second;
        out.push_str(&format!(
            "{:>5}  {:>7}  {:>13}  {:>8}  {:>10}  {:>13}\n",
            p.machine.ranks,
            p.machine.threads,
            round(p.evaluations_per_second, 2),
            format!("{}×", round(speed_up, 2)),
            round(
                p.evaluations_per_second / (ceiling * p.machine.slots() as f64),
                3
            ),
            if p.walking_share.is_finite() {
                round(p.walking_share, 3)
            } else {
                "-".to_string() // no walk to share out
            },
        ));
    }
    out.push_str(&format!("predicted: {}", schedule.describe()));
    out
}

/// Whether the profile records its walks' creature sizes, which `longest_first` needs: a
/// profile written before they were recorded has 0 parts for every walk.
pub fn records_parts(profile: &[GenerationProfile]) -> bool {
    let mut walks = profile.iter().flat_map(|g| &g.walks).peekable();
    walks.peek().is_none() || walks.any(|w| w.parts > 0)
}

/// The predictions as one JSON object: the profile's name and figures, the schedule (its
/// `algorithm`, the generational levers modelled, the steady-state's births in flight), the
/// ceiling's evaluations per second per thread ([`ceiling_per_thread`]) and a prediction per
/// machine.
pub fn json(
    name: &str,
    recorded: &Recorded,
    ceiling: f64,
    rows: &[Prediction],
    schedule: Schedule,
) -> String {
    let (algorithm, levers, in_flight) = match schedule {
        Schedule::Generational(levers) => ("generational", levers, None),
        Schedule::SteadyState { in_flight } => ("steady-state", Levers::default(), Some(in_flight)),
    };
    serde_json::to_string_pretty(&serde_json::json!({
        "profile": name,
        "recorded": recorded,
        "algorithm": algorithm,
        "levers": levers,
        "in_flight": in_flight,
        "ceiling_per_thread": ceiling,
        "predictions": rows,
    }))
    .unwrap_or_default()
}

/// `value` rounded to `places` decimals, written as people read it.
fn round(value: f64, places: i32) -> String {
    let scale = 10f64.powi(places);
    format_number((value * scale).round() / scale)
}

fn plural(n: impl TryInto<u32>) -> &'static str {
    if n.try_into().ok() == Some(1) {
        ""
    } else {
        "s"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::evolve::timing::WalkTime;

    /// A generation whose walks of `walks` seconds are its individuals' in order.
    fn generation(walks: &[f64], outside: f64, evaluations: u64) -> GenerationProfile {
        let owned: Vec<(u32, f64)> = walks
            .iter()
            .enumerate()
            .map(|(i, &seconds)| (i as u32, seconds))
            .collect();
        births_generation(&owned, outside, evaluations)
    }

    #[test]
    fn greedy_list_scheduling_gives_the_hand_computed_makespan() {
        let walks = [3.0, 1.0, 1.0, 1.0, 2.0];
        // One thread: 3 + 1 + 1 + 1 + 2.
        assert_eq!(makespan(&walks, 1), 8.0);
        // Two: A takes 3 (0-3); B takes 1, 1, 1 (0-1, 1-2, 2-3); both fall free at 3 and the
        // 2 ends at 5: greedy in this order, although 3 + 1 | 1 + 1 + 2 would end at 4.
        assert_eq!(makespan(&walks, 2), 5.0);
        // Three: A 3 (0-3); B 1 (0-1), C 1 (0-1); B 1 (1-2); C 2 (1-3).
        assert_eq!(makespan(&walks, 3), 3.0);
        // As many threads as walks, or more: the longest walk.
        assert_eq!(makespan(&walks, 5), 3.0);
        assert_eq!(makespan(&walks, 1024), 3.0);
        assert_eq!(makespan(&[], 4), 0.0);
        // The longest first packs them: 3 | 2 + 1, then 1 and 1 to the first free.
        assert_eq!(makespan(&[3.0, 2.0, 1.0, 1.0, 1.0], 2), 4.0);
    }

    #[test]
    fn a_prediction_adds_each_generation_s_barrier_and_its_time_outside_evaluation() {
        // Generation 0: walks 3, 1, 1, 1, 2 and 0.5 s outside; generation 1: walks 2, 2, 2
        // and 0.5 s outside; 5 + 3 = 8 evaluations.
        let profile = [
            generation(&[3.0, 1.0, 1.0, 1.0, 2.0], 0.5, 5),
            generation(&[2.0, 2.0, 2.0], 0.5, 3),
        ];
        let one = predict(
            &profile,
            Machine {
                ranks: 1,
                threads: 1,
            },
            Levers::default(),
        );
        // 8.5 + 6.5 = 15 s.
        assert_eq!(one.seconds, 15.0);
        assert_eq!(one.evaluations_per_second, 8.0 / 15.0);
        assert_eq!(one.walking_share, 1.0);
        let two = predict(
            &profile,
            Machine {
                ranks: 1,
                threads: 2,
            },
            Levers::default(),
        );
        // 5 + 0.5, then 2 + 2 on one thread: 4 + 0.5; 10 s.
        assert_eq!(two.seconds, 10.0);
        assert_eq!(two.walking_seconds, 9.0);
        assert_eq!(two.evaluations_per_second, 0.8);
        // 14 s of walks on 2 threads × 9 s.
        assert_eq!(two.walking_share, 14.0 / 18.0);
        // 2 ranks × 2 threads are 4 threads: 3 + 0.5, 2 + 0.5.
        let four = predict(
            &profile,
            Machine {
                ranks: 2,
                threads: 2,
            },
            Levers::default(),
        );
        assert_eq!(four.seconds, 6.0);
        // The profile's own figures: 14 s of walks and 1 s outside, measured at 8 / 15.
        let r = recorded(&profile);
        assert_eq!((r.walks, r.walk_seconds, r.outside_seconds), (8, 14.0, 1.0));
        assert_eq!(r.evaluations_per_second, 8.0 / 15.0);
    }

    #[test]
    fn the_levers_reorder_the_walks_and_move_the_fine_re_walk_into_the_next_batch() {
        // Generation 0: walks of 1, 1, 1 and 3 s by creatures of 2, 2, 3 and 9 parts, 0.5 s
        // outside evaluation of which 0.4 s the fine re-walk; generation 1: walks of 2 and 2 s
        // (4 and 4 parts), 0.5 s outside of which 0.4 s fine.
        let mut g0 = generation(&[1.0, 1.0, 1.0, 3.0], 0.5, 4);
        for (w, parts) in g0.walks.iter_mut().zip([2, 2, 3, 9]) {
            w.parts = parts;
        }
        g0.fine = 0.4;
        let mut g1 = generation(&[2.0, 2.0], 0.5, 2);
        for w in &mut g1.walks {
            w.parts = 4;
        }
        g1.fine = 0.4;
        let profile = [g0, g1];
        let two = Machine {
            ranks: 1,
            threads: 2,
        };
        // As recorded: 1 | 1, then 1 to the first free (A, 1-2), 3 to B (1-4): 4 s; then 2 |
        // 2: 2 s. 6 s of walking + 1 s outside.
        let plain = predict(&profile, two, Levers::default());
        assert_eq!((plain.walking_seconds, plain.seconds), (6.0, 7.0));
        // Longest first: 3 (9 parts) to A, then 1 (3 parts), 1, 1 to B: 3 s; then 2 | 2.
        let longest = Levers {
            longest_first: true,
            fine_beside: false,
        };
        assert_eq!(
            replayed(&profile, longest)[0],
            (vec![3.0, 1.0, 1.0, 1.0], 0.5)
        );
        let p = predict(&profile, two, longest);
        assert_eq!((p.walking_seconds, p.seconds), (5.0, 6.0));
        // Fine beside: generation 0's 0.4 s leaves its 0.5 s outside (0.1 s left) and walks
        // first in generation 1's batch: 0.4 | 2, then 2 to A (0.4-2.4): 2.4 s. The last
        // generation's fine re-walk stays outside (0.5 s).
        let beside = Levers {
            longest_first: false,
            fine_beside: true,
        };
        assert_eq!(replayed(&profile, beside)[1], (vec![0.4, 2.0, 2.0], 0.5));
        let p = predict(&profile, two, beside);
        assert!((p.walking_seconds - 6.4).abs() < 1e-12);
        assert!((p.seconds - 7.0).abs() < 1e-12);
        // Both: 3 s, then 2.4 s walking, 0.1 + 0.5 s outside: 6 s; 6 evaluations.
        let both = Levers {
            longest_first: true,
            fine_beside: true,
        };
        let p = predict(&profile, two, both);
        assert!((p.seconds - 6.0).abs() < 1e-12);
        assert!((p.evaluations_per_second - 1.0).abs() < 1e-12);
        // Walks 10 + 0.4 s on 2 threads × 5.4 s.
        assert!((p.walking_share - 10.4 / 10.8).abs() < 1e-12);
        // One thread: the levers only move time about: 10 s of walks, 0.4 + 0.4 of fine
        // re-walks and 0.2 s else: 11 s either way.
        let one = Machine {
            ranks: 1,
            threads: 1,
        };
        assert!((predict(&profile, one, both).seconds - 11.0).abs() < 1e-12);
        assert_eq!(predict(&profile, one, Levers::default()).seconds, 11.0);
        assert!(records_parts(&profile));
        assert!(!records_parts(&[generation(&[1.0], 0.0, 1)]));
    }

    #[test]
    fn machines_beyond_the_limits_are_refused_by_flag() {
        assert!(
            Machine {
                ranks: 1,
                threads: 1024
            }
            .check()
            .is_ok()
        );
        assert_eq!(
            Machine {
                ranks: 1,
                threads: 0
            }
            .check()
            .unwrap_err(),
            "--threads must be 1 to 1024, not 0"
        );
        assert_eq!(
            Machine {
                ranks: 1025,
                threads: 1
            }
            .check()
            .unwrap_err(),
            "--ranks must be 1 to 1024, not 1025"
        );
        assert_eq!(default_threads().last(), Some(&1024));
    }

    /// A generation whose walks are (individual, seconds), in the order handed out; every
    /// creature of 0 parts (not recorded).
    fn births_generation(
        walks: &[(u32, f64)],
        outside: f64,
        evaluations: u64,
    ) -> GenerationProfile {
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
                    parts: 0,
                })
                .collect(),
        }
    }

    const TWO: Machine = Machine {
        ranks: 1,
        threads: 2,
    };

    #[test]
    fn a_steady_state_replay_gives_the_hand_computed_times() {
        // A population of 2 (walks of 3 and 1 s), then generations of one birth (1 s each):
        // P = 2, C = 1; no time outside.
        let profile = [
            births_generation(&[(0, 3.0), (1, 1.0)], 0.0, 2),
            births_generation(&[(0, 1.0)], 0.0, 1),
            births_generation(&[(0, 1.0)], 0.0, 1),
            births_generation(&[(0, 1.0)], 0.0, 1),
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
        let generational = predict(&profile, TWO, Default::default());
        assert_eq!(generational.seconds, 6.0);
        // Blocks of 2 (P = C = 2): birth 3 is bred from generation 0 like birth 2, even with
        // one in flight: 3-4 on both threads.
        let pairs = [
            births_generation(&[(0, 3.0), (1, 1.0)], 0.0, 2),
            births_generation(&[(0, 1.0), (1, 1.0)], 0.0, 2),
        ];
        assert_eq!(predict_steady(&pairs, TWO, 1).seconds, 4.0);
    }

    #[test]
    fn the_driver_s_time_is_serial_before_each_birth_is_handed_out() {
        // 4 births of one 1-s walk; 0.8 s outside in all: 0.2 s a birth on the driver.
        let profile = [births_generation(
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
        assert!((predict(&profile, four, Default::default()).seconds - 1.8).abs() < 1e-12);
        // A driver of 0.05 s an evaluation in place of the recorded time.
        let cheap = super::super::steady_schedule::with_driver(&profile, 0.05);
        assert!((cheap[0].outside_evaluation() - 0.2).abs() < 1e-12);
        assert!((predict_steady(&cheap, four, 4).seconds - 1.2).abs() < 1e-12);
    }
}
