//! Numbers for people to read, in every room's messages and pictures: the shortest decimal
//! that a value differs from only by rounding error.

/// A number for people to read: exact values as Rust prints them, values that differ from a
/// short decimal only by rounding error (`1.9999999999999998`) as that decimal (`2`).
pub fn format_number(v: f64) -> String {
    let short = format!("{v:.9}");
    let short = short.trim_end_matches('0').trim_end_matches('.');
    let short = if short == "-0" { "0" } else { short };
    match short.parse::<f64>() {
        Ok(s) if (s - v).abs() <= 1e-12 * v.abs().max(1.0) => short.to_string(),
        _ => format!("{v}"),
    }
}

/// Numbers for people to read ([`format_number`]), separated by spaces: `0 0.5`.
pub fn format_numbers(values: &[f64]) -> String {
    let words: Vec<String> = values.iter().map(|&v| format_number(v)).collect();
    words.join(" ")
}
