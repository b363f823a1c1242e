//! The integration tests, as one test binary: a module per concern, and the helpers they
//! share in [`util`]. One binary links the library (and rapier) once, where a binary per
//! file would link it once per file.
//!
//! Run one concern with a filter on its module: `cargo test --release --test it -- cli::`.
//! Scratch files go under `CARGO_TARGET_TMPDIR` (`util::scratch_dir`). Proptest keeps the
//! failing cases it finds in `tests/proptest-regressions/MODULE.txt`, its default place for a
//! test binary whose `main.rs` is in `tests/it/`.

mod brain;
mod canalization;
mod cancel;
mod changing;
mod cli;
mod compare;
mod continuous;
mod defines;
mod derivation;
mod develop;
mod documents;
mod dt_independence;
mod errors;
mod evaluate;
mod evolve;
mod export;
mod fidelity;
mod files;
mod findings;
mod fitness_expression;
mod ga;
mod genome_continuous;
mod genome_direct;
mod genome_graph;
mod genome_limits_common;
mod genome_lsystem;
mod genome_lsystem_repeat;
mod genome_plastic;
mod genome_plastic_lsystem;
mod grow_while_walking;
mod growing_shown;
mod growth_honesty;
mod habitats;
mod json;
mod key;
mod limits;
mod long_runs;
mod mirroring;
#[cfg(feature = "mpi")]
mod mpi;
mod never_panics;
mod old_release;
mod outputs;
mod plasticity;
mod profile;
mod projectile;
mod render;
mod rooms;
mod store;
mod stubs;
mod sustained;
mod swim;
mod task_tables;
mod textbook;
mod util;
mod view;
mod worlds;
