//! A champion's record: every input of the evaluation that gave a run's best its fitness (the
//! task specification with its `[task.sim]` values, the grammar seed and the development
//! limits), written into `best.lsys` as a comment line and into `best.json` as its
//! `"champion"` member, and read back by `ontogeny eval`, so that evaluating the file with no
//! flags repeats its fitness to the digit.

use serde::{Deserialize, Serialize};

use crate::task::TaskSpec;

/// The comment that carries the record in a genome's text form with `#` comments: the line
/// `# evaluation: {JSON}`.
pub const COMMENT_KEY: &str = "evaluation: ";

/// The member of a JSON genome (`best.json`) that carries the record (with the note).
pub const JSON_KEY: &str = crate::encoding::graph::CHAMPION_KEY;

/// Every input of a champion's evaluation, and the fitness it gave.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChampionRecord {
    /// The fitness the run stored for it.
    pub fitness: f64,
    /// The task, its settings and the simulator's (`[task.sim]`), as the run's config
    /// gives them.
    pub task: TaskSpec,
    /// The seed of the grammar's stochastic rules in development (the run's develop seed of
    /// this individual).
    pub grammar_seed: u64,
    /// Most parts a creature may have (the run's limit), where the encoding has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_parts: Option<usize>,
    /// Most modules a derived string may have (the run's limit), where the encoding has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_modules: Option<usize>,
}

impl ChampionRecord {
    /// A record of an evaluation of `task` giving `fitness`, developed with `grammar_seed`
    /// under the encoding's `limits` (their `max_parts` and `max_modules` kept, where they
    /// have them).
    pub fn new(fitness: f64, task: &TaskSpec, grammar_seed: u64, limits: &impl Serialize) -> Self {
        let limits = serde_json::to_value(limits).unwrap_or_default();
        let count = |key: &str| {
            limits
                .get(key)
                .and_then(serde_json::Value::as_u64)
                .map(|v| v as usize)
        };
        ChampionRecord {
            fitness,
            task: task.clone(),
            grammar_seed,
            max_parts: count("max_parts"),
            max_modules: count("max_modules"),
        }
    }

    /// The record as one line of JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// The note's lines followed by the record's comment line (`evaluation: {JSON}`), for a
    /// text form with comments.
    pub fn comment(&self, note: &str) -> String {
        format!("{note}\n{COMMENT_KEY}{}", self.to_json())
    }

    /// The champion file of `genome` with `note` and this record: in its `#` comments, or,
    /// for a genome written as JSON, in its `"champion"` member ([`ChampionRecord::into_json`]).
    pub fn file_text<G: crate::encoding::Genome>(&self, genome: &G, note: &str) -> String {
        if G::TEXT_EXTENSION == "json" {
            self.into_json(&genome.to_text(), note)
        } else {
            genome.annotated_text(&self.comment(note))
        }
    }

    /// The record in a genome's text, if it has one: in the `#` comments before its first
    /// other line, or, for JSON, in its `"champion"` member. `Err` says what is wrong with a
    /// record that is there but unreadable.
    pub fn of_text(text: &str) -> Result<Option<ChampionRecord>, String> {
        if text.trim_start().starts_with('{') {
            let Ok(serde_json::Value::Object(map)) = serde_json::from_str(text) else {
                return Ok(None);
            };
            return match map.get(JSON_KEY).and_then(|c| c.get("evaluation")) {
                Some(v) => serde_json::from_value(v.clone())
                    .map(Some)
                    .map_err(|e| format!("its champion record cannot be read: {e}")),
                None => Ok(None),
            };
        }
        for line in text.lines() {
            let Some(comment) = line.trim_start().strip_prefix('#') else {
                if line.trim().is_empty() {
                    continue;
                }
                break;
            };
            if let Some(json) = comment.trim_start().strip_prefix(COMMENT_KEY) {
                return serde_json::from_str(json)
                    .map(Some)
                    .map_err(|e| format!("its champion record cannot be read: {e}"));
            }
        }
        Ok(None)
    }

