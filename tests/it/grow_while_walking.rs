//! Growing while acting: a creature whose development goes on during the walk
//! (`develop = "during"`).

use std::sync::Arc;

use ontogeny::develop::BuildOptions;
use ontogeny::lsystem::{DeriveOptions, LSystem};
use ontogeny::task::{Growing, Phase, Status, TaskKind, TaskSpec, Watch};

const EXAMPLE: &str = "examples/grow-while-walking.lsys";

fn example() -> Arc<LSystem> {
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    Arc::new(LSystem::from_text(EXAMPLE, &text).unwrap())
}

/// A 2 s walk.
fn short_walk() -> TaskSpec {
    let mut spec = TaskSpec::new(TaskKind::Walker);
    *spec.seconds_mut() = 2.0;
    spec
}

/// The example evaluated growing from its first valid frame at one unit of developmental
/// time per second, recorded.
fn grown_walk() -> ontogeny::task::Evaluation {
    let mut growing = Growing::start(
        example(),
        &DeriveOptions::default(),
        &BuildOptions::default(),
        1.0,
        None,
    )
    .unwrap();
    let creature = growing.creature().clone();
    short_walk()
        .evaluate_growing(
            &creature,
            Watch::uncancelled(true, &mut |_| {}),
            Some(&mut growing),
        )
        .unwrap()
}

#[test]
fn a_creature_growing_during_the_walk_gains_parts_as_it_walks() {
    let evaluation = grown_walk();
    assert_eq!(evaluation.status, Status::Ok, "{evaluation:?}");
    // Dropped as two segments, it has them at the start of the walk; a pair of legs appears
    // half a second into the walk, another a second in.
    let counts: Vec<(Option<Phase>, usize)> = evaluation
        .recording
        .iter()
        .map(|s| (s.phase, s.parts.len()))
        .collect();
    assert!(
        counts
            .iter()
            .all(|&(phase, n)| phase == Some(Phase::Measuring) || n == 2)
    );
    let walking: Vec<usize> = counts
        .iter()
        .filter(|(phase, _)| *phase == Some(Phase::Measuring))
        .map(|&(_, n)| n)
        .collect();
    assert_eq!(walking.first(), Some(&2));
    assert!(walking.contains(&4));
    assert_eq!(walking.last(), Some(&6));
    assert!(walking.windows(2).all(|w| w[0] <= w[1]));
    assert_eq!(evaluation.terms["grown_parts"], 4.0);
    assert_eq!(evaluation.terms["grown_neurons"], 4.0);
    assert_eq!(evaluation.terms["grown_links"], 4.0);
    // The size terms are the body's at the start of the walk: two parts.
    assert_eq!(evaluation.terms["N"], 2.0);
}

#[test]
fn a_creature_growing_during_the_walk_walks_the_same_twice() {
    assert_eq!(grown_walk(), grown_walk());
}
