//! The colours of pictures: the ones that carry meaning (neuron roles, joints, the target, the
//! trail, the marking red, ink), the paints made of them, and the GIF palette that keeps those
//! colours exact whatever else an image needs.

use std::collections::HashMap;

use tiny_skia::{Color, Paint, Pixmap};

/// Sensor neurons.
pub(super) const SENSOR: [u8; 3] = [40, 170, 70];
/// Actuator neurons.
pub(super) const ACTUATOR: [u8; 3] = [210, 50, 50];
/// Oscillator neurons.
pub(super) const OSCILLATOR: [u8; 3] = [140, 70, 190];
/// Other neurons.
pub(super) const NEURON: [u8; 3] = [60, 110, 200];
/// Movable joints' discs.
pub(super) const JOINT: [u8; 3] = [215, 40, 40];
/// Growing joints' discs.
pub(super) const GROWING_JOINT: [u8; 3] = [255, 120, 0];
/// Hinge axes.
pub(super) const AXIS: [u8; 3] = [25, 25, 25];
/// The aim task's target.
pub(super) const TARGET: [u8; 3] = [225, 0, 200];
/// A projectile's trail.
pub(super) const TRAIL: [u8; 3] = [190, 90, 0];
/// A walker's path on the ground.
pub(super) const PATH: [u8; 3] = [0, 120, 215];
/// What makes a creature invalid: interpenetrating parts, problem text.
pub(super) const MARK: [u8; 3] = [255, 0, 0];
/// Text.
pub(super) const INK: [u8; 3] = [20, 20, 20];
/// The brain panel's background.
pub(super) const PANEL: [u8; 3] = [248, 248, 250];

/// The colours a GIF's palette holds exactly, whatever else the image needs.
const KEY_COLOURS: [[u8; 3]; 14] = [
    SENSOR,
    ACTUATOR,
    OSCILLATOR,
    NEURON,
    JOINT,
    GROWING_JOINT,
    AXIS,
    TARGET,
    TRAIL,
    PATH,
    MARK,
    INK,
    PANEL,
    [255, 255, 255],
];

pub(super) fn paint(r: u8, g: u8, b: u8, a: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(r, g, b, a));
    p.anti_alias = true;
    p
}

pub(super) fn solid(c: [u8; 3]) -> Paint<'static> {
    paint(c[0], c[1], c[2], 255)
}

/// One GIF image of an opaque picture: a palette of the colours that carry meaning
/// ([`KEY_COLOURS`], exact) and the 242 more (256 less the key colours) that NeuQuant fits
/// to the rest of the picture; each pixel takes the nearest of the two candidates (its
/// NeuQuant colour or the nearest key colour), so a red actuator stays the red of the legend.
pub(super) fn gif_image(pixmap: &Pixmap) -> gif::Frame<'static> {
    let rgba = pixmap.data(); // opaque background: premultiplied = straight
    let quant = color_quant::NeuQuant::new(10, 256 - KEY_COLOURS.len(), rgba);
    let mut palette = quant.color_map_rgb();
    let learned = palette.len() / 3;
    palette.extend(KEY_COLOURS.iter().flatten());
    let distance = |a: &[u8], b: &[u8]| -> u32 {
        (0..3)
            .map(|k| (a[k] as i32 - b[k] as i32).pow(2) as u32)
            .sum()
    };
    let mut chosen: HashMap<[u8; 3], u8> = HashMap::new();
    let indices: Vec<u8> = rgba
        .chunks_exact(4)
        .map(|p| {
            *chosen.entry([p[0], p[1], p[2]]).or_insert_with(|| {
                let own = quant.index_of(p);
                let mut best = (distance(p, &palette[3 * own..3 * own + 3]), own);
                for (k, key) in KEY_COLOURS.iter().enumerate() {
                    let d = distance(p, key);
                    if d < best.0 {
                        best = (d, learned + k);
                    }
                }
                best.1 as u8
            })
        })
        .collect();
    gif::Frame::from_palette_pixels(
        pixmap.width() as u16,
        pixmap.height() as u16,
        indices,
        palette,
        None,
    )
}
