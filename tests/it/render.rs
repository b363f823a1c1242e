//! Pictures: the PNG shows the body where the camera says it is, and the GIF has a frame per
//! growth frame.

use ontogeny::creature::Creature;
use ontogeny::develop::{BuildOptions, grow};
use ontogeny::lsystem::{DeriveOptions, LSystem};
use ontogeny::render::{Overlay, View, picture, write_gif};

fn none() -> Overlay {
    Overlay::default()
}

fn creature(axiom: &str) -> Creature {
    ontogeny::develop::creature_from_commands(axiom).unwrap()
}

/// Pixels of the body panel (the left 70% of a `width`-wide picture) whose colour is the
/// parts' blue (bluer than red and green by a margin).
fn blue_pixels(data: &[u8], width: usize) -> usize {
    data.chunks(4)
        .enumerate()
        .filter(|(i, p)| {
            i % width < width * 7 / 10
                && p[2] as i32 > p[0] as i32 + 40
                && p[2] as i32 > p[1] as i32 + 20
        })
        .count()
}

#[test]
fn a_picture_shows_the_body_and_grows_with_it() {
    let one = creature("forward(1)");
    let four = creature("forward(1) forward(1) left(1) forward(1) forward(1)");
    let view = View::framing(&four);
    let small = picture(&one, &view, 400, 300, &none()).unwrap();
    let large = picture(&four, &view, 400, 300, &none()).unwrap();
    assert_eq!((small.width(), small.height()), (400, 300));
    let (a, b) = (
        blue_pixels(small.data(), 400),
        blue_pixels(large.data(), 400),
    );
    assert!(a > 200, "one part is visible: {a} blue pixels");
    assert!(
        b > 2 * a,
        "four parts cover more of the same view: {b} vs {a}"
    );
    // Same creature, same picture.
    assert_eq!(
        picture(&four, &view, 400, 300, &none()).unwrap().data(),
        large.data()
    );
}

#[test]
fn an_empty_creature_still_draws_and_bad_sizes_are_errors() {
    let empty = creature("A");
    let pic = picture(&empty, &View::framing(&empty), 200, 100, &none()).unwrap();
    assert_eq!(blue_pixels(pic.data(), 200), 0);
    assert!(picture(&empty, &View::framing(&empty), 0, 100, &none()).is_err());
}

#[test]
fn the_growth_gif_has_a_frame_per_growth_frame() {
    let lsys = LSystem::from_path(std::path::Path::new("examples/snake.lsys")).unwrap();
    let options = DeriveOptions {
        time: Some(2.0),
        dt: Some(0.5),
        ..DeriveOptions::default()
    };
    let frames = grow(&lsys, &options, None, &BuildOptions::default()).unwrap();
    assert_eq!(frames.len(), 5);
    let dir = crate::util::scratch_dir("render-growth");
    let path = dir.join("growth.gif");
    write_gif(
        frames.iter().map(|f| &f.creature),
        &[],
        &path,
        160,
        100,
        &[20],
        ontogeny::render::Framing::Still,
        &mut |_| {},
    )
    .unwrap();
    let mut decoder = gif::DecodeOptions::new()
        .read_info(std::fs::File::open(&path).unwrap())
        .unwrap();
    let mut count = 0;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!((frame.width, frame.height, frame.delay), (160, 100, 20));
        count += 1;
    }
    assert_eq!(count, 5);
}

#[test]
fn growth_builds_a_creature_per_frame_with_parts_appearing() {
    let lsys = LSystem::from_path(std::path::Path::new("examples/snake.lsys")).unwrap();
    let frames = grow(
        &lsys,
        &DeriveOptions::default(),
        None,
        &BuildOptions::default(),
    )
    .unwrap();
    assert_eq!(frames.len(), 21, "t = 0, 0.25, ..., 5");
    let parts: Vec<usize> = frames.iter().map(|f| f.creature.parts.len()).collect();
    assert!(parts.windows(2).all(|w| w[0] <= w[1]), "{parts:?}");
    assert_eq!(parts[0], 1, "the buds have no length yet");
    assert_eq!(*parts.last().unwrap(), 9);
    // A growing limb is marked as such and lengthens.
    let growing: Vec<f64> = frames[1..4]
        .iter()
        .map(|f| f.creature.parts.iter().find(|p| p.growing).unwrap().size.x)
        .collect();
    assert!(
        (growing[0] - 0.125).abs() < 1e-9 && (growing[2] - 0.375).abs() < 1e-9,
        "{growing:?}"
    );
}

/// The blue pixels of each frame of a GIF.
fn blue_pixels_per_frame(path: &std::path::Path, width: usize) -> Vec<usize> {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(path).unwrap())
        .unwrap();
    let mut counts = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        counts.push(blue_pixels(&frame.buffer, width));
    }
    counts
}

