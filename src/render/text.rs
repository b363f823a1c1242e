//! Text in pictures: the public-domain 8×8 bitmap font of `font8x8`, text fitted or wrapped to
//! a width, and the round lengths and labels of scale bars.

use tiny_skia::{PathBuilder, Pixmap, Rect, Transform};

use super::palette::{paint, solid};
use super::pen::fill;

/// Text that fits the 8×8 font: ASCII, with the symbols messages use spelt out.
fn ascii(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '−' | '–' | '—' => '-',
            '·' | '×' => '*',
            '²' => '2',
            '³' => '3',
            '°' => 'o',
            c if c.is_ascii() && !c.is_ascii_control() => c,
            _ => '?',
        })
        .collect()
}

/// The width in pixels of `text` drawn at `scale`.
pub(super) fn text_width(text: &str, scale: f32) -> f32 {
    text.chars().count() as f32 * 8.0 * scale
}

/// `text`, cut with "..." to fit `width` pixels at `scale`.
pub(super) fn fit(text: &str, width: f32, scale: f32) -> String {
    let text = ascii(text);
    let room = (width / (8.0 * scale)).floor().max(0.0) as usize;
    if text.len() <= room {
        text
    } else if room > 3 {
        format!("{}...", &text[..room - 3])
    } else {
        String::new()
    }
}

/// Draws `text` with its top left at `(x, y)`, each font pixel `scale` pixels square, on a
/// pale backing when `backing` is set.
pub(super) fn draw_text(
    pixmap: &mut Pixmap,
    (x, y): (f32, f32),
    text: &str,
    scale: f32,
    colour: [u8; 3],
    backing: bool,
) {
    let text = ascii(text);
    if text.is_empty() {
        return;
    }
    let (x, y) = (x.round(), y.round());
    if backing
        && let Some(rect) = Rect::from_xywh(
            x - 2.0,
            y - 2.0,
            text_width(&text, scale) + 4.0,
            8.0 * scale + 4.0,
        )
    {
        pixmap.fill_rect(
            rect,
            &paint(255, 255, 255, 215),
            Transform::identity(),
            None,
        );
    }
    let mut pb = PathBuilder::new();
    for (i, c) in text.bytes().enumerate() {
        let glyph = font8x8::legacy::BASIC_LEGACY[c as usize & 0x7f];
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                if bits >> col & 1 == 1
                    && let Some(r) = Rect::from_xywh(
                        x + (i * 8 + col) as f32 * scale,
                        y + row as f32 * scale,
                        scale,
                        scale,
                    )
                {
                    pb.push_rect(r);
                }
            }
        }
    }
    if let Some(path) = pb.finish() {
        let mut p = solid(colour);
        p.anti_alias = false;
        fill(pixmap, &path, &p, Transform::identity());
    }
}

/// The round length (1, 2 or 5 × a power of ten, in metres) whose bar is at most `room`
/// pixels long at `scale` pixels per metre.
pub(super) fn scale_bar_length(scale: f64, room: f64) -> f64 {
    let mut best = 1e-3;
    for exponent in -3..=4 {
        for m in [1.0, 2.0, 5.0] {
            let length = m * 10f64.powi(exponent);
            if length * scale <= room {
                best = length;
            }
        }
    }
    best
}

/// A length for a scale bar's label: "1 m", "50 cm", "5 mm".
pub(super) fn length_label(metres: f64) -> String {
    if metres >= 1.0 {
        format!("{} m", crate::number::format_number(metres))
    } else if metres >= 0.01 {
        format!("{} cm", (metres * 100.0).round())
    } else {
        format!("{} mm", (metres * 1000.0).round())
    }
}

/// `text` broken at spaces into lines of at most `width` characters (a longer word alone on
/// its line).
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if line.chars().count() + 1 + word.chars().count() <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// The most problems a picture lists before "... and N more".
pub(super) const MAX_LISTED: usize = 3;

