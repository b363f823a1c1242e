//! The genetic algorithm on a toy genome: the presets' proportions, elitism, fallbacks for
//! missing operators, and bit-identical results on any number of threads.

use ontogeny::cancel::Cancel;
use ontogeny::creature::Creature;
use ontogeny::encoding::{DevelopError, Genome, Rng};
use ontogeny::evolve::cache::EvaluationCache;
use ontogeny::evolve::ga::{
    Evolution, Fallbacks, GaSettings, Individual, Operator, Preset, ranking, schedule,
};
use ontogeny::run::store::GenerationRecord;
use ontogeny::task::{Status, TaskKind, TaskSpec};
use rand::RngExt;
use serde::{Deserialize, Serialize};

/// A two-part creature: its limb length, its oscillator's output and a width.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct Toy {
    genes: [f64; 3],
}

#[derive(Clone, Debug, Default, Serialize, Deserialize)]
struct ToyLimits;

/// The toy has no limits to range.
impl ontogeny::encoding::CheckedLimits for ToyLimits {
    fn check_ranges(&self) -> Result<(), ontogeny::sim::SettingError> {
        Ok(())
    }
}

impl Genome for Toy {
    type Limits = ToyLimits;
    const NAME: &'static str = "toy";

    fn random(_: &ToyLimits, rng: &mut Rng) -> Self {
        Toy {
            genes: [
                rng.random_range(0.2..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(0.1..0.5),
            ],
        }
    }

    fn mutate(&self, _: &ToyLimits, rate: f64, rng: &mut Rng) -> Self {
        let mut genes = self.genes;
        for g in &mut genes {
            if rng.random_bool(rate) {
                *g = (*g + rng.random_range(-0.1..0.1)).clamp(0.1, 1.0);
            }
        }
        Toy { genes }
    }

    fn crossover(&self, other: &Self, _: &ToyLimits, rng: &mut Rng) -> Option<Self> {
        let cut = rng.random_range(0..3);
        let mut genes = self.genes;
        genes[cut..].copy_from_slice(&other.genes[cut..]);
        Some(Toy { genes })
    }

    fn develop(&self, _: &ToyLimits, _: u64) -> Result<Creature, DevelopError> {
        let [length, output, width] = self.genes;
        if length > 0.95 {
            return Err(DevelopError("too long".into()));
        }
        ontogeny::develop::creature_from_commands(&format!(
            "width({width:.3}) forward({length:.3}) revolute2 forward({length:.3}) output({output:.3})"
        ))
        .map_err(|e| DevelopError(e.to_string()))
    }

    fn to_text(&self) -> String {
        format!("{:?}", self.genes)
    }
}

fn evolution(preset: Preset, population: usize) -> Evolution<Toy> {
    let mut task = TaskSpec::new(TaskKind::Walker);
    *task.seconds_mut() = 0.5;
    Evolution {
        settings: GaSettings {
            population,
            generations: 3,
            ..GaSettings::preset(preset)
        },
        limits: ToyLimits,
        task,
        seed: 7,
        init: None,
        key_version: Default::default(),
        key_tables: None,
        walk_order: Default::default(),
    }
}

fn json<G: Serialize>(population: &[Individual<G>]) -> String {
    serde_json::to_string(population).unwrap()
}

#[test]
fn chaumont_proportions_are_exact() {
    // 240 children: 96 by mutation, 72 by crossover, 72 by grafting.
    let ops: Vec<Operator> = (0..240).map(|k| schedule(k, 240, 0.4, 0.3)).collect();
    let count = |op| ops.iter().filter(|&&o| o == op).count();
    assert_eq!(count(Operator::Mutation), 96);
    assert_eq!(count(Operator::Crossover), 72);
    assert_eq!(count(Operator::Graft), 72);
    let s = GaSettings::preset(Preset::Chaumont);
    assert_eq!((s.population, s.generations), (300, 100));
    assert_eq!(s.survivors(), 60);
    let w = GaSettings::preset(Preset::Wwd);
    assert_eq!((w.survivors(), w.breeder_count()), (60, 90));
}

#[test]
fn a_generation_keeps_the_elite_and_makes_the_rest_by_the_schedule() {
    let evo = evolution(Preset::Chaumont, 20);
    let first = evo
        .first_generation(&mut EvaluationCache::new(true), &Cancel::new())
        .unwrap();
    assert_eq!(first.len(), 20);
    assert!(first.iter().all(|i| i.operator == Operator::Random));
    let mut fallbacks = Fallbacks::default();
    let (next, evaluations) = evo
        .next_generation(
            &first,
            1,
            &mut fallbacks,
            &mut EvaluationCache::new(true),
            &Cancel::new(),
        )
        .unwrap();
    assert_eq!(next.len(), 20);
    // 20% elite: 4 kept, not evaluated again, best first and unchanged.
    assert_eq!(evaluations, 16);
    let order = ranking(&first);
    for (k, i) in next[..4].iter().enumerate() {
        assert_eq!(i.operator, Operator::Elite);
        assert_eq!(i.parents, vec![order[k] as u32]);
        assert_eq!(i.genome, first[order[k]].genome);
        assert_eq!(i.evaluation, first[order[k]].evaluation);
    }
    // 16 children: 6 (round 6.4) by mutation, 5 (round 4.8) by crossover, 5 grafts, which the
    // toy genome lacks: made by mutation instead, and counted.
    let count = |op| next[4..].iter().filter(|i| i.operator == op).count();
    assert_eq!(count(Operator::Crossover), 5);
    assert_eq!(count(Operator::Mutation), 11);
    assert_eq!(count(Operator::Graft), 0);
    assert_eq!(fallbacks.graft, 5);
    // Parents come from the elite only.
    let elite: Vec<u32> = order[..4].iter().map(|&i| i as u32).collect();
    assert!(
        next[4..]
            .iter()
            .all(|i| i.parents.iter().all(|p| elite.contains(p)))
    );
}

#[test]
fn a_developmental_error_is_an_invalid_evaluation_at_the_failure_floor() {
    let evo = evolution(Preset::Chaumont, 4);
    let bad = Toy {
        genes: [0.99, 0.5, 0.2],
    };
    let init = Evolution {
        init: Some(bad),
        ..evo
    };
    let first = init
        .first_generation(&mut EvaluationCache::new(true), &Cancel::new())
        .unwrap();
    assert_eq!(first[0].operator, Operator::Init);
    assert_eq!(first[0].evaluation.status, Status::Invalid);
    assert_eq!(first[0].evaluation.fitness, ontogeny::task::FAILURE_FITNESS);
    assert_eq!(first[0].size, (0, 0, 0));
    let stats = GenerationRecord::of(&first, 4);
    assert!(stats.valid_fraction < 1.0);
}

#[test]
fn runs_are_identical_on_one_and_two_threads() {
    for preset in [Preset::Chaumont, Preset::Wwd] {
        let evo = evolution(preset, 10);
        let go = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut population = evo
                    .first_generation(&mut EvaluationCache::new(true), &Cancel::new())
                    .unwrap();
                let mut out = vec![json(&population)];
                for g in 1..3 {
                    population = evo
                        .next_generation(
                            &population,
                            g,
                            &mut Fallbacks::default(),
                            &mut EvaluationCache::new(true),
                            &Cancel::new(),
                        )
                        .unwrap()
                        .0;
                    out.push(json(&population));
                }
                out
            })
        };
        assert_eq!(go(1), go(2), "{preset:?}");
    }
}

