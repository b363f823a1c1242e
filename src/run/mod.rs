//! A run of the genetic algorithm in its directory: its lifecycle (start, resume, one
//! generation after another: [`Run`]), its configuration ([`config`], its errors in words:
//! [`config_errors`]), its folder ([`folder`]), its database ([`store`], the only code that
//! knows SQL), the lock that keeps a directory one process's ([`lock`]), the record of a
//! champion's evaluation in its file ([`champion`]), its fitness plot ([`plot`]) with the
//! spread of each generation's best over its habitats and trials ([`spread`]), an
//! individual picked by rank ([`pick`]), and where its generations' time went, when it is
//! profiled ([`profile`]).

pub mod champion;
pub mod config;
pub mod config_errors;
pub mod folder;
mod lifecycle;
pub mod lock;
pub mod pick;
pub mod plot;
pub mod profile;
pub mod spread;
pub mod store;

pub use lifecycle::*;
