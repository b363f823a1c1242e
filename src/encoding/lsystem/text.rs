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
        out.push_str(&crate::encoding::projectile::text_line(self.projectile));
        out.push_str(&format!("derivation length: {}\n", self.derivation_length));
        if !self.environment.is_empty() {
            let values: Vec<String> = self.environment.iter().map(f64::to_string).collect();
            out.push_str(&format!("environment: {}\n", values.join(" ")));
        }
        let start: Vec<String> = self.start.iter().map(|v| format!("{v}")).collect();
        let read = self.productions.first().and_then(|p| p.read);
        let read = read
            .map(|slot| format!("{} ", read_text(slot)))
            .unwrap_or_default();
        if start.is_empty() {
            out.push_str(&format!("axiom: {read}P0\n\n"));
        } else {
            out.push_str(&format!("axiom: {read}P0({})\n\n", start.join(", ")));
        }
        for (i, p) in self.productions.iter().enumerate() {
            let context = p
                .read
                .map(|slot| format!("?E(1, {slot}, {READ_VALUE}) < "))
                .unwrap_or_default();
            for pair in &p.pairs {
                out.push_str(&format!("{context}P{i}{formal}"));
                if let Some(c) = pair.condition {
                    out.push_str(&format!(" : {}", c.text()));
                }
                out.push_str(" -->");
                out.push_str(&self.successor_text(&pair.successor));
                out.push('\n');
            }
        }
        out
    }

    /// A successor as text, each item after a space, with the read of a production that
    /// reads right before each call of it.
    pub(crate) fn successor_text(&self, successor: &[Item]) -> String {
        let mut out = String::new();
        for item in successor {
            out.push(' ');
            if let Item::Call(t, _) = item
                && let Some(slot) = self.productions.get(*t).and_then(|p| p.read)
            {
                out.push_str(&read_text(slot));
                out.push(' ');
            }
            push_item_text(item, &mut out);
        }
        out
    }
}

/// The read of `slot`, as a genome's text writes it before a call of a production that
/// reads.
pub(crate) fn read_text(slot: usize) -> String {
    format!("?E(1, {slot}, 0)")
}

/// Appends an item as the language writes it (`[`, `forward(0.5)`, `P1(n0 - 1, 2)`).
pub(crate) fn push_item_text(item: &Item, out: &mut String) {
    match item {
        Item::Push => out.push('['),
        Item::Pop => out.push(']'),
        Item::RepeatOpen => out.push('{'),
        Item::RepeatClose(n) => out.push_str(&format!("}}({n})")),
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
