//! A genome file developed in each of several habitats (`ontogeny genome show --habitats`):
//! the creature each habitat's chemical array grows ([`Genome::develop_in`]), and how the
//! creatures of every pair of habitats differ ([`phenotype_differences`]), so that a genome
//! whose body depends on its environment can be told from one whose body does not.

use std::path::Path;

use super::show::{develops_into, read_genome_file};
use super::{DevelopError, Genome, ShowError};
use crate::creature::{Creature, PhenotypeDifferences, Summary, phenotype_differences};
use crate::environment::Environment;
use crate::number::format_numbers;

/// A habitat as the genome sees it: its name and the initial values of its chemical array
/// (none: the genome's own).
#[derive(Clone, Debug, PartialEq)]
pub struct HabitatArray {
    /// The habitat's name.
    pub name: String,
    /// Its array's initial values, if it gives one.
    pub environment: Option<Vec<f64>>,
}

/// The creature a genome grows in one habitat, or why it grows none.
#[derive(Clone, Debug)]
pub struct HabitatCreature {
    /// The habitat.
    pub habitat: HabitatArray,
    /// The creature, or why the genome does not develop there.
    pub creature: Result<Creature, String>,
}

/// A genome developed in each habitat: the creatures, and the differences of every pair.
#[derive(Clone, Debug)]
pub struct HabitatPhenotypes {
    /// The genome file, as named.
    pub file: String,
    /// The encoding that reads it.
    pub encoding: &'static str,
    /// One creature per habitat, in the habitats' order.
    pub creatures: Vec<HabitatCreature>,
    /// For every pair (i, j), i < j, of habitats where the genome develops: how the creature
    /// of j differs from that of i.
    pub pairs: Vec<(usize, usize, PhenotypeDifferences)>,
}

impl HabitatPhenotypes {
    /// Whether some pair of habitats grows different creatures.
    pub fn depends_on_habitat(&self) -> bool {
        self.pairs.iter().any(|(_, _, d)| !d.is_same())
    }

    /// The verdict, a line: `the body depends on the habitat`, or `the same body in every
    /// habitat`.
    pub fn verdict(&self) -> &'static str {
        if self.depends_on_habitat() {
            "the body depends on the habitat"
        } else {
            "the same body in every habitat"
        }
    }

    /// As `ontogeny genome show --habitats` prints it: a line naming the file, then a line
    /// per habitat (what the genome develops into there), a line per pair of habitats (how
    /// their creatures differ), and the verdict.
    pub fn text(&self) -> String {
        let mut lines = vec![format!(
            "{}: {} genome, developed in {} habitat(s)",
            self.file,
            self.encoding,
            self.creatures.len()
        )];
        for c in &self.creatures {
            let grown = match &c.creature {
                Ok(creature) => develops_into(creature).replace('\n', "\n  "),
                Err(e) => format!("does not develop: {e}"),
            };
            lines.push(format!(
                "habitat {} ({}): {grown}",
                c.habitat.name,
                array_text(c.habitat.environment.as_deref())
            ));
        }
        for (i, j, d) in &self.pairs {
            lines.push(format!(
                "{} -> {}: {d}",
                self.creatures[*i].habitat.name, self.creatures[*j].habitat.name
            ));
        }
        lines.push(self.verdict().to_string());
        lines.join("\n")
    }

    /// As `ontogeny genome show --habitats --json` prints it: `{"file", "encoding",
    /// "habitats": [{"name", "environment" (null: the genome's own), "develops", "creature"
    /// (summarised as grow --json does, without its file, time and frames; null when it
    /// does not develop), "error"}], "differences": [{"from", "to", "same", "parts",
    /// "joints", "neurons", "links", "volume" (each [from's, to's]), "resized",
    /// "largest_resize", "summed_resize", "moved", "joints_of_another_kind", "text"}],
    /// "depends_on_habitat",
    /// "verdict"}`.
    pub fn json(&self) -> serde_json::Value {
        let habitats: Vec<serde_json::Value> = self
            .creatures
            .iter()
            .map(|c| {
                let creature = c.creature.as_ref().ok().map(|c| {
                    let mut summary = serde_json::to_value(Summary::of("", 0.0, 1, c))
                        .expect("a summary is plain data");
                    if let Some(map) = summary.as_object_mut() {
                        for key in ["file", "t", "frames"] {
                            map.remove(key);
                        }
                    }
                    summary
                });
                serde_json::json!({
                    "name": c.habitat.name,
                    "environment": c.habitat.environment,
                    "develops": c.creature.is_ok(),
                    "creature": creature,
                    "error": c.creature.as_ref().err(),
                })
            })
            .collect();
        let differences: Vec<serde_json::Value> = self
            .pairs
            .iter()
            .map(|(i, j, d)| {
                serde_json::json!({
                    "from": self.creatures[*i].habitat.name,
                    "to": self.creatures[*j].habitat.name,
                    "same": d.is_same(),
                    "parts": [d.parts.0, d.parts.1],
                    "joints": [d.joints.0, d.joints.1],
                    "neurons": [d.neurons.0, d.neurons.1],
                    "links": [d.links.0, d.links.1],
                    "volume": [d.volume.0, d.volume.1],
                    "resized": d.resized,
                    "largest_resize": d.largest_resize,
                    "summed_resize": d.summed_resize,
                    "moved": d.moved,
                    "joints_of_another_kind": d.joints_of_another_kind,
                    "text": d.to_string(),
                })
            })
            .collect();
        serde_json::json!({
            "file": self.file,
            "encoding": self.encoding,
            "habitats": habitats,
            "differences": differences,
            "depends_on_habitat": self.depends_on_habitat(),
            "verdict": self.verdict(),
        })
    }
}

