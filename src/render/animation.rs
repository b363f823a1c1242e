//! Animations: which moments a GIF shows (developmental frames or recorded samples, evenly in
//! time, under [`MAX_GIF_IMAGES`]), a creature posed as a recorded sample shows it, with the
//! projectile's trail, and GIF encoding of a sequence of pictures (growth, behaviour) or of
//! one still image standing in for an animation.
//!
//! Words: a *frame* is a developmental frame (growth), a *sample* a recorded moment of an
//! evaluation ([`Sample`]), an *image* one picture of a GIF.

use std::sync::Arc;

use nalgebra::{UnitQuaternion, Vector3};

use super::camera::{Framing, View};
use super::palette::gif_image;
use super::text::wrap;
use super::walk::{root_path, thinned, walked, walked_label};
use super::{Overlay, RenderError, checked_with_label, picture};
use crate::creature::{Creature, Part};
use crate::sim::terrain::Terrain;
use crate::task::{Recording, Sample};

/// The largest rate (images per second) an animation takes: GIF delays are whole
/// centiseconds, and browsers slow images shorter than 2 cs down to 10.
pub const MAX_FPS: f64 = 50.0;

/// The most images a GIF holds (behaviour.gif and growth.gif; 10–11 MB at 480 × 300): longer
/// evaluations are drawn at a lower rate, longer growth with frames left out.
pub const MAX_GIF_IMAGES: usize = 600;

/// The most points of a projectile's trail drawn in one image.
const MAX_TRAIL_POINTS: usize = 400;

/// The most characters of a line of a refused recording's picture (its 3D view's width in
/// the 8-pixel font, less a margin).
const STILL_LINE: usize = 40;

/// Which of the moments at `times` (in time order) a GIF of at most `max` images shows: the
/// moment nearest each of `max` times evenly spaced from the first to the last, each one
/// once, the first and last always. All of them when there are no more than `max`.
pub fn evenly_in_time(times: &[f64], max: usize) -> Vec<usize> {
    let n = times.len();
    if n <= max || n == 0 {
        return (0..n).collect();
    }
    if max < 2 {
        return vec![n - 1];
    }
    let (first, last) = (times[0], times[n - 1]);
    let mut chosen: Vec<usize> = Vec::with_capacity(max);
    let mut next = 0;
    for k in 0..max {
        let t = first + (last - first) * k as f64 / (max - 1) as f64;
        while next + 1 < n && (times[next + 1] - t).abs() <= (times[next] - t).abs() {
            next += 1;
        }
        if chosen.last() != Some(&next) {
            chosen.push(next);
        }
    }
    chosen[0] = 0;
    if chosen.last() != Some(&(n - 1)) {
        chosen.push(n - 1);
    }
    chosen.dedup();
    chosen
}

/// How a behaviour animation plays a recording: which samples its images show, how long
/// each image lasts, and at what rate.
#[derive(Clone, Debug, PartialEq)]
pub struct Playback {
    /// The sample each image shows (indices into the recording, in time order).
    pub shown: Vec<usize>,
    /// Each image's GIF delay in centiseconds.
    pub delays_cs: Vec<u16>,
    /// Images per second of simulated time: the rate asked for, or lower when the recording
    /// is too long for [`MAX_GIF_IMAGES`].
    pub fps: f64,
}

