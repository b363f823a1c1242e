//! Saying a repeated problem once: the same warning from every pass of a repeat block, or from
//! every frame of a growth, is one line with how many times it came up, in the order the
//! problems first arose.

use std::collections::HashMap;
use std::hash::Hash;

/// `lines` with each distinct line once, where it first appears, followed by how many times
/// it appeared when more than once: `warning: ... (5 times)`.
pub fn said_once(lines: impl IntoIterator<Item = String>) -> Vec<String> {
    counted(lines)
        .into_iter()
        .map(|(line, n)| match n {
            1 => line,
            n => format!("{line} ({n} times)"),
        })
        .collect()
}

/// Each distinct item of `items` once, in the order of first appearance, with how many times
/// it appeared.
pub fn counted<T: Eq + Hash + Clone>(items: impl IntoIterator<Item = T>) -> Vec<(T, usize)> {
    let mut out: Vec<(T, usize)> = Vec::new();
    let mut index: HashMap<T, usize> = HashMap::new();
    for item in items {
        match index.get(&item) {
            Some(&i) => out[i].1 += 1,
            None => {
                index.insert(item.clone(), out.len());
                out.push((item, 1));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_said_three_times_is_said_once_with_its_count_where_it_first_came() {
        let lines = ["a", "b", "a", "c", "a"].map(String::from);
        assert_eq!(said_once(lines), ["a (3 times)", "b", "c"]);
    }
}
