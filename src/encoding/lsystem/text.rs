//! The L-system genome as text: the printed `.lsys` file (a genome read from a hand-written
//! one is `seed`'s).

use super::*;

impl LSystemGenome {
    /// The genome as a valid `.lsys` file.
    pub(super) fn text(&self) -> String {
        let params: Vec<String> = (0..self.start.len()).map(|i| format!("n{i}")).collect();
        let formal = if params.is_empty() {
            String::new()
        } else {
            format!("({})", params.join(", "))
        };
        let mut out = String::new();
        out.push_str(&format!(
            "# An L-system genome (Hornby & Pollack 2001): {} production(s) of {} parameter(s).\n",
            self.productions.len(),
            self.start.len()
        ));
        out.push_str(&format!("derivation length: {}\n", self.derivation_length));
        let start: Vec<String> = self.start.iter().map(|v| format!("{v}")).collect();
        if start.is_empty() {
            out.push_str("axiom: P0\n\n");
        } else {
            out.push_str(&format!("axiom: P0({})\n\n", start.join(", ")));
        }
        for (i, p) in self.productions.iter().enumerate() {
            for pair in &p.pairs {
                out.push_str(&format!("P{i}{formal}"));
                if let Some(c) = pair.condition {
                    out.push_str(&format!(
                        " : n{} {} {}",
                        c.param,
                        c.compare.symbol(),
                        c.value
                    ));
                }
                out.push_str(" -->");
                for item in &pair.successor {
                    out.push(' ');
                    push_item_text(item, &mut out);
                }
                out.push('\n');
            }
        }
        out
    }
}

/// Appends an item as the language writes it (`[`, `forward(0.5)`, `P1(n0 - 1, 2)`).
pub(crate) fn push_item_text(item: &Item, out: &mut String) {
    match item {
        Item::Push => out.push('['),
        Item::Pop => out.push(']'),
        Item::Command(c, None) => out.push_str(c.name()),
        Item::Command(c, Some(a)) => out.push_str(&format!("{}({})", c.name(), a.text())),
        Item::Call(t, args) if args.is_empty() => out.push_str(&format!("P{t}")),
        Item::Call(t, args) => {
            let args: Vec<String> = args.iter().map(Arg::text).collect();
            out.push_str(&format!("P{t}({})", args.join(", ")));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_print_as_the_language_reads_them() {
        assert_eq!(Arg::Const(-1.5).text(), "-1.5");
        assert_eq!(Arg::Plus(0, 0.0).text(), "n0");
        assert_eq!(Arg::Plus(1, -2.0).text(), "n1 - 2");
        assert_eq!(Arg::Plus(1, 0.25).text(), "n1 + 0.25");
        assert_eq!(Arg::Times(0, -1.0).text(), "n0 * -1");
    }
}