/// How an animation at `fps` images per second of simulated time plays `samples`: image k
/// shows the sample nearest time k / fps, and its delay is chosen so that image k starts at
/// round(100 k / fps) cs: played back, the animation keeps the simulation's time, whatever
/// the ratio of `fps` to the recording's rate. The last image shows the last sample (one more
/// image when the rate steps past it). A recording too long for [`MAX_GIF_IMAGES`] is played
/// at a lower rate.
pub fn playback(samples: &[Sample], fps: f64) -> Playback {
    let (Some(first), Some(last)) = (samples.first(), samples.last()) else {
        return Playback {
            shown: Vec::new(),
            delays_cs: Vec::new(),
            fps,
        };
    };
    let span = (last.t - first.t).max(0.0);
    // A long evaluation is shown at a lower rate, so the GIF stays under MAX_GIF_IMAGES.
    let fps = if span * fps + 1.0 > MAX_GIF_IMAGES as f64 {
        (MAX_GIF_IMAGES - 1) as f64 / span
    } else {
        fps
    };
    let count = (span * fps + 1e-9).floor() as usize + 1;
    let mut shown = Vec::with_capacity(count);
    let mut next = 0;
    for k in 0..count {
        let t = first.t + k as f64 / fps;
        // The sample nearest t (samples are in time order).
        while next + 1 < samples.len()
            && (samples[next + 1].t - t).abs() <= (samples[next].t - t).abs()
        {
            next += 1;
        }
        shown.push(next);
    }
    let start = |k: usize| (100.0 * k as f64 / fps).round() as u64;
    let mut delays_cs: Vec<u16> = (0..count)
        .map(|k| (start(k + 1) - start(k)).clamp(2, u16::MAX as u64) as u16)
        .collect();
    // The last image shows the last sample (the end of the evaluation: a walker's D_w), one
    // more image when the rate stepped past it.
    let last = samples.len() - 1;
    if shown.last() != Some(&last) {
        if shown.len() < MAX_GIF_IMAGES {
            shown.push(last);
            delays_cs.push(*delays_cs.last().unwrap_or(&10));
        } else if let Some(end) = shown.last_mut() {
            *end = last;
        }
    }
    Playback {
        shown,
        delays_cs,
        fps,
    }
}

/// `creature` posed as `sample` shows it: every part where it was, the joints moved with
/// their parent part, and the projectile, when there is one, as one more part drawn orange
/// like a growing part.
pub fn posed(creature: &Creature, sample: &Sample) -> Creature {
    let mut c = creature.clone();
    for (part, (position, orientation)) in c.parts.iter_mut().zip(&sample.parts) {
        part.position = *position;
        part.orientation = *orientation;
    }
    if let Some(p) = sample.projectile {
        c.parts.push(Part {
            size: sample.projectile_size.unwrap_or(Vector3::repeat(0.2)),
            position: p,
            orientation: UnitQuaternion::identity(),
            density: 1.0,
            growing: true,
        });
    }
    // Joints move with their parent part.
    for joint in &mut c.joints {
        let (Some(before), Some(after)) =
            (creature.parts.get(joint.parent), c.parts.get(joint.parent))
        else {
            continue;
        };
        let turn = after.orientation * before.orientation.inverse();
        joint.anchor = after.position + turn * (joint.anchor - before.position);
        for axis in &mut joint.axes {
            *axis = turn * *axis;
        }
    }
    c
}

/// The projectile's trail up to sample `until` (included): its positions so far, oldest
/// first, thinned to at most about `MAX_TRAIL_POINTS`, the latest always kept.
pub fn trail(samples: &[Sample], until: usize) -> Vec<Vector3<f64>> {
    let flown: Vec<_> = samples[..=until]
        .iter()
        .filter_map(|s| s.projectile)
        .collect();
    thinned(&flown, MAX_TRAIL_POINTS)
}

