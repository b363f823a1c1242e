//! Pictures of creatures, headless and in pure Rust: a shaded 3/4 view of the body on a
//! ground grid with joints and growing parts marked, a drawing of the neural network beside
//! it, and animations of growth and behaviour. Drawing is done with tiny-skia, text with the
//! public-domain 8×8 bitmap font of `font8x8`; GIFs are encoded with `gif`, on a palette that
//! keeps the colours that carry meaning exact.

mod animation;
mod body;
mod brain;
mod camera;
pub mod growth;
mod palette;
mod pen;
mod text;
mod top_view;
mod walk;
mod world;

use std::sync::Arc;

use nalgebra::{UnitQuaternion, Vector3};
use tiny_skia::{Color, Pixmap};

use crate::creature::Creature;
use crate::sim::terrain::Terrain;
pub use animation::{
    MAX_FPS, MAX_GIF_IMAGES, Playback, evenly_in_time, playback, posed, trail, write_behaviour_gif,
    write_gif, write_still_gif,
};
use body::{Checks, draw_body};
use brain::draw_brain;
pub use camera::{Framing, View};
pub use text::wrap;
pub use walk::{root_path, walk_start, walked, walked_label};

/// Why a picture could not be made or written.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The requested picture size is zero or too large.
    #[error("cannot make a {0}x{1} picture")]
    Size(u32, u32),
    /// PNG encoding or writing failed.
    #[error("cannot write the PNG: {0}")]
    Png(String),
    /// GIF encoding or writing failed.
    #[error("cannot write the GIF: {0}")]
    Gif(String),
    /// A file could not be written.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// The output file was refused or could not be written (see [`crate::output`]).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
}

/// What is drawn over a picture besides the creature.
#[derive(Clone, Debug, Default)]
pub struct Overlay {
    /// Lines of text at the top left (a behaviour image's time and phase, say).
    pub label: Vec<String>,
    /// A target, in world coordinates (the aim task's): a bullseye with a line down to the
    /// ground.
    pub target: Option<Vector3<f64>>,
    /// A projectile's past positions, oldest first, drawn as its trail. With a target or a
    /// trail, a top view in the corner shows them even when they are out of the camera's
    /// view.
    pub trail: Vec<Vector3<f64>>,
    /// A walker's path on the ground so far (its root part's centre at y = 0), oldest first,
    /// drawn as a line on the ground.
    pub path: Vec<Vector3<f64>>,
    /// The world the creature is in (none: level ground in air, as for a flat world): its
    /// shaped ground, obstacles and objects are drawn, and water tints the scene.
    pub world: Option<Arc<Terrain>>,
    /// The world's free objects' centres and orientations now, in the order of its objects
    /// (none: where they start).
    pub objects: Vec<(Vector3<f64>, UnitQuaternion<f64>)>,
}

/// A picture of the creature: the body in a 3/4 view on the left, its brain on the right
/// (none for a creature with no joint that moves, such as a plant), with
/// `overlay` drawn over the body.
pub fn picture(
    creature: &Creature,
    view: &View,
    width: u32,
    height: u32,
    overlay: &Overlay,
) -> Result<Pixmap, RenderError> {
    compose(creature, view, width, height, overlay, Checks::Off)
}

fn compose(
    creature: &Creature,
    view: &View,
    width: u32,
    height: u32,
    overlay: &Overlay,
    checks: Checks,
) -> Result<Pixmap, RenderError> {
    if width < 64 || height < 64 || width > 8192 || height > 8192 {
        return Err(RenderError::Size(width, height));
    }
    let mut pixmap = Pixmap::new(width, height).ok_or(RenderError::Size(width, height))?;
    pixmap.fill(Color::from_rgba8(255, 255, 255, 255));
    let (w, h) = (width as f32, height as f32);
    // A brain with no joint to drive (a plant's) gets no panel.
    let moves = creature.joints.iter().any(|j| j.kind.dof() > 0);
    let brain_w = if moves { (w * 0.3).round() } else { 0.0 };
    draw_body(
        &mut pixmap,
        creature,
        view,
        (0.0, 0.0, w - brain_w, h),
        overlay,
        checks,
    );
    if brain_w > 0.0 {
        draw_brain(&mut pixmap, creature, (w - brain_w, 0.0, brain_w, h));
    }
    Ok(pixmap)
}