/// The lines that list `items` (text and colour) in `rows` lines of `columns` characters:
/// repeated items once with how many times, each wrapped at spaces (its later lines indented),
/// at most [`MAX_LISTED`] of them, and "... and N more" (in the colour of the first left out)
/// for those that do not fit.
pub(super) fn listed_lines<C: Copy + PartialEq>(
    items: Vec<(String, C)>,
    columns: usize,
    rows: usize,
) -> Vec<(String, C)> {
    let mut grouped: Vec<(String, C, usize)> = Vec::new();
    for (text, colour) in items {
        match grouped.iter_mut().find(|g| g.0 == text && g.1 == colour) {
            Some(g) => g.2 += 1,
            None => grouped.push((text, colour, 1)),
        }
    }
    let total: usize = grouped.iter().map(|g| g.2).sum();
    let mut lines = Vec::new();
    let mut listed = 0;
    for (k, (text, colour, times)) in grouped.iter().enumerate() {
        let text = if *times > 1 {
            format!("{text} ({times} times)")
        } else {
            text.clone()
        };
        let mut wrapped = wrap(&text, columns.saturating_sub(2).max(1));
        for line in wrapped.iter_mut().skip(1) {
            line.insert_str(0, "  ");
        }
        let last = k + 1 == grouped.len();
        // Room for this item, and for the "more" line unless it is the last.
        let needed = wrapped.len() + usize::from(!last);
        if k >= MAX_LISTED || lines.len() + needed > rows {
            if rows > lines.len() {
                lines.push((format!("... and {} more", total - listed), *colour));
            }
            break;
        }
        lines.extend(wrapped.into_iter().map(|l| (l, *colour)));
        listed += times;
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_bars_take_round_lengths() {
        // 100 px per metre and 120 px of room: 1 m; 90 px: 50 cm; 1000 px: 10 m.
        assert_eq!(scale_bar_length(100.0, 120.0), 1.0);
        assert_eq!(scale_bar_length(100.0, 90.0), 0.5);
        assert_eq!(scale_bar_length(100.0, 1000.0), 10.0);
        assert_eq!(length_label(1.0), "1 m");
        assert_eq!(length_label(0.5), "50 cm");
        assert_eq!(length_label(0.005), "5 mm");
        assert_eq!(fit("a long label", 48.0, 1.0), "a l...");
        assert_eq!(ascii("D_p − D_t · 2"), "D_p - D_t * 2");
    }

    #[test]
    fn refusals_are_wrapped_at_spaces() {
        assert_eq!(
            wrap("self-intersecting: parts 0 and 3 interpenetrate", 20),
            ["self-intersecting:", "parts 0 and 3", "interpenetrate"]
        );
        assert_eq!(
            wrap("averyveryverylongword x", 5),
            ["averyveryverylongword", "x"]
        );
        assert!(wrap("", 5).is_empty());
    }

    #[test]
    fn long_lists_are_wrapped_grouped_and_cut_with_how_many_more() {
        let item = |t: &str| (t.to_string(), 0u8);
        // A long warning goes onto more lines, its later ones indented.
        let lines = listed_lines(
            vec![item("warning: the first part has nothing to be jointed to")],
            26,
            10,
        );
        let texts: Vec<&str> = lines.iter().map(|l| l.0.as_str()).collect();
        assert_eq!(
            texts,
            [
                "warning: the first part",
                "  has nothing to be",
                "  jointed to"
            ]
        );
        // The same warning 57 times is one line; ten different ones are three and the rest.
        let mut many = vec![item("warning: '}' unmatched"); 57];
        many.extend((0..10).map(|k| item(&format!("warning: {k}"))));
        let lines = listed_lines(many, 40, 30);
        let texts: Vec<&str> = lines.iter().map(|l| l.0.as_str()).collect();
        assert_eq!(
            texts,
            [
                "warning: '}' unmatched (57 times)",
                "warning: 0",
                "warning: 1",
                "... and 8 more"
            ]
        );
        // Too few rows: as many as fit with the last row saying how many more.
        let lines = listed_lines((0..4).map(|k| item(&format!("w{k}"))).collect(), 40, 3);
        let texts: Vec<&str> = lines.iter().map(|l| l.0.as_str()).collect();
        assert_eq!(texts, ["w0", "w1", "... and 2 more"]);
        // All that fit: no "more".
        assert_eq!(listed_lines(vec![item("a"), item("b")], 40, 2).len(), 2);
    }
}