/// Writes `behaviour.gif`, the animation of `recording`'s samples as `playback` plays them:
/// each image labelled with its simulated time and the protocol's phase (and, for a walker,
/// the distance walked so far, with the root's path drawn on the ground), the projectile's
/// trail so far drawn, and the aim task's target when there is one; the camera follows the
/// creature. A growing body is drawn as each sample has it: the parts that have appeared, at
/// their sizes then. `progress` is told the fraction of images written.
///
/// A recording without samples (an evaluation refused before simulating) is drawn as one
/// image of the creature as built, checked, saying that nothing was recorded and `why`.
pub fn write_behaviour_gif(
    recording: &Recording,
    playback: &Playback,
    why: &str,
    path: &std::path::Path,
    (width, height): (u32, u32),
    progress: &mut dyn FnMut(f64),
) -> Result<(), RenderError> {
    let creature: &Creature = &recording.creature;
    let samples: &[Sample] = &recording.samples;
    if samples.is_empty() {
        let label: Vec<String> = std::iter::once("no frames recorded (starting pose)".to_string())
            .chain(wrap(why, STILL_LINE))
            .collect();
        return write_still_gif(creature, &label, path, width, height);
    }
    let target = recording.target_point();
    let walks = recording.task == "walker";
    let world = (!recording.world.is_flat()).then(|| Arc::new(Terrain::new(&recording.world)));
    // The body at each image: a growing one has the parts that have appeared, at their sizes.
    let mut bodies = recording.bodies();
    let poses: Vec<Creature> = playback
        .shown
        .iter()
        .map(|&i| posed(bodies.at(i), &samples[i]))
        .collect();
    let overlays: Vec<Overlay> = playback
        .shown
        .iter()
        .map(|&i| {
            let sample = &samples[i];
            let walked = walks.then(|| walked(samples, i)).flatten();
            Overlay {
                // The time, the protocol's phase below it, then the distance walked.
                label: std::iter::once(format!("t = {:.2} s", sample.t))
                    .chain(sample.phase.map(|p| p.label().to_string()))
                    .chain(walked.map(walked_label))
                    .collect(),
                target,
                trail: trail(samples, i),
                path: if walks {
                    root_path(samples, i)
                } else {
                    Vec::new()
                },
                world: world.clone(),
                objects: sample.objects.clone(),
            }
        })
        .collect();
    let framing = Framing::Following {
        parts: bodies.at(samples.len() - 1).parts.len(),
    };
    write_gif(
        poses.iter(),
        &overlays,
        path,
        width,
        height,
        &playback.delays_cs,
        framing,
        progress,
    )
}

/// A looping GIF encoder writing to `out`.
fn gif_encoder<W: std::io::Write>(
    out: W,
    width: u32,
    height: u32,
) -> Result<gif::Encoder<W>, RenderError> {
    let w = u16::try_from(width).map_err(|_| RenderError::Size(width, height))?;
    let h = u16::try_from(height).map_err(|_| RenderError::Size(width, height))?;
    let mut encoder =
        gif::Encoder::new(out, w, h, &[]).map_err(|e| RenderError::Gif(e.to_string()))?;
    encoder
        .set_repeat(gif::Repeat::Infinite)
        .map_err(|e| RenderError::Gif(e.to_string()))?;
    Ok(encoder)
}

/// Writes a GIF of one image: the creature as built, checked as in [`checked_picture`](super::checked_picture)
/// (interpenetrating parts outlined red, its validity and problems written), under the lines
/// of `label`. It stands in for an animation when there is nothing to animate (an
/// evaluation refused before simulating), so that the file opens and says why.
pub fn write_still_gif(
    creature: &Creature,
    label: &[String],
    path: &std::path::Path,
    width: u32,
    height: u32,
) -> Result<(), RenderError> {
    let pixmap = checked_with_label(creature, label.to_vec(), width, height)?;
    crate::output::write_with(path, |out| {
        let mut encoder = gif_encoder(out, width, height)?;
        encoder
            .write_frame(&gif_image(&pixmap))
            .map_err(|e| RenderError::Gif(e.to_string()))?;
        finish_gif(encoder)
    })
}

/// Writes a GIF's trailer and flushes it, reporting a failure (dropping the encoder would
/// hide it).
fn finish_gif<W: std::io::Write>(encoder: gif::Encoder<W>) -> Result<(), RenderError> {
    let mut out = encoder
        .into_inner()
        .map_err(|e| RenderError::Gif(e.to_string()))?;
    Ok(out.flush()?)
}

