//! "Did you mean ...?": the known name closest to a misspelt one, for messages about a name
//! that is not one of a fixed few (an encoding, a task, a preset, a key of a config file).

/// The name of `names` closest to `word` (fewest letters inserted, deleted, replaced or two
/// neighbours swapped, ignoring case), when it is close enough to be what was meant: at most
/// one edit for a word of up to four letters, and one more for every four letters after.
/// The first of equally close names wins.
pub fn closest<'a>(word: &str, names: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let word = word.to_lowercase();
    let most = 1 + word.chars().count().saturating_sub(1) / 4;
    names
        .into_iter()
        .map(|name| (edit_distance(&word, &name.to_lowercase()), name))
        .filter(|&(distance, _)| distance <= most)
        .min_by_key(|&(distance, _)| distance)
        .map(|(_, name)| name)
}

/// " (did you mean NAME?)" after a message about `word`, or nothing when no name of `names` is
/// close to it ([`closest`]).
pub fn did_you_mean<'a>(word: &str, names: impl IntoIterator<Item = &'a str>) -> String {
    closest(word, names).map_or(String::new(), |name| format!(" (did you mean {name}?)"))
}

/// The optimal string alignment distance between `a` and `b`: the fewest characters inserted,
/// deleted or replaced, or neighbours swapped, that make one the other.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    // rows[i][j]: the distance between a[..i] and b[..j].
    let mut rows = vec![vec![0; b.len() + 1]; a.len() + 1];
    for (i, row) in rows.iter_mut().enumerate() {
        row[0] = i;
    }
    rows[0] = (0..=b.len()).collect();
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let replace = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (rows[i - 1][j] + 1)
                .min(rows[i][j - 1] + 1)
                .min(rows[i - 1][j - 1] + replace);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(rows[i - 2][j - 2] + 1);
            }
            rows[i][j] = best;
        }
    }
    rows[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slip_of_the_keyboard_finds_the_name_meant() {
        let encodings = ["lsystem", "lsystem-continuous", "direct", "graph"];
        assert_eq!(closest("lsytem", encodings), Some("lsystem"));
        assert_eq!(closest("Graph", encodings), Some("graph"));
        assert_eq!(closest("drect", encodings), Some("direct"));
        assert_eq!(closest("fst", ["fast", "default", "fine"]), Some("fast"));
        assert_eq!(closest("walkre", ["walker", "jump"]), Some("walker"));
    }

    #[test]
    fn a_word_far_from_every_name_gets_no_suggestion() {
        assert_eq!(
            closest("banana", ["walker", "jump", "catapult", "aim"]),
            None
        );
        assert_eq!(closest("ab", ["aim"]), None);
        assert_eq!(did_you_mean("banana", ["walker"]), "");
        assert_eq!(
            did_you_mean("jmup", ["walker", "jump"]),
            " (did you mean jump?)"
        );
    }
}
