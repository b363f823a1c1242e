//! What the command line and the Python package share: the settings of a run or comparison
//! from flags or keyword arguments ([`settings`]), a task's flags ([`flags`]), and what is
//! said about runs and comparisons, as text ([`text`]) or as JSON ([`json`]).

pub mod flags;
pub mod json;
pub mod settings;
pub mod text;