#[test]
fn a_following_camera_keeps_a_travelling_creature_large() {
    // The same creature at rest and 40 m further on.
    let start = creature("width(0.3) forward(1) revolute2 forward(1)");
    let mut far = start.clone();
    for part in &mut far.parts {
        part.position.x += 40.0;
    }
    let dir = crate::util::scratch_dir("render-follow");
    let mut counts = Vec::new();
    for framing in [
        ontogeny::render::Framing::Still,
        ontogeny::render::Framing::Following {
            parts: start.parts.len(),
        },
    ] {
        let path = dir.join("travel.gif");
        write_gif(
            [&start, &far],
            &[],
            &path,
            240,
            150,
            &[10],
            framing,
            &mut |_| {},
        )
        .unwrap();
        counts.push(blue_pixels_per_frame(&path, 240));
    }
    let (still, following) = (&counts[0], &counts[1]);
    // Following: the creature is as large in the last frame as in the first.
    assert!(following[0] > 500, "{following:?}");
    assert!(
        following[1] as f64 > 0.8 * following[0] as f64,
        "{following:?}"
    );
    // A still camera framing the whole trip shows it far smaller.
    assert!(
        (still[1] as f64) < 0.2 * following[1] as f64,
        "{still:?} {following:?}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn drawing_a_gif_reports_its_progress_frame_by_frame() {
    let c = creature("forward(1) forward(1)");
    let path = crate::util::scratch_dir("render-progress").join("progress.gif");
    let mut seen = Vec::new();
    ontogeny::render::write_gif(
        [&c, &c, &c, &c],
        &[],
        &path,
        120,
        80,
        &[10],
        ontogeny::render::Framing::Still,
        &mut |f| seen.push(f),
    )
    .unwrap();
    // A quarter more after each of the four frames.
    assert_eq!(seen, [0.25, 0.5, 0.75, 1.0]);
    let _ = std::fs::remove_file(path);
}

#[test]
fn a_still_gif_is_one_checked_picture() {
    // Parts 0 and 3 cross: outlined red, the text red, a red frame round the picture.
    let crossing = creature("forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)");
    let fine = creature("forward(1) forward(1)");
    let dir = crate::util::scratch_dir("render-still");
    let mut red = Vec::new();
    for (name, c) in [("crossing", &crossing), ("fine", &fine)] {
        let path = dir.join(format!("{name}.gif"));
        let label = vec!["no frames recorded".to_string()];
        ontogeny::render::write_still_gif(c, &label, &path, 480, 300).unwrap();
        let frames = blue_pixels_per_frame(&path, 480);
        assert_eq!(frames.len(), 1, "{name}");
        assert!(frames[0] > 1000, "{name}: the body is drawn: {frames:?}");
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options
            .read_info(std::fs::File::open(&path).unwrap())
            .unwrap();
        let frame = decoder.read_next_frame().unwrap().unwrap();
        red.push(
            frame
                .buffer
                .chunks_exact(4)
                .filter(|p| p[..3] == [255, 0, 0])
                .count(),
        );
    }
    assert!(red[0] > 2000, "{red:?}");
    assert_eq!(red[1], 0, "{red:?}");
    let _ = std::fs::remove_dir_all(dir);
}

/// The worlds the guide shows, by name, as `[task.world]` tables, placed round a creature
/// whose bounding box is `lo` to `hi`.
fn worlds(lo: [f64; 3], hi: [f64; 3]) -> Vec<(&'static str, String)> {
    let (cx, cz) = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[2] + hi[2]));
    vec![
        (
            "slope",
            "slope = { degrees = 12, direction = 0 }".to_string(),
        ),
        (
            "steps",
            format!(
                "steps = {{ height = 0.08, depth = 0.3, count = 5, start = {}, direction = 0 }}",
                hi[0] + 0.1
            ),
        ),
        (
            "rough",
            "rough = { amplitude = 0.05, wavelength = 0.6, seed = 3, size = 8 }".to_string(),
        ),
        (
            "obstacles",
            format!(
                "obstacles = {{ size = [0.3, 0.25, 0.3], at = [[{cx}, {}], [{}, {cz}], [{}, {}]] }}",
                hi[2] + 0.4,
                hi[0] + 0.35,
                lo[0] - 0.3,
                lo[2] - 0.3
            ),
        ),
        (
            "objects",
            format!(
                "objects = [{{ shape = \"ball\", size = 0.15, mass = 2, position = [{}, 0.15, {}] }},\n\
                 {{ shape = \"box\", size = 0.25, mass = 2, position = [{}, 0.125, {}] }}]",
                hi[0] + 0.3,
                hi[2] + 0.3,
                lo[0] - 0.3,
                hi[2] + 0.2
            ),
        ),
        (
            "water",
            "medium = { kind = \"water\", viscosity = 5 }".to_string(),
        ),
    ]
}

#[test]
fn every_world_is_drawn_round_the_creature_and_a_flat_one_changes_no_pixel() {
    use ontogeny::sim::WorldSpec;
    use ontogeny::sim::terrain::Terrain;
    use std::sync::Arc;
    let quadruped = crate::util::grown("examples/quadruped.lsys");
    let view = View::framing(&quadruped);
    let draw = |world: Option<WorldSpec>| {
        let overlay = Overlay {
            world: world.map(|w| Arc::new(Terrain::new(&w))),
            ..none()
        };
        picture(&quadruped, &view, 960, 600, &overlay).unwrap()
    };
    let flat = draw(None);
    assert!(flat.data() == draw(Some(WorldSpec::default())).data());
    let dir = crate::util::scratch_dir("world-pictures");
    let (lo, hi) = quadruped.bounding_box();
    for (name, table) in worlds([lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z]) {
        let world: WorldSpec = toml::from_str(&table).unwrap();
        world.check().unwrap();
        let pixmap = draw(Some(world));
        let changed = flat
            .data()
            .chunks_exact(4)
            .zip(pixmap.data().chunks_exact(4))
            .filter(|(a, b)| a != b)
            .count();
        assert!(changed > 5000, "{name}: {changed} pixels changed");
        pixmap
            .save_png(dir.join(format!("world-{name}.png")))
            .unwrap();
    }
}
