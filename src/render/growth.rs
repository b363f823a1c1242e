//! A growth animation (`grow --out`'s `growth.gif`): which frames it shows, how long each
//! shows, and their labels; drawn by [`write_growth_gif`].

use std::path::Path;

use super::{Framing, MAX_GIF_IMAGES, Overlay, RenderError, evenly_in_time};
use crate::develop::GrowthFrame;
use crate::lsystem::FramePlan;

/// How long (centiseconds) each image of a growth animation of `images` images shows: a
/// quarter of a second, shorter for long animations so that the whole plays in at most
/// 30 s, and never under 4 cs (browsers slow shorter images down).
pub fn growth_image_delay(images: usize) -> u16 {
    (3000 / images.max(1)).clamp(4, 25) as u16
}

/// Which frames (by step) a growth animation shows: at most [`MAX_GIF_IMAGES`], evenly spaced
/// in developmental time, the first and last kept; `wanted[step]` says whether frame `step` is
/// one.
pub fn growth_gif_steps(plan: &FramePlan) -> Vec<bool> {
    let times: Vec<f64> = (0..=plan.last_step()).map(|k| plan.time(k)).collect();
    let mut wanted = vec![false; times.len()];
    for i in evenly_in_time(&times, MAX_GIF_IMAGES) {
        wanted[i] = true;
    }
    wanted
}

/// The note for a growth animation at `path` that shows `shown` of `total` frames, if it
/// leaves some out.
pub fn growth_gif_note(shown: usize, total: u64, path: &Path) -> Option<String> {
    ((shown as u64) < total).then(|| {
        format!(
            "note: {total} frames of growth: {} shows {shown} of them, evenly spaced in \
             developmental time, to keep to {MAX_GIF_IMAGES} frames",
            path.display()
        )
    })
}

/// The frames a growth animation shows of `frames`: from the first that has a part (the
/// frames before it, an axiom that builds nothing yet, would show empty ground), or all of
/// them when none has.
pub fn growth_gif_frames(frames: &[GrowthFrame]) -> &[GrowthFrame] {
    let first = frames
        .iter()
        .position(|f| !f.creature.parts.is_empty())
        .unwrap_or(0);
    &frames[first..]
}

/// Draws a growth animation of `frames` (480 × 300) from the first frame with a part
/// ([`growth_gif_frames`]), each labelled with its developmental time, telling `progress` how
/// far it is (0 to 1).
pub fn write_growth_gif(
    frames: &[GrowthFrame],
    path: &Path,
    progress: &mut dyn FnMut(f64),
) -> Result<(), RenderError> {
    let frames = growth_gif_frames(frames);
    let labels: Vec<Overlay> = frames
        .iter()
        .map(|frame| Overlay {
            label: vec![format!("t = {}", crate::number::format_number(frame.t))],
            ..Default::default()
        })
        .collect();
    super::write_gif(
        frames.iter().map(|frame| &frame.creature),
        &labels,
        path,
        480,
        300,
        &[growth_image_delay(frames.len())],
        Framing::Still,
        progress,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::creature::Creature;
    use crate::develop::creature_from_commands;

    #[test]
    fn a_growth_animation_starts_at_the_first_part() {
        let frame = |step: u64, creature: Creature| GrowthFrame {
            step,
            t: step as f64,
            creature,
        };
        let empty = || creature_from_commands("split").unwrap();
        let one = creature_from_commands("forward(1)").unwrap();
        assert!(empty().parts.is_empty());
        let frames = vec![
            frame(0, empty()),
            frame(1, empty()),
            frame(2, one.clone()),
            frame(3, empty()),
        ];
        let shown = growth_gif_frames(&frames);
        assert_eq!(shown.iter().map(|f| f.step).collect::<Vec<_>>(), [2, 3]);
        // Nothing ever built: every frame is shown.
        let nothing = vec![frame(0, empty()), frame(1, empty())];
        assert_eq!(growth_gif_frames(&nothing).len(), 2);
        // The GIF holds the shown frames only.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("growth.gif");
        write_growth_gif(&frames, &path, &mut |_| {}).unwrap();
        assert_eq!(crate::render::tests::gif_frames(&path).len(), 2);
    }

    #[test]
    fn a_growth_animation_plays_in_at_most_half_a_minute() {
        // Up to 120 images: a quarter of a second each.
        assert_eq!(growth_image_delay(1), 25);
        assert_eq!(growth_image_delay(120), 25);
        // 600 images (the most a GIF holds): 5 cs each, 30 s in all.
        assert_eq!(growth_image_delay(600), 5);
        assert!(growth_image_delay(300) as usize * 300 <= 3000);
        // Never under 4 cs.
        assert_eq!(growth_image_delay(10_000), 4);
        assert_eq!(growth_image_delay(0), 25);
    }
}
