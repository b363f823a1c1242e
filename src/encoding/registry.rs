//! The registry of encodings: the one list of the genome types a run can evolve, from which
//! the table of their names and descriptions ([`ENCODINGS`]) and the dispatch from a name to a
//! type ([`with_genome!`](crate::with_genome)) derive. Adding an encoding is its folder or
//! file in `encoding/` and one line in [`for_each_encoding!`](crate::for_each_encoding).

use super::Genome;

/// What can be known of an encoding without its type: for the command line's lists and help,
/// and for reading a run's configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EncodingInfo {
    /// Its name, as the CLI and the run store spell it ([`Genome::NAME`]).
    pub name: &'static str,
    /// One line for people ([`Genome::DESCRIPTION`]).
    pub description: &'static str,
    /// The extension of its text form ([`Genome::TEXT_EXTENSION`]).
    pub text_extension: &'static str,
    /// Keys of its limits added after runs had begun, with the value such a run ran with
    /// ([`Genome::LIMITS_OF_OLDER_RUNS`]).
    pub limits_of_older_runs: &'static [(&'static str, &'static str)],
}

impl EncodingInfo {
    /// The information of genome type `G`.
    pub const fn of<G: Genome>() -> EncodingInfo {
        EncodingInfo {
            name: G::NAME,
            description: G::DESCRIPTION,
            text_extension: G::TEXT_EXTENSION,
            limits_of_older_runs: G::LIMITS_OF_OLDER_RUNS,
        }
    }
}

/// The registry: calls the macro `$callback` with its arguments, then `;` and every genome
/// type, one line each, in the order the command line lists them.
#[doc(hidden)]
#[macro_export]
macro_rules! for_each_encoding {
    ($callback:ident!($($args:tt)*)) => {
        $crate::$callback!($($args)*;
            $crate::encoding::LSystemGenome,
            $crate::encoding::ContinuousGenome,
            $crate::encoding::DirectGenome,
            $crate::encoding::GraphGenome
        )
    };
}

/// Runs `$body` with `$G` standing for the genome type of the encoding named `$name`, or
/// `$unknown(name)` when no encoding has that name:
/// `with_genome!(name, G => start::<G>(args), |other| Err(..))`.
#[macro_export]
macro_rules! with_genome {
    ($name:expr, $G:ident => $body:expr, $unknown:expr) => {
        $crate::for_each_encoding!(__with_genome_arms!($name, $G => $body, $unknown))
    };
}

/// The arms of [`with_genome!`](crate::with_genome), one per genome type.
#[doc(hidden)]
#[macro_export]
macro_rules! __with_genome_arms {
    ($name:expr, $G:ident => $body:expr, $unknown:expr; $($genome:path),*) => {
        match $name {
            $(n if n == <$genome as $crate::encoding::Genome>::NAME => {
                type $G = $genome;
                $body
            })*
            other => $unknown(other),
        }
    };
}

/// The table of [`ENCODINGS`], one row per genome type.
#[doc(hidden)]
#[macro_export]
macro_rules! __encoding_table {
    (; $($genome:path),*) => {
        [$($crate::encoding::EncodingInfo::of::<$genome>()),*]
    };
}

/// Every encoding, in the registry's order.
pub const ENCODINGS: &[EncodingInfo] = &crate::for_each_encoding!(__encoding_table!());

/// The encoding named `name`.
pub fn encoding_named(name: &str) -> Option<&'static EncodingInfo> {
    ENCODINGS.iter().find(|e| e.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encoding::{ContinuousGenome, DirectGenome, GraphGenome, LSystemGenome};

    #[test]
    fn every_encoding_is_listed_once_and_dispatches_to_its_own_type() {
        let names: Vec<&str> = ENCODINGS.iter().map(|e| e.name).collect();
        assert_eq!(
            names,
            [
                LSystemGenome::NAME,
                ContinuousGenome::NAME,
                DirectGenome::NAME,
                GraphGenome::NAME
            ]
        );
        for e in ENCODINGS {
            assert!(!e.description.is_empty(), "{}", e.name);
            let dispatched = crate::with_genome!(e.name, G => G::NAME, |_| "none");
            assert_eq!(dispatched, e.name);
        }
        assert_eq!(
            crate::with_genome!("nothing", G => G::NAME, |n| n),
            "nothing"
        );
        assert_eq!(
            encoding_named("graph").map(|e| e.text_extension),
            Some("json")
        );
    }
}
