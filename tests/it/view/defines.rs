//! The defines of an `.lsys` page: `/data.json` grows the file with the values its query
//! sets (`?define.NAME=VALUE`), lists every define as a slider, and refuses a name the grammar
//! does not define; `view --define` opens the page at an address that carries the values.

use super::*;

/// A row of `PARTS` parts, `LENGTH` (which follows `PARTS`) long each, with a range for
/// `PARTS`.
const ROW: &str = "\
define PARTS = 2  # range 1..6 step 1
define LENGTH = PARTS * 0.25
axiom: S(PARTS)
derivation length: 6
S(n) : n > 0 --> forward(LENGTH) S(n - 1)
";

/// The grammar [`ROW`] in the scratch directory `name`.
pub(super) fn row_file(name: &str) -> PathBuf {
    let file = scratch(name).join("row.lsys");
    std::fs::write(&file, ROW).unwrap();
    file
}

/// The parts of the last frame of an `.lsys` page's data.
fn last_parts(data: &serde_json::Value) -> usize {
    let frames = data["frames"].as_array().unwrap();
    frames.last().unwrap()["creature"]["parts"]
        .as_array()
        .unwrap()
        .len()
}

#[test]
fn the_data_of_an_lsys_page_is_grown_with_the_defines_its_query_sets() {
    let viewer = Viewer::start(&row_file("defines-data"));
    let (status, body) = viewer.get("/data.json");
    assert_eq!(status, 200, "{body}");
    let data: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(last_parts(&data), 2);
    assert_eq!(
        data["defines"],
        serde_json::json!([
            {"name": "PARTS", "value": 2.0, "min": 1.0, "max": 6.0, "step": 1.0, "note": null, "set": false},
            {"name": "LENGTH", "value": 0.5, "min": 0.0, "max": 1.0, "step": 0.01, "note": null, "set": false},
        ])
    );
    // PARTS set to 4: four parts, LENGTH follows it (its slider's range widened to hold it).
    let (status, body) = viewer.get("/data.json?define.PARTS=4");
    assert_eq!(status, 200, "{body}");
    let data: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(last_parts(&data), 4);
    assert_eq!(
        data["defines"],
        serde_json::json!([
            {"name": "PARTS", "value": 4.0, "min": 1.0, "max": 6.0, "step": 1.0, "note": null, "set": true},
            {"name": "LENGTH", "value": 1.0, "min": 0.0, "max": 1.0, "step": 0.01, "note": null, "set": false},
        ])
    );
    // Escaped as a browser escapes it, and other keys left alone.
    let (status, body) = viewer.get("/data.json?frame=1&define.PARTS=3%2E0&define.LENGTH=1e%2B0");
    assert_eq!(status, 200, "{body}");
    let data: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(last_parts(&data), 3);
    assert_eq!(data["defines"][1]["value"], 1.0);
    assert_eq!(data["defines"][1]["set"], true);
}

#[test]
fn a_define_the_grammar_lacks_or_a_value_that_is_no_number_is_a_bad_request() {
    let file = row_file("defines-refused");
    let viewer = Viewer::start(&file);
    let (status, body) = viewer.get("/data.json?define.PART=4");
    assert_eq!(status, 400);
    let message = format!(
        "{}: cannot set PART: the grammar has no define by that name (did you mean PARTS?); \
         its defines are PARTS, LENGTH",
        file.display()
    );
    assert_eq!(
        body,
        serde_json::json!({"error": {"message": message}}).to_string()
    );
    let (status, body) = viewer.get("/data.json?define.PARTS=many");
    assert_eq!(status, 400);
    assert_eq!(
        body,
        r#"{"error":{"message":"define.PARTS=many: the value of PARTS, 'many', is not a number"}}"#
    );
}

#[test]
fn view_with_defines_opens_the_page_at_an_address_that_carries_them() {
    let file = row_file("defines-address");
    let mut child = ontogeny_command()
        .arg("view")
        .arg(&file)
        .args([
            "--port",
            "0",
            "--define",
            "PARTS=3",
            "--define",
            "LENGTH=0.5",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.as_mut().unwrap())
        .read_line(&mut line)
        .unwrap();
    let _ = child.kill();
    let _ = child.wait();
    let url = line.split_whitespace().last().unwrap();
    assert!(url.starts_with("http://127.0.0.1:"), "{line}");
    assert!(
        url.ends_with("/?define.PARTS=3&define.LENGTH=0.5"),
        "{line}"
    );
}
