//! The evaluator's behaviour version: one number that changes whenever this program would
//! evaluate some genome differently (its development, the physics, a task's protocol or
//! fitness). The run store records it with every generation, and a run is not resumed or
//! extended by an ontogeny whose evaluator differs from the one that made its last
//! generation, so a run never mixes evaluations of two evaluators unknowingly.

/// This program's evaluator version. Raise it in a release that changes what any evaluation
/// gives (a development rule, a rapier upgrade that moves bodies differently, a task's
/// protocol or fitness formula); keep it when results stay the same bit for bit. Generations
/// stored before the version was recorded are taken as version 1.
///
/// Version 2: a creature that never comes to rest scores 0 (Chaumont et al. 3.3), not the
/// failure floor.
pub const EVALUATOR_VERSION: u32 = 2;
