//! A recording of a body that grows during the walk, served to the page: the frames with
//! their growth, and the body with every part that appears, for which the page makes meshes.

use super::Viewer;
use super::server::get_json;
use crate::growing_shown::{growing_recording, old_recording};

#[test]
fn the_served_recording_of_a_growing_walk_carries_the_parts_that_appear() {
    let rec = growing_recording("view");
    let viewer = Viewer::start(&rec);
    let data = get_json(&viewer, "/data.json");
    assert_eq!(data["kind"], "recording");
    // Dropped as three parts; the body has the fifteen there are at the end, each jointed.
    assert_eq!(data["creature"]["parts"].as_array().unwrap().len(), 3);
    assert_eq!(data["body"]["parts"].as_array().unwrap().len(), 15);
    assert_eq!(data["body"]["joints"].as_array().unwrap().len(), 14);
    let frames = data["frames"].as_array().unwrap();
    let appears: Vec<(usize, u64)> = frames
        .iter()
        .enumerate()
        .flat_map(|(i, f)| {
            f["growth"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(move |c| Some((i, c["appears"]["part"].as_u64()?)))
        })
        .collect();
    assert_eq!(
        appears.iter().map(|&(_, p)| p).collect::<Vec<_>>(),
        (3..15).collect::<Vec<u64>>()
    );
    for (i, part) in appears {
        // The frame a part appears in is the first to pose it.
        let posed = |i: usize| frames[i]["parts"].as_array().unwrap().len() as u64;
        assert!(
            posed(i) > part && posed(i - 1) <= part,
            "part {part}, frame {i}"
        );
    }
    // A recording of a body that does not grow is served as before: no body.
    let old = Viewer::start(&old_recording("view"));
    let data = get_json(&old, "/data.json");
    assert!(data.get("body").is_none());
    assert_eq!(data["frames"].as_array().unwrap().len(), 72);
}