    /// The genome's text in `text`, a champion file in a text form with `#` comments: what
    /// follows the record's comment line ([`ChampionRecord::file_text`] writes the genome's
    /// [`crate::encoding::Genome::to_text`] there); all of `text` when it has no record.
    pub fn genome_text(text: &str) -> &str {
        let mut rest = text;
        while let Some((line, after)) = rest.split_once('\n') {
            let Some(comment) = line.trim_start().strip_prefix('#') else {
                if line.trim().is_empty() {
                    rest = after;
                    continue;
                }
                break;
            };
            if comment.trim_start().starts_with(COMMENT_KEY) {
                return after;
            }
            rest = after;
        }
        text
    }

    /// `json`, a genome's JSON object, with the member `"champion"` holding `note` and the
    /// record (`{"note": ..., "evaluation": {...}}`) first.
    pub fn into_json(&self, json: &str, note: &str) -> String {
        let Some(rest) = json.strip_prefix("{\n") else {
            return json.to_string();
        };
        let member = serde_json::json!({ "note": note, "evaluation": self });
        let member = serde_json::to_string_pretty(&member)
            .unwrap_or_default()
            .replace('\n', "\n  ");
        format!("{{\n  \"{JSON_KEY}\": {member},\n{rest}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::task::{TaskKind, TaskOptions, WalkerFitness, WalkerOptions};

    fn record() -> ChampionRecord {
        let mut task = TaskSpec::new(TaskKind::Walker);
        task.task = TaskOptions::Walker(WalkerOptions {
            fitness: WalkerFitness::Distance.into(),
            ..WalkerOptions::default()
        });
        task.sim.control_step = 1.0 / 60.0;
        ChampionRecord {
            fitness: 13.569980138461052,
            task,
            grammar_seed: u64::MAX,
            max_parts: Some(50),
            max_modules: Some(1000),
        }
    }

    #[test]
    fn a_record_reads_back_from_the_comment_it_writes_to_the_last_bit() {
        let r = record();
        let text = format!(
            "# {}\naxiom: A\n",
            r.comment("The best.").replace('\n', "\n# ")
        );
        let read = ChampionRecord::of_text(&text).unwrap().unwrap();
        assert_eq!(read.to_json(), r.to_json());
        assert_eq!(read.fitness.to_bits(), r.fitness.to_bits());
        assert!(
            ChampionRecord::of_text("axiom: A\n# evaluation: {}\n")
                .unwrap()
                .is_none()
        );
    }

    #[test]
    fn a_record_reads_back_from_a_json_genome_and_leaves_the_genome_as_it_was() {
        let r = record();
        let genome = "{\n  \"nodes\": [],\n  \"neurons\": []\n}\n";
        let text = r.into_json(genome, "The best.");
        assert!(text.starts_with("{\n  \"champion\": {"), "{text}");
        let read = ChampionRecord::of_text(&text).unwrap().unwrap();
        assert_eq!(read.to_json(), r.to_json());
        let value = |t: &str| serde_json::from_str::<serde_json::Value>(t).unwrap();
        assert_eq!(
            value(&crate::encoding::graph::without_champion(&text)),
            value(genome)
        );
        assert!(ChampionRecord::of_text(genome).unwrap().is_none());
    }

    #[test]
    fn a_champion_file_s_genome_text_is_what_follows_its_record() {
        let genome = "# a genome's own comment\ntime: 3\naxiom: A(0)\n";
        let file = format!("# note\n# evaluation: {{}}\n{genome}");
        assert_eq!(ChampionRecord::genome_text(&file), genome);
        // A file without a record is all genome, its comments included.
        assert_eq!(ChampionRecord::genome_text(genome), genome);
        let late = "time: 3\n# evaluation: {}\naxiom: A(0)\n";
        assert_eq!(ChampionRecord::genome_text(late), late);
    }

    #[test]
    fn a_damaged_record_is_named() {
        let e = ChampionRecord::of_text("# evaluation: {\"fitness\": 1}\naxiom: A\n").unwrap_err();
        assert!(
            e.starts_with("its champion record cannot be read: missing field `task`"),
            "{e}"
        );
    }
}