#[test]
fn generation_stats_by_hand() {
    let evo = evolution(Preset::Chaumont, 4);
    let mut p = evo
        .first_generation(&mut EvaluationCache::new(true), &Cancel::new())
        .unwrap();
    let fitness = [3.0, 1.0, 2.0, 4.0];
    for (i, f) in p.iter_mut().zip(fitness) {
        i.evaluation.fitness = f;
        i.evaluation.status = Status::Ok;
    }
    p[3].evaluation.status = Status::Unstable;
    p[3].evaluation.fitness = ontogeny::task::FAILURE_FITNESS;
    let s = GenerationRecord::of(&p, 4);
    assert_eq!(s.best, 3.0);
    assert_eq!(s.mean, 2.0);
    assert_eq!(s.median, 2.0);
    assert!((s.sd - (2.0f64 / 3.0).sqrt()).abs() < 1e-12);
    assert_eq!(s.valid_fraction, 0.75);
}

#[test]
fn newborns_whose_parts_collide_are_made_again_as_chaumont_made_them() {
    // Chaumont et al. 5.5: "If such collisions occur, the creature is eliminated and the
    // system generates a new one until it finds a valid candidate." About 40% of random
    // `lsystem` genomes build bodies whose parts interpenetrate; with ten tries, none of a
    // first generation of 60 does, on one thread or two, and with one try as many as before.
    use ontogeny::encoding::LSystemGenome;
    let first_generation = |regenerate: usize, threads: usize| {
        let mut task = TaskSpec::new(TaskKind::Walker);
        *task.seconds_mut() = 0.1;
        let evo = Evolution::<LSystemGenome> {
            settings: GaSettings {
                population: 60,
                regenerate,
                ..GaSettings::preset(Preset::Chaumont)
            },
            limits: Default::default(),
            task,
            seed: 11,
            init: None,
            key_version: Default::default(),
            key_tables: None,
            walk_order: Default::default(),
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            evo.first_generation(&mut EvaluationCache::new(true), &Cancel::new())
                .unwrap()
        })
    };
    let colliding = |population: &[Individual<LSystemGenome>]| {
        population
            .iter()
            .filter(|i| i.evaluation.status == Status::SelfIntersecting)
            .count()
    };
    let once = first_generation(1, 1);
    assert!(colliding(&once) >= 12, "{} of 60", colliding(&once));
    let regenerated = first_generation(10, 1);
    assert_eq!(colliding(&regenerated), 0);
    // A newborn that did not collide at the first try is the same genome either way: the
    // tries draw on from its own random stream.
    for (a, b) in once.iter().zip(&regenerated) {
        if a.evaluation.status != Status::SelfIntersecting {
            assert_eq!(json(std::slice::from_ref(a)), json(std::slice::from_ref(b)));
        }
    }
    assert_eq!(json(&regenerated), json(&first_generation(10, 2)));
}

#[test]
fn a_configuration_without_the_regenerate_key_makes_each_newborn_once() {
    // Runs stored before the key existed resume as they ran; Chaumont's preset writes 10.
    let mut settings: GaSettings =
        toml::from_str(&toml::to_string(&GaSettings::preset(Preset::Chaumont)).unwrap()).unwrap();
    assert_eq!(settings.regenerate, 10);
    let text = toml::to_string(&GaSettings {
        regenerate: 1,
        ..settings.clone()
    })
    .unwrap();
    assert!(!text.contains("regenerate"), "{text}");
    settings = toml::from_str(&text).unwrap();
    assert_eq!(settings.regenerate, 1);
    assert_eq!(GaSettings::preset(Preset::Wwd).regenerate, 1);
    let refused = GaSettings {
        regenerate: 0,
        ..GaSettings::preset(Preset::Chaumont)
    };
    assert!(
        refused
            .check()
            .unwrap_err()
            .to_string()
            .contains("regenerate")
    );
}
