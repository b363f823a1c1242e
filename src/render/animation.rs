//! Animations: GIF encoding of a sequence of pictures (growth, behaviour) and of one still
//! image standing in for an animation.

use super::camera::{Framing, View};
use super::palette::gif_image;
use super::{Checks, Overlay, RenderError, compose, picture};
use crate::creature::Creature;

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

/// Writes a GIF of one frame: the creature as built, checked as in [`checked_picture`]
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
    let overlay = Overlay {
        label: label.to_vec(),
        ..Overlay::default()
    };
    let pixmap = compose(
        creature,
        &View::framing(creature),
        width,
        height,
        &overlay,
        Checks::On,
    )?;
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
/// frame i is drawn with `overlays[i]` (none beyond the slice) and lasts `delays_cs[i]`
/// hundredths of a second (the last delay for frames beyond the slice, 10 if it is empty).
pub fn write_gif<'a>(
    creatures: impl IntoIterator<Item = &'a Creature> + Clone,
    overlays: &[Overlay],
    path: &std::path::Path,
    width: u32,
    height: u32,
    delays_cs: &[u16],
    framing: Framing,
) -> Result<(), RenderError> {
    write_gif_with_progress(
        creatures,
        overlays,
        path,
        width,
        height,
        delays_cs,
        framing,
        &mut |_| {},
    )
}

/// [`write_gif`], calling `progress` with the fraction of frames written (0 to 1) after
/// each one, so that the caller can show how far drawing has got.
#[allow(clippy::too_many_arguments)]
pub fn write_gif_with_progress<'a>(
    creatures: impl IntoIterator<Item = &'a Creature> + Clone,
    overlays: &[Overlay],
    path: &std::path::Path,
    width: u32,
    height: u32,
    delays_cs: &[u16],
    framing: Framing,
    progress: &mut dyn FnMut(f64),
) -> Result<(), RenderError> {
    let views = View::per_frame(creatures.clone(), framing);
    let count = views.len().max(1);
    crate::output::write_with(path, |out| {
        let mut encoder = gif_encoder(out, width, height)?;
        let none = Overlay::default();
        for (i, creature) in creatures.into_iter().enumerate() {
            let overlay = overlays.get(i).unwrap_or(&none);
            let pixmap = picture(creature, &views[i], width, height, overlay)?;
            let mut frame = gif_image(&pixmap);
            frame.delay = delays_cs.get(i).or(delays_cs.last()).copied().unwrap_or(10);
            encoder
                .write_frame(&frame)
                .map_err(|e| RenderError::Gif(e.to_string()))?;
            progress((i + 1) as f64 / count as f64);
        }
        finish_gif(encoder)
    })
}