/// The `creature.png` picture: the body and brain with the creature checked — parts that
/// interpenetrate outlined red, every part numbered, `title`, the counts and validity and
/// the problems written at the top left (wrapped; repeated ones once; the first few, then how
/// many more; a red frame round an invalid creature) — and a scale bar.
pub fn checked_picture(
    creature: &Creature,
    title: &str,
    width: u32,
    height: u32,
) -> Result<Pixmap, RenderError> {
    let label = if title.is_empty() {
        Vec::new()
    } else {
        vec![title.to_string()]
    };
    checked_with_label(creature, label, width, height)
}

/// The creature framed whole and checked (see [`checked_picture`]), under the lines of
/// `label`.
fn checked_with_label(
    creature: &Creature,
    label: Vec<String>,
    width: u32,
    height: u32,
) -> Result<Pixmap, RenderError> {
    let overlay = Overlay {
        label,
        ..Overlay::default()
    };
    compose(
        creature,
        &View::framing(creature),
        width,
        height,
        &overlay,
        Checks::On,
    )
}

/// Writes the `creature.png` picture of one creature (see [`checked_picture`]).
pub fn write_png(
    creature: &Creature,
    title: &str,
    path: &std::path::Path,
    width: u32,
    height: u32,
) -> Result<(), RenderError> {
    let pixmap = checked_picture(creature, title, width, height)?;
    let png = pixmap
        .encode_png()
        .map_err(|e| RenderError::Png(e.to_string()))?;
    Ok(crate::output::write(path, png)?)
}

#[cfg(test)]
mod tests {
    use super::body::joint_radius;
    use super::palette::{ACTUATOR, AXIS, INK, JOINT, MARK, OSCILLATOR, PANEL, TARGET, TRAIL};
    use super::*;
    use crate::creature::{Role, Severity};
    use crate::develop::creature_from_commands;

    fn creature(commands: &str) -> Creature {
        creature_from_commands(commands).unwrap()
    }

    /// How many pixels of straight RGBA `data` are exactly `colour`.
    fn count(data: &[u8], colour: [u8; 3]) -> usize {
        data.chunks_exact(4)
            .filter(|p| p[..3] == colour[..])
            .count()
    }