/// Writes an animated GIF of a sequence of creatures, framed as `framing` says, looping:
/// image i is drawn with `overlays[i]` (none beyond the slice) and lasts `delays_cs[i]`
/// hundredths of a second (the last delay for images beyond the slice, 10 if it is empty).
/// `progress` is told the fraction of images written (0 to 1) after each one, so that the
/// caller can show how far drawing has got.
#[allow(clippy::too_many_arguments)]
pub fn write_gif<'a>(
    creatures: impl IntoIterator<Item = &'a Creature> + Clone,
    overlays: &[Overlay],
    path: &std::path::Path,
    width: u32,
    height: u32,
    delays_cs: &[u16],
    framing: Framing,
    progress: &mut dyn FnMut(f64),
) -> Result<(), RenderError> {
    let views = View::per_image(creatures.clone(), framing);
    let count = views.len().max(1);
    crate::output::write_with(path, |out| {
        let mut encoder = gif_encoder(out, width, height)?;
        let none = Overlay::default();
        for (i, creature) in creatures.into_iter().enumerate() {
            let overlay = overlays.get(i).unwrap_or(&none);
            let pixmap = picture(creature, &views[i], width, height, overlay)?;
            let mut image = gif_image(&pixmap);
            image.delay = delays_cs.get(i).or(delays_cs.last()).copied().unwrap_or(10);
            encoder
                .write_frame(&image)
                .map_err(|e| RenderError::Gif(e.to_string()))?;
            progress((i + 1) as f64 / count as f64);
        }
        finish_gif(encoder)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::develop::BuildOptions;
    use crate::lsystem::LSystem;
    use crate::render::tests::gif_frames;
    use crate::sim::SimOptions;
    use crate::task::{self, CatapultOptions, Evaluation, Recording, WalkerOptions};
    use std::path::Path;

    fn recording(seconds: f64) -> Vec<Sample> {
        (0..=(seconds * 60.0).round() as usize)
            .map(|k| Sample {
                t: k as f64 / 60.0,
                phase: None,
                parts: Vec::new(),
                projectile: None,
                projectile_size: None,
                objects: Vec::new(),
                growth: Vec::new(),
            })
            .collect()
    }

    fn thrower() -> Creature {
        let lsys = LSystem::from_path(Path::new("examples/thrower.lsys")).unwrap();
        let options = crate::lsystem::DeriveOptions::default();
        let frames = crate::develop::grow(&lsys, &options, None, &BuildOptions::default()).unwrap();
        frames.into_iter().last().unwrap().creature
    }

    /// What `eval --record` writes into `dir`: recording.json and behaviour.gif at 10 images
    /// per second.
    fn write_recording_at(dir: &Path, creature: &Creature, evaluation: &Evaluation) {
        std::fs::create_dir_all(dir).unwrap();
        let recording = Recording::of(creature, evaluation);
        let json = serde_json::to_string(&recording).unwrap();
        std::fs::write(dir.join("recording.json"), json).unwrap();
        let why = format!(
            "{}: {}",
            evaluation.status.name(),
            evaluation.message.as_deref().unwrap_or("")
        );
        write_behaviour_gif(
            &recording,
            &playback(&recording.samples, 10.0),
            &why,
            &dir.join("behaviour.gif"),
            (480, 300),
            &mut |_| {},
        )
        .unwrap();
    }

    use crate::render::palette::{PATH, TARGET};

    #[test]
    fn an_aim_recording_shows_its_target_and_a_catapult_one_does_not() {
        let creature = thrower();
        let scratch = tempfile::tempdir().unwrap();
        let dir = scratch.path();
        let sim = SimOptions::default();
        let mut gifs = Vec::new();
        for (name, target) in [("catapult", None), ("aim", Some([5.0, 0.0, 0.0]))] {
            let options = CatapultOptions {
                target: target.map(|[x, y, z]| nalgebra::Vector3::new(x, y, z)),
                ..CatapultOptions::default()
            };
            let evaluation = task::catapult(&creature, &sim, &options, true);
            assert_eq!(
                evaluation.status,
                task::Status::Ok,
                "{:?}",
                evaluation.message
            );
            write_recording_at(&dir.join(name), &creature, &evaluation);
            gifs.push(std::fs::read(dir.join(name).join("behaviour.gif")).unwrap());
        }
        assert_ne!(gifs[0], gifs[1], "an aim GIF differs from a catapult one");
        let has_target = |name: &str| {
            gif_frames(&dir.join(name).join("behaviour.gif"))
                .iter()
                .map(|f| f.chunks_exact(4).filter(|p| p[..3] == TARGET).count())
                .collect::<Vec<_>>()
        };
        assert!(has_target("catapult").iter().all(|&n| n == 0));
        assert!(
            has_target("aim").iter().all(|&n| n > 20),
            "{:?}",
            has_target("aim")
        );
        // The projectile's trail grows: the last image holds more of its colour than the first.
        let trail = |f: &Vec<u8>| f.chunks_exact(4).filter(|p| p[..3] == [190, 90, 0]).count();
        let images = gif_frames(&dir.join("catapult").join("behaviour.gif"));
        assert!(trail(images.last().unwrap()) > trail(&images[0]) + 50);

        // A failed aim evaluation still records its target, and its GIF still shows it.
        let cut = CatapultOptions {
            target: Some(nalgebra::Vector3::new(5.0, 0.0, 0.0)),
            max_seconds: 1.0,
            ..CatapultOptions::default()
        };
        let failed = task::catapult(&creature, &sim, &cut, true);
        assert_eq!(failed.status, task::Status::Unstable);
        let out = dir.join("failed");
        write_recording_at(&out, &creature, &failed);
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("recording.json")).unwrap())
                .unwrap();
        assert!(json["target"].is_array(), "{}", json["target"]);
        assert!(has_target("failed").iter().all(|&n| n > 20));
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn a_walk_shows_its_distance_so_far_and_its_path_on_the_ground() {
        let lsys = LSystem::from_path(Path::new("examples/quadruped.lsys")).unwrap();
        let options = crate::lsystem::DeriveOptions::default();
        let frames = crate::develop::grow(&lsys, &options, None, &BuildOptions::default()).unwrap();
        let creature = frames.into_iter().last().unwrap().creature;
        let walk = WalkerOptions {
            seconds: 2.0,
            ..WalkerOptions::default()
        };
        let evaluation = task::walker(&creature, &SimOptions::default(), &walk, true);
        assert_eq!(
            evaluation.status,
            task::Status::Ok,
            "{:?}",
            evaluation.message
        );
        let samples = &evaluation.recording;
        // The distance the last image shows is the evaluation's D_w (poses are recorded at
        // f32 precision).
        let last = crate::render::walked(samples, samples.len() - 1).unwrap();
        let d_w = evaluation.terms["D_w"];
        assert!(d_w > 0.05, "{d_w}");
        assert!((last - d_w).abs() < 1e-4, "{last} {d_w}");
        // The GIF's last image shows the last sample: it says D_w.
        assert_eq!(
            playback(samples, 10.0).shown.last(),
            Some(&(samples.len() - 1))
        );
        // Nothing is walked before the measured walk starts.
        let start = crate::render::walk_start(samples).unwrap();
        assert!(start > 0);
        assert_eq!(crate::render::walked(samples, start - 1), None);
        assert_eq!(crate::render::walked(samples, start), Some(0.0));
        // The GIF draws the path on the ground once the walk has started, not before.
        let scratch = tempfile::tempdir().unwrap();
        write_recording_at(scratch.path(), &creature, &evaluation);
        let images = gif_frames(&scratch.path().join("behaviour.gif"));
        let path = |f: &Vec<u8>| f.chunks_exact(4).filter(|p| p[..3] == PATH).count();
        assert_eq!(path(&images[0]), 0);
        assert!(
            path(images.last().unwrap()) > 20,
            "{}",
            path(images.last().unwrap())
        );
    }

    #[test]
    fn long_growth_keeps_600_frames_evenly_spaced_in_time() {
        // `grow --dt 0.002` of a 4-unit development: 2001 frames.
        let times: Vec<f64> = (0..=2000).map(|k| k as f64 * 0.002).collect();
        let chosen = evenly_in_time(&times, MAX_GIF_IMAGES);
        assert_eq!(chosen.len(), MAX_GIF_IMAGES);
        assert_eq!(chosen[0], 0);
        assert_eq!(*chosen.last().unwrap(), 2000);
        // Frame k is the one nearest 4 k / 599: within half a frame (0.001) of it.
        for (k, &i) in chosen.iter().enumerate() {
            let ideal = 4.0 * k as f64 / 599.0;
            assert!(
                (times[i] - ideal).abs() <= 0.001 + 1e-12,
                "{k}: {}",
                times[i]
            );
        }
        assert!(chosen.windows(2).all(|w| w[0] < w[1]));
        // Few frames: all of them.
        assert_eq!(evenly_in_time(&[0.0, 1.0, 2.0], 600), [0, 1, 2]);
        assert!(evenly_in_time(&[], 600).is_empty());
    }

    #[test]
    fn uneven_growth_frames_are_each_shown_once() {
        // Nine frames crowded at the start, then one at t = 10: three evenly spaced times
        // (0, 5, 10) pick frame 0, then the one nearest 5 (t = 0.8), then the last.
        let mut times: Vec<f64> = (0..9).map(|k| k as f64 * 0.1).collect();
        times.push(10.0);
        assert_eq!(evenly_in_time(&times, 3), [0, 8, 9]);
        // Four times (0, 3.33, 6.67, 10) would pick frame 8 twice: it is shown once.
        assert_eq!(evenly_in_time(&times, 4), [0, 8, 9]);
    }

    #[test]
    fn a_refused_evaluation_writes_one_picture_saying_why() {
        let creature = crate::develop::creature_from_commands(
            "forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)",
        )
        .unwrap();
        let evaluation = task::walker(
            &creature,
            &SimOptions::default(),
            &WalkerOptions::default(),
            true,
        );
        assert_eq!(evaluation.status, task::Status::SelfIntersecting);
        assert!(evaluation.recording.is_empty());
        let scratch = tempfile::tempdir().unwrap();
        let dir = scratch.path();
        write_recording_at(dir, &creature, &evaluation);
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("recording.json")).unwrap())
                .unwrap();
        assert_eq!(json["status"], "self-intersecting");
        assert_eq!(json["message"], "parts 0 and 3 interpenetrate");
        let images = gif_frames(&dir.join("behaviour.gif"));
        assert_eq!(images.len(), 1, "one picture, not an empty GIF");
        // The picture is checked: the interpenetrating parts are outlined and the text is
        // written in the marking red (render's `MARK`), thousands of pixels of it with the
        // frame round an invalid creature.
        let red = images[0]
            .chunks_exact(4)
            .filter(|p| p[..3] == [255, 0, 0])
            .count();
        assert!(red > 2000, "{red}");
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn a_short_recording_is_drawn_at_the_asked_rate() {
        let drawn = playback(&recording(2.0), 10.0);
        assert_eq!(drawn.fps, 10.0);
        assert_eq!(drawn.shown.len(), 21);
        // Image k shows the recording at k / 10 s: sample 6k at 60 samples/s.
        assert!(drawn.shown.iter().enumerate().all(|(k, &i)| i == 6 * k));
        assert!(drawn.delays_cs.iter().all(|&d| d == 10));
    }

    #[test]
    fn a_long_recording_stays_under_the_image_cap() {
        // An hour at 10 images/s would be 36,001 images.
        let drawn = playback(&recording(3600.0), 10.0);
        assert_eq!(drawn.shown.len(), MAX_GIF_IMAGES);
        assert!((drawn.fps - 599.0 / 3600.0).abs() < 1e-12);
        // It still plays back in real time: the delays add up to the hour (in cs).
        let delays = &drawn.delays_cs;
        let total: u64 = delays[..delays.len() - 1].iter().map(|&d| d as u64).sum();
        assert!((total as f64 - 360_000.0).abs() <= 1.0, "{total}");
    }
}
