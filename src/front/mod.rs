//! What the command line and the Python package share: the settings of a run or comparison
//! from flags or keyword arguments ([`settings`]), a task's flags ([`flags`]), and what is
//! said about runs and comparisons, as text ([`text`]) or as JSON ([`json`]), and a genome
//! developed in each habitat of a configuration ([`habitats`]).

pub mod flags;
pub mod habitats;
pub mod json;
pub mod settings;
pub mod start;
pub mod text;