/// An array for people: `environment 0 0.5`, or `its own environment`.
fn array_text(values: Option<&[f64]>) -> String {
    match values {
        Some(v) => format!("environment {}", format_numbers(v)),
        None => "its own environment".to_string(),
    }
}

/// The genome file `path` holding `text` (any encoding's, recognised as `genome show`
/// recognises it), developed with its encoding's default limits and development seed 0 in
/// each of `habitats`. `Err` when the file is no genome, or a habitat's array has another
/// size than the genome's own (naming the habitat).
pub fn develop_in_habitat_arrays(
    path: &Path,
    text: &str,
    habitats: &[HabitatArray],
) -> Result<HabitatPhenotypes, ShowError> {
    let shown = read_genome_file(path, text)?;
    let creatures = crate::with_genome!(shown.encoding, G => creatures::<G>(text, habitats),
        |other| Err(DevelopError(format!("unknown encoding '{other}'"))))
    .map_err(|e| ShowError::NotAGenome(format!("{}: {e}", path.display())))?;
    let mut pairs = Vec::new();
    for i in 0..creatures.len() {
        for j in i + 1..creatures.len() {
            if let (Ok(a), Ok(b)) = (&creatures[i].creature, &creatures[j].creature) {
                pairs.push((i, j, phenotype_differences(a, b)));
            }
        }
    }
    Ok(HabitatPhenotypes {
        file: path.display().to_string(),
        encoding: shown.encoding,
        creatures,
        pairs,
    })
}

/// The creature genome `text`, of type `G`, grows in each habitat; `Err` when a habitat's
/// array does not fit the genome's.
fn creatures<G: Genome>(
    text: &str,
    habitats: &[HabitatArray],
) -> Result<Vec<HabitatCreature>, DevelopError> {
    let limits = G::Limits::default();
    let genome = G::read_text(text, &limits)?;
    let own = genome.environment().len();
    habitats
        .iter()
        .map(|h| {
            let creature = match &h.environment {
                Some(values) => {
                    if own != 0 && values.len() != own {
                        return Err(DevelopError(format!(
                            "habitat {}'s environment has {} slot(s); the genome develops in \
                             an environment of {own}",
                            h.name,
                            values.len()
                        )));
                    }
                    genome.develop_in(&limits, 0, &Environment::new(values.clone()))
                }
                None => genome.develop(&limits, 0),
            };
            Ok(HabitatCreature {
                habitat: h.clone(),
                creature: creature.map_err(|e| e.to_string()),
            })
        })
        .collect()
}