    /// Every frame of the GIF at `path`, as straight RGBA.
    pub(super) fn gif_frames(path: &std::path::Path) -> Vec<Vec<u8>> {
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options
            .read_info(std::fs::File::open(path).unwrap())
            .unwrap();
        let mut frames = Vec::new();
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            frames.push(frame.buffer.to_vec());
        }
        frames
    }

    /// A private scratch directory, removed when dropped.
    fn scratch() -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix("ontogeny-render-unit-")
            .tempdir()
            .unwrap()
    }

    /// A thrower-like creature with an actuator, posed with a projectile-like growing part.
    fn arm() -> Creature {
        let c = creature("forward(1) revolute2 forward(1) output(1)");
        assert!(
            c.brain
                .neurons
                .iter()
                .any(|n| matches!(n.role, Role::Actuator { .. }))
        );
        c
    }

    /// Writes a one-image GIF of `c` drawn with `overlay`.
    fn still_gif(c: &Creature, overlay: Overlay, path: &std::path::Path) {
        write_gif(
            [c],
            &[overlay],
            path,
            480,
            300,
            &[10],
            Framing::Still,
            &mut |_| {},
        )
        .unwrap();
    }

    #[test]
    fn a_creature_with_no_joint_that_moves_gets_no_brain_panel() {
        let panel = |c: &Creature| {
            let pixmap = picture(c, &View::framing(c), 480, 300, &Overlay::default()).unwrap();
            count(pixmap.data(), PANEL)
        };
        // Rigidly joined parts, as a plant's: the body has the whole picture.
        assert_eq!(panel(&creature("forward forward forward")), 0);
        // A hinge to drive: the brain panel, a third of the picture, is there.
        assert!(panel(&arm()) > 480 * 300 / 5);
    }

    #[test]
    fn legend_colours_survive_the_gif_palette() {
        let c = arm();
        let view = View::framing(&c);
        let pixmap = picture(&c, &view, 480, 300, &Overlay::default()).unwrap();
        let dir = scratch();
        let path = dir.path().join("legend.gif");
        still_gif(&c, Overlay::default(), &path);
        let frames = gif_frames(&path);
        assert_eq!(frames.len(), 1);
        // Every pixel that is exactly a legend colour in the picture is that colour in the
        // GIF: the actuator's red, the joint's red, the panel.
        for colour in [ACTUATOR, JOINT, PANEL, OSCILLATOR] {
            let drawn: Vec<usize> = pixmap
                .data()
                .chunks_exact(4)
                .enumerate()
                .filter(|(_, p)| p[..3] == colour[..])
                .map(|(i, _)| i)
                .collect();
            if colour != OSCILLATOR {
                assert!(drawn.len() > 20, "{colour:?} drawn: {}", drawn.len());
            }
            for i in drawn {
                assert_eq!(&frames[0][4 * i..4 * i + 3], &colour[..], "pixel {i}");
            }
        }
        // The actuator disc is solid red in the GIF (dot radius >= 3 px: at least 9 pixels).
        assert!(count(&frames[0], ACTUATOR) >= 9);
    }

    #[test]
    fn a_target_and_a_trail_are_drawn_and_shown_in_the_top_view() {
        let c = arm();
        let view = View::framing(&c);
        let trail: Vec<Vector3<f64>> = (0..20)
            .map(|k| Vector3::new(2.0 + 0.2 * k as f64, 1.0 - 0.002 * (k * k) as f64, 0.0))
            .collect();
        let plain = picture(&c, &view, 480, 300, &Overlay::default()).unwrap();
        let thrown = Overlay {
            trail: trail.clone(),
            ..Overlay::default()
        };
        let aimed = Overlay {
            trail,
            target: Some(Vector3::new(12.0, 0.0, 3.0)),
            ..Overlay::default()
        };
        let thrown_pic = picture(&c, &view, 480, 300, &thrown).unwrap();
        let aimed_pic = picture(&c, &view, 480, 300, &aimed).unwrap();
        assert_eq!(count(plain.data(), TARGET), 0);
        assert_eq!(count(plain.data(), TRAIL), 0);
        assert!(count(thrown_pic.data(), TRAIL) > 30);
        assert_eq!(count(thrown_pic.data(), TARGET), 0);
        // The target, 12 m off, is outside the camera's view but in the top view.
        assert!(count(aimed_pic.data(), TARGET) > 20);
        // Through a GIF: the target's colour in the aim animation only.
        let dir = scratch();
        let (a, b) = (dir.path().join("aim.gif"), dir.path().join("catapult.gif"));
        still_gif(&c, aimed, &a);
        still_gif(&c, thrown, &b);
        assert!(count(&gif_frames(&a)[0], TARGET) > 20);
        assert_eq!(count(&gif_frames(&b)[0], TARGET), 0);
    }

    #[test]
    fn a_label_is_written_in_the_top_left_corner() {
        let c = arm();
        let view = View::framing(&c);
        let plain = picture(&c, &view, 480, 300, &Overlay::default()).unwrap();
        let label = Overlay {
            label: vec!["t = 1.50 s  measuring".to_string()],
            ..Overlay::default()
        };
        let labelled = picture(&c, &view, 480, 300, &label).unwrap();
        // The label's box: 21 characters of 8 px from x = 8, y = 6.
        let ink = |p: &Pixmap| {
            (6..14)
                .flat_map(|y| (8..8 + 21 * 8).map(move |x| (x, y)))
                .filter(|&(x, y)| {
                    let i = 4 * (y * 480 + x) as usize;
                    p.data()[i..i + 3] == INK[..]
                })
                .count()
        };
        assert_eq!(ink(&plain), 0);
        assert!(ink(&labelled) > 150, "{}", ink(&labelled));
    }

    #[test]
    fn a_creature_with_its_own_projectile_is_captioned_with_its_size() {
        let plain = arm();
        let mut thrower = plain.clone();
        thrower.projectile = Some([0.162, 0.243, 0.218]);
        assert_eq!(body::projectile_line(&plain), None);
        assert_eq!(
            body::projectile_line(&thrower).as_deref(),
            Some("projectile 16.2 x 24.3 x 21.8 cm")
        );
        // The caption is one more line of ink under the counts, top left.
        let ink = |c: &Creature| {
            let pic = checked_picture(c, "arm", 960, 600).unwrap();
            (0..120)
                .flat_map(|y| (0..600).map(move |x| (x, y)))
                .filter(|&(x, y)| {
                    let i = 4 * (y * 960 + x) as usize;
                    pic.data()[i..i + 3] == INK[..]
                })
                .count()
        };
        let (without, with) = (ink(&plain), ink(&thrower));
        assert!(with > without + 200, "{without} then {with}");
    }

    #[test]
    fn an_invalid_creature_is_marked_and_a_valid_one_is_not() {
        let valid = arm();
        let pic = checked_picture(&valid, "arm", 960, 600).unwrap();
        assert_eq!(count(pic.data(), MARK), 0);
        // Two parts laid one inside the other (a creature.json may hold anything).
        let mut overlapping = valid.clone();
        overlapping.parts[1].position = overlapping.parts[0].position;
        assert!(!overlapping.interpenetrating_pairs().is_empty());
        let pic = checked_picture(&overlapping, "arm", 960, 600).unwrap();
        // The red frame alone is 2 × (960 × 0.7 + 600) × 3 px; the outlines and the text add.
        assert!(
            count(pic.data(), MARK) > 6000,
            "{}",
            count(pic.data(), MARK)
        );
        // A problem listed by development marks it too, with no geometry to outline.
        let mut listed = valid.clone();
        listed.problems.push(crate::creature::Problem {
            severity: Severity::Error,
            message: "too many parts".to_string(),
            module: None,
            t: None,
        });
        let pic = checked_picture(&listed, "", 960, 600).unwrap();
        assert!(count(pic.data(), MARK) > 6000);
    }

    #[test]
    fn joint_discs_follow_the_parts_and_show_the_axis() {
        // Parts 0.1 m wide and thick and 1 m long: discs 0.05 m in radius.
        let thin = creature("width(0.1) thickness(0.1) forward(1) revolute2 forward(1)");
        assert!((joint_radius(&thin, 0, 1) - 0.05).abs() < 1e-12);
        // Twice as wide: twice the radius, about four times the red pixels (less the
        // anti-aliased rim, where the colour is not exact).
        let wide = creature("width(0.2) thickness(0.2) forward(1) revolute2 forward(1)");
        assert!((joint_radius(&wide, 0, 1) - 0.1).abs() < 1e-12);
        let view = View::framing(&wide);
        let red = |c: &Creature| {
            let pic = picture(c, &view, 960, 600, &Overlay::default()).unwrap();
            count(pic.data(), JOINT)
        };
        let (a, b) = (red(&thin), red(&wide));
        assert!(
            a > 10 && (2.5..6.0).contains(&(b as f64 / a as f64)),
            "{a} {b}"
        );
        // The axis is drawn: some pixels of the axis colour near the anchor.
        let pic = picture(&thin, &view, 960, 600, &Overlay::default()).unwrap();
        assert!(count(pic.data(), AXIS) > 5);
    }
}
