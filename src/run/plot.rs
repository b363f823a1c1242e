//! The fitness plot of a run (`runs/NAME/fitness.svg`), and a comparison's plots: mean best
//! fitness with 95% bands per encoding, and a strip chart of the champions' parts.

use std::path::{Path, PathBuf};

use plotters::chart::MeshStyle;
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;

use super::spread::Spread;
use super::store::GenerationRecord;

/// The failure floor: a failed evaluation's fitness. Values at or below it are not plotted.
pub const FAILURE_FLOOR: f64 = -999_999.0;

/// Why the plot could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// Drawing the chart failed.
    #[error("{}: cannot draw the fitness plot: {detail}", path.display())]
    Draw {
        /// The picture's path.
        path: PathBuf,
        /// What plotters reported.
        detail: String,
    },
    /// The file was refused or could not be written (see [`crate::output`]).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
}

/// A series: name, colour (Okabe–Ito, readable by colour-blind people), value.
type Series = (&'static str, RGBColor, fn(&GenerationRecord) -> f64);
const SERIES: [Series; 3] = [
    ("best", RGBColor(0, 114, 178), |g| g.best),
    ("mean", RGBColor(230, 159, 0), |g| g.mean),
    ("median", RGBColor(0, 158, 115), |g| g.median),
];

/// The legend of the best's line over the band of its walks' spread (a run with habitats or
/// trials).
pub const SPREAD_LABEL: &str = "best; band: its walks, lowest to highest";

/// The legend of the dashed line of the best re-walked at the fine reference setting.
pub const FINE_LABEL: &str = "best, re-walked at the fine reference";

/// The dashed series: the best individual re-walked at the fine reference (NaN, so not
/// plotted, where it was not), in the best's colour.
const FINE: Series = (FINE_LABEL, RGBColor(0, 114, 178), |g| {
    g.best_fine.as_ref().map_or(f64::NAN, |f| f.fitness)
});

/// The series to draw: the three, and the dashed one when some generation was verified.
fn series(generations: &[GenerationRecord]) -> Vec<(Series, bool)> {
    let mut out: Vec<(Series, bool)> = SERIES.iter().map(|&s| (s, false)).collect();
    if generations.iter().any(|g| g.best_fine.is_some()) {
        out.push((FINE, true));
    }
    out
}

/// A value worth plotting: a number above the failure floor.
fn plotted(y: f64) -> bool {
    y.is_finite() && y > FAILURE_FLOOR
}

/// Writes an SVG plot of best, mean and median fitness per generation to `path` (three
/// labelled lines with a legend beside the chart; axes "generation" and `y_desc`, what the
/// fitness measures and its unit), under `title`. When some
/// generation's best was re-walked at the fine reference setting
/// ([`GenerationRecord::best_fine`]), a fourth, dashed line ([`FINE_LABEL`]) shows it.
///
/// The GA computes `mean` and `median` over valid individuals only, since failed ones score
/// the failure floor −999999 and would drown the others. The plot is robust anyway: values at
/// or below the floor, and NaN (no valid individual), are skipped, leaving a gap in the line,
/// and do not stretch the y range. A point with no neighbour is drawn as a dot.
///
/// The file is written to a temporary name beside `path` and renamed, so a viewer never sees
/// half a picture.
pub fn fitness_svg(
    path: &Path,
    generations: &[GenerationRecord],
    title: &str,
    y_desc: &str,
) -> Result<(), PlotError> {
    fitness_svg_with_spreads(path, generations, &[], title, y_desc)
}

/// [`fitness_svg`] of a run with habitats or trials: the best's line (the aggregate of its
/// walks) is drawn over a shaded band from its lowest walk's fitness to its highest, each
/// generation's of `spreads` ([`SPREAD_LABEL`]); with no spreads, the plain picture.
pub fn fitness_svg_with_spreads(
    path: &Path,
    generations: &[GenerationRecord],
    spreads: &[Spread],
    title: &str,
    y_desc: &str,
) -> Result<(), PlotError> {
    write_plot(path, |svg| draw(svg, generations, spreads, title, y_desc))
}

/// The y range: the plotted values' span (the spreads' too), padded by 5 % (at least ±0.5
/// around a single value), or 0..1 when there is nothing to plot.
fn y_range(generations: &[GenerationRecord], spreads: &[Spread]) -> (f64, f64) {
    let shown = series(generations);
    let values = generations
        .iter()
        .flat_map(|g| shown.iter().map(move |((_, _, f), _)| f(g)))
        .chain(spreads.iter().flat_map(|s| [s.low, s.high]))
        .filter(|&y| plotted(y));
    let (lo, hi) = span(values.map(|y| (y, y)));
    if lo > hi {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05).max(0.5);
    (lo - pad, hi + pad)
}

/// Splits the spreads into runs of consecutive generations.
fn spread_runs(spreads: &[Spread]) -> Vec<&[Spread]> {
    let mut runs = Vec::new();
    let mut start = 0;
    for k in 1..=spreads.len() {
        if k == spreads.len() || spreads[k].generation != spreads[k - 1].generation + 1 {
            runs.push(&spreads[start..k]);
            start = k;
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// The lowest low and the highest high of `ranges` (low, high); (∞, −∞) when empty.
fn span(ranges: impl Iterator<Item = (f64, f64)>) -> (f64, f64) {
    ranges.fold(
        (f64::INFINITY, f64::NEG_INFINITY),
        |(lo, hi), (low, high)| (lo.min(low), hi.max(high)),
    )
}

/// Splits a series into runs of consecutive plotted points.
fn segments(
    generations: &[GenerationRecord],
    value: fn(&GenerationRecord) -> f64,
) -> Vec<Vec<(u32, f64)>> {
    let mut out: Vec<Vec<(u32, f64)>> = Vec::new();
    let mut previous: Option<u32> = None;
    for g in generations {
        let y = value(g);
        if !plotted(y) {
            previous = None;
            continue;
        }
        match (previous, out.last_mut()) {
            (Some(p), Some(run)) if g.index == p + 1 => run.push((g.index, y)),
            _ => out.push(vec![(g.index, y)]),
        }
        previous = Some(g.index);
    }
    out
}

/// The fitness plot's chart.
type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordu32, plotters::coord::types::RangedCoordf64>,
>;

/// Draws one run of points as a line, dashed (6 pixels, 4 apart) or solid.
fn draw_line(
    chart: &mut Chart<'_, '_>,
    run: Vec<(u32, f64)>,
    style: ShapeStyle,
    dashed: bool,
) -> Result<(), String> {
    if dashed {
        chart.draw_series(DashedLineSeries::new(run, 6, 4, style))
    } else {
        chart.draw_series(LineSeries::new(run, style))
    }
    .map(|_| ())
    .map_err(|x| x.to_string())
}

fn draw(
    svg: &mut String,
    generations: &[GenerationRecord],
    spreads: &[Spread],
    title: &str,
    y_desc: &str,
) -> Result<(), String> {
    let root = canvas(svg)?;
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let first = generations.iter().map(|g| g.index).min().unwrap_or(0);
    let last = generations.iter().map(|g| g.index).max().unwrap_or(0);
    let (y0, y1) = y_range(generations, spreads);
    let shown = series(generations);
    let banded = !spreads.is_empty();
    let entries: Vec<LegendEntry> = shown
        .iter()
        .enumerate()
        .map(|(k, &((name, colour, _), dashed))| LegendEntry {
            // The best's line (the first) is drawn over the band.
            name: if k == 0 && banded { SPREAD_LABEL } else { name }.to_string(),
            colour,
            dashed,
            band: k == 0 && banded,
        })
        .collect();
    let (area, legend) = beside_legend(&root, title, &entries)?;
    let mut chart = chart(&area, first..last.max(first + 1), y0..y1)?;
    draw_mesh(chart.configure_mesh().x_desc("generation").y_desc(y_desc))?;
    let (_, best_colour, _) = SERIES[0];
    for run in spread_runs(spreads) {
        if run.len() == 1 {
            // One generation: a bar from low to high.
            let s = run[0];
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(s.generation, s.low), (s.generation, s.high)],
                    best_colour.mix(0.4).stroke_width(6),
                )))
                .map_err(|x| e(&x))?;
            continue;
        }
        let mut outline: Vec<(u32, f64)> = run.iter().map(|s| (s.generation, s.high)).collect();
        outline.extend(run.iter().rev().map(|s| (s.generation, s.low)));
        chart
            .draw_series(std::iter::once(Polygon::new(
                outline,
                best_colour.mix(0.18),
            )))
            .map_err(|x| e(&x))?;
    }
    for ((_, colour, value), dashed) in shown {
        let style = colour.stroke_width(2);
        for run in segments(generations, value) {
            if run.len() == 1 {
                chart
                    .draw_series(std::iter::once(Circle::new(run[0], 3, colour.filled())))
                    .map_err(|x| e(&x))?;
            } else {
                draw_line(&mut chart, run, style, dashed)?;
            }
        }
    }
    draw_legend(&legend, &entries)?;
    root.present().map_err(|x| e(&x))?;
    Ok(())
}

/// One line with a band: a name and points (x, mean, low, high).
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    /// The legend's text.
    pub name: String,
    /// (x, y, band low, band high), by increasing x.
    pub points: Vec<(f64, f64, f64, f64)>,
}

/// Colours of a comparison's series (Okabe–Ito), in order.
const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(213, 94, 0),
    RGBColor(0, 0, 0),
];

/// Draws an SVG with `draw` and writes it to `path`, whole or not at all
/// ([`crate::output::write`]).
fn write_plot(
    path: &Path,
    draw: impl FnOnce(&mut String) -> Result<(), String>,
) -> Result<(), PlotError> {
    let mut svg = String::new();
    draw(&mut svg).map_err(|detail| PlotError::Draw {
        path: path.into(),
        detail,
    })?;
    Ok(crate::output::write(path, svg)?)
}

/// A plot's drawing area: 900 × 540 pixels of SVG, written into `svg`, filled white.
fn canvas(svg: &mut String) -> Result<DrawingArea<SVGBackend<'_>, Shift>, String> {
    let root = SVGBackend::with_string(svg, (900, 540)).into_drawing_area();
    root.fill(&WHITE).map_err(|x| x.to_string())?;
    Ok(root)
}

/// A chart of `x` against `y` drawn into SVG.
type PlotChart<'a, 'b, X, Y> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<<X as AsRangedCoord>::CoordDescType, <Y as AsRangedCoord>::CoordDescType>,
>;

/// A chart of `x` against `y` on `area`, with the plots' margin and label areas.
fn chart<'a, 'b, X: AsRangedCoord, Y: AsRangedCoord>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    x: X,
    y: Y,
) -> Result<PlotChart<'a, 'b, X, Y>, String> {
    ChartBuilder::on(area)
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(x, y)
        .map_err(|x| x.to_string())
}

/// Draws `mesh`, set up with what differs between plots, in their common style: sans-serif
/// labels and light grid lines.
fn draw_mesh<X, Y>(mesh: &mut MeshStyle<'_, '_, X, Y, SVGBackend<'_>>) -> Result<(), String>
where
    X: Ranged + ValueFormatter<X::ValueType>,
    Y: Ranged + ValueFormatter<Y::ValueType>,
{
    mesh.label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|x| x.to_string())
}

/// A part of a plot's SVG drawing.
type Area<'b> = DrawingArea<SVGBackend<'b>, Shift>;

/// An entry of a plot's legend: a line of a colour, solid or dashed, over a shaded band or
/// not.
struct LegendEntry {
    name: String,
    colour: RGBColor,
    dashed: bool,
    band: bool,
}

/// `root` under `title`, split into the chart's area and, on its right, the legend's, wide
/// enough for the longest entry: the legend hides no data.
fn beside_legend<'b>(
    root: &Area<'b>,
    title: &str,
    entries: &[LegendEntry],
) -> Result<(Area<'b>, Area<'b>), String> {
    let titled = root
        .titled(title, ("sans-serif", 24))
        .map_err(|x| x.to_string())?;
    let longest = entries
        .iter()
        .map(|e| e.name.chars().count())
        .max()
        .unwrap_or(0);
    let width = (longest as i32 * 13 / 2 + 52).clamp(110, 320);
    let (w, _) = titled.dim_in_pixel();
    Ok(titled.split_horizontally(w as i32 - width))
}

/// Draws the legend's `entries` down `area`, from the height of the chart's top.
fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    entries: &[LegendEntry],
) -> Result<(), String> {
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let font = ("sans-serif", 14).into_font().color(&BLACK);
    for (k, entry) in entries.iter().enumerate() {
        let y = 28 + 22 * k as i32;
        let style = entry.colour.stroke_width(2);
        if entry.band {
            area.draw(&Rectangle::new(
                [(4, y - 7), (32, y + 7)],
                entry.colour.mix(0.18).filled(),
            ))
            .map_err(|x| e(&x))?;
        }
        let pieces: &[(i32, i32)] = if entry.dashed {
            &[(4, 13), (19, 28), (34, 36)]
        } else {
            &[(4, 32)]
        };
        for &(a, b) in pieces {
            area.draw(&PathElement::new(
                vec![(a.min(32), y), (b.min(32), y)],
                style,
            ))
            .map_err(|x| e(&x))?;
        }
        area.draw(&Text::new(entry.name.clone(), (40, y - 8), font.clone()))
            .map_err(|x| e(&x))?;
    }
    Ok(())
}

/// Writes an SVG of one line per band (mean best fitness against evaluations, whole numbers
/// on the x axis) over its shaded 95% band, with a legend beside the chart; `y_desc` says what
/// the fitness measures. Values at or below the failure floor are left out.
pub fn bands_svg(path: &Path, bands: &[Band], title: &str, y_desc: &str) -> Result<(), PlotError> {
    write_plot(path, |svg| draw_bands(svg, bands, title, y_desc))
}

fn draw_bands(svg: &mut String, bands: &[Band], title: &str, y_desc: &str) -> Result<(), String> {
    let root = canvas(svg)?;
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let shown = |b: &Band| -> Vec<(f64, f64, f64, f64)> {
        b.points
            .iter()
            .copied()
            .filter(|p| plotted(p.1) && plotted(p.2) && plotted(p.3))
            .collect()
    };
    let all: Vec<(f64, f64, f64, f64)> = bands.iter().flat_map(shown).collect();
    let (x0, x1) = span(all.iter().map(|p| (p.0, p.0)));
    let (x0, x1) = if x0 > x1 {
        (0.0, 1.0)
    } else {
        (x0, x1.max(x0 + 1.0))
    };
    let (lo, hi) = span(all.iter().map(|p| (p.2, p.3)));
    // Fitness of a comparison may span hundredths: pad by 5% of the span, not a fixed amount.
    let (y0, y1) = if lo > hi {
        (0.0, 1.0)
    } else if hi - lo < 1e-12 {
        (lo - 0.5, hi + 0.5)
    } else {
        let pad = (hi - lo) * 0.05;
        (lo - pad, hi + pad)
    };
    let entries: Vec<LegendEntry> = bands
        .iter()
        .enumerate()
        .map(|(i, b)| LegendEntry {
            name: b.name.clone(),
            colour: PALETTE[i % PALETTE.len()],
            dashed: false,
            band: true,
        })
        .collect();
    let (area, legend) = beside_legend(&root, title, &entries)?;
    // Evaluations are whole numbers: an integer axis labels them so.
    let whole = |x: f64| x.round() as i64;
    let (x0, x1) = (
        x0.floor() as i64,
        (x1.ceil() as i64).max(x0.floor() as i64 + 1),
    );
    let mut chart = chart(&area, x0..x1, y0..y1)?;
    draw_mesh(
        chart
            .configure_mesh()
            .x_desc("evaluations")
            .y_desc(format!("mean best fitness: {y_desc}")),
    )?;
    for (i, band) in bands.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        let points = shown(band);
        let mut outline: Vec<(i64, f64)> = points.iter().map(|p| (whole(p.0), p.3)).collect();
        outline.extend(points.iter().rev().map(|p| (whole(p.0), p.2)));
        if points.len() > 1 {
            chart
                .draw_series(std::iter::once(Polygon::new(outline, colour.mix(0.18))))
                .map_err(|x| e(&x))?;
        }
        let style = colour.stroke_width(2);
        chart
            .draw_series(LineSeries::new(
                points.iter().map(|p| (whole(p.0), p.1)),
                style,
            ))
            .map_err(|x| e(&x))?;
    }
    draw_legend(&legend, &entries)?;
    root.present().map_err(|x| e(&x))?;
    Ok(())
}

/// Writes an SVG strip chart of counts: one column per group (its name below it), a dot per
/// value (spread sideways so equal values stay visible) and a bar at the median, whole numbers
/// on the y axis; `y_desc` names the values.
pub fn strip_svg(
    path: &Path,
    groups: &[(String, Vec<f64>)],
    y_desc: &str,
    title: &str,
) -> Result<(), PlotError> {
    write_plot(path, |svg| draw_strip(svg, groups, y_desc, title))
}

fn draw_strip(
    svg: &mut String,
    groups: &[(String, Vec<f64>)],
    y_desc: &str,
    title: &str,
) -> Result<(), String> {
    let root = canvas(svg)?;
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let hi = groups
        .iter()
        .flat_map(|g| g.1.iter().copied())
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    let n = groups.len().max(1);
    let names: Vec<String> = groups.iter().map(|g| g.0.clone()).collect();
    let area = root.titled(title, ("sans-serif", 24)).map_err(|x| e(&x))?;
    let mut chart = chart(&area, -0.5..(n as f64 - 0.5), 0.0..(hi * 1.1).max(1.0))?;
    draw_mesh(
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(n)
            .x_label_formatter(&|x| {
                let i = x.round();
                if (x - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < names.len() {
                    names[i as usize].clone()
                } else {
                    String::new()
                }
            })
            // Counts: whole numbers only on the axis.
            .y_label_formatter(&|y| {
                if (y - y.round()).abs() < 1e-9 {
                    format!("{}", y.round())
                } else {
                    String::new()
                }
            })
            .y_desc(y_desc),
    )?;
    for (i, (_, values)) in groups.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        let count = values.len().max(1) as f64;
        chart
            .draw_series(values.iter().enumerate().map(|(k, &v)| {
                let x = i as f64 + 0.3 * ((k as f64 + 0.5) / count - 0.5);
                Circle::new((x, v), 4, colour.filled())
            }))
            .map_err(|x| e(&x))?;
        let mut sorted: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
        sorted.sort_by(f64::total_cmp);
        if !sorted.is_empty() {
            let m = sorted.len();
            let median = if m % 2 == 1 {
                sorted[m / 2]
            } else {
                (sorted[m / 2 - 1] + sorted[m / 2]) / 2.0
            };
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(i as f64 - 0.25, median), (i as f64 + 0.25, median)],
                    colour.stroke_width(3),
                )))
                .map_err(|x| e(&x))?;
        }
    }
    root.present().map_err(|x| e(&x))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::fs;

    use super::*;

    fn generation(index: u32, best: f64, mean: f64, median: f64) -> GenerationRecord {
        GenerationRecord {
            index,
            best,
            mean,
            median,
            sd: 0.0,
            valid_fraction: 1.0,
            evaluations: 10,
            reused: 0,
            wall_seconds: 1.0,
            evaluations_per_second: 10.0,
            best_fine: None,
        }
    }

    /// `count` generations whose best rises by 1 each from `first_best`, with a constant
    /// mean and median.
    fn rising(count: u32, first_best: f64, mean: f64, median: f64) -> Vec<GenerationRecord> {
        (0..count)
            .map(|g| generation(g, first_best + g as f64, mean, median))
            .collect()
    }

    /// A scratch folder (removed when dropped) and the path of `fitness.svg` in it.
    fn scratch_chart() -> (tempfile::TempDir, std::path::PathBuf) {
        let scratch = tempfile::tempdir().unwrap();
        let path = scratch.path().join("fitness.svg");
        (scratch, path)
    }

    #[test]
    fn y_range_ignores_the_failure_floor_and_nan() {
        let gs = [
            generation(0, 10.0, FAILURE_FLOOR, f64::NAN),
            generation(1, 30.0, 20.0, -999_999.5),
        ];
        // Plotted values 10, 30, 20: span 20, padded by 1 on each side.
        assert_eq!(y_range(&gs, &[]), (9.0, 31.0));
        assert_eq!(y_range(&[], &[]), (0.0, 1.0));
        // A single value gets ±0.5.
        assert_eq!(y_range(&[generation(0, 2.0, 2.0, 2.0)], &[]), (1.5, 2.5));
    }

    #[test]
    fn segments_break_at_skipped_points_and_gaps() {
        let gs = [
            generation(0, 1.0, 0.0, 0.0),
            generation(1, FAILURE_FLOOR, 0.0, 0.0),
            generation(2, 2.0, 0.0, 0.0),
            generation(3, 3.0, 0.0, 0.0),
            generation(5, 5.0, 0.0, 0.0),
        ];
        assert_eq!(
            segments(&gs, |g| g.best),
            vec![vec![(0, 1.0)], vec![(2, 2.0), (3, 3.0)], vec![(5, 5.0)]]
        );
    }

    /// The x of the text `text` in `svg` (plotters writes a text's words on a line of their
    /// own, after its tag).
    fn text_x(svg: &str, text: &str) -> f64 {
        let lines: Vec<&str> = svg.lines().collect();
        let k = lines.iter().position(|l| l.trim() == text).unwrap();
        let tag = lines[k - 1];
        let x = tag.split("x=\"").nth(1).unwrap().split('"').next().unwrap();
        x.parse().unwrap()
    }

    /// The largest x of the chart's frame and data lines.
    fn rightmost_line(svg: &str) -> f64 {
        svg.split("points=\"")
            .skip(1)
            .flat_map(|rest| rest.split('"').next().unwrap().split_whitespace())
            .map(|p| p.split(',').next().unwrap().parse::<f64>().unwrap())
            .fold(f64::NEG_INFINITY, f64::max)
    }

    #[test]
    fn a_run_with_habitats_draws_the_best_over_the_band_of_its_walks() {
        let (_scratch, path) = scratch_chart();
        let gs = rising(3, 2.0, 1.5, 1.5);
        let spreads: Vec<Spread> = (0..3)
            .map(|g| Spread {
                generation: g,
                low: 1.0 + g as f64,
                high: 4.0 + g as f64,
            })
            .collect();
        // The band reaches 1 and 6: span 5, padded by 0.5 (5 % is less).
        assert_eq!(y_range(&gs, &spreads), (0.5, 6.5));
        fitness_svg_with_spreads(&path, &gs, &spreads, "title", "fitness").unwrap();
        let banded = fs::read_to_string(&path).unwrap();
        assert!(banded.lines().any(|l| l.trim() == SPREAD_LABEL));
        assert!(!banded.lines().any(|l| l.trim() == "best"));
        fitness_svg(&path, &gs, "title", "fitness").unwrap();
        let plain = fs::read_to_string(&path).unwrap();
        assert!(plain.lines().any(|l| l.trim() == "best"));
        // The band is one shaded polygon, and a square in the legend.
        assert_eq!(
            banded.matches("<polygon").count(),
            plain.matches("<polygon").count() + 1
        );
        assert_eq!(
            banded.matches("<rect").count(),
            plain.matches("<rect").count() + 1
        );
    }

    #[test]
    fn the_legend_is_beside_the_chart_and_the_y_axis_names_the_fitness() {
        let (_scratch, path) = scratch_chart();
        let gs = rising(5, 1.0, 0.5, 0.4);
        fitness_svg(&path, &gs, "title", "fitness: distance (m)").unwrap();
        let svg = fs::read_to_string(&path).unwrap();
        assert!(svg.lines().any(|l| l.trim() == "fitness: distance (m)"));
        let right = rightmost_line(&svg);
        for name in ["best", "mean", "median"] {
            assert!(text_x(&svg, name) > right, "{name} over the chart");
        }
        // A comparison: whole numbers of evaluations on its x axis, the legend beside.
        let bands = [Band {
            name: "lsystem".into(),
            points: vec![
                (10.0, 1.0, 0.5, 1.5),
                (12.0, 2.0, 1.5, 2.5),
                (14.0, 3.0, 2.0, 4.0),
            ],
        }];
        bands_svg(&path, &bands, "title", "distance (m)").unwrap();
        let svg = fs::read_to_string(&path).unwrap();
        let texts: Vec<&str> = svg.lines().map(str::trim).collect();
        assert!(texts.contains(&"12") && !texts.contains(&"12.0"), "{svg}");
        assert!(texts.contains(&"mean best fitness: distance (m)"));
        assert!(text_x(&svg, "lsystem") > rightmost_line(&svg));
    }

    #[test]
    fn comparison_plots_draw_every_series() {
        let scratch = tempfile::tempdir().unwrap();
        let dir = scratch.path();
        let bands = [
            Band {
                name: "first-encoding".into(),
                points: vec![(6.0, 0.01, 0.0, 0.02), (11.0, 0.03, 0.02, 0.04)],
            },
            Band {
                name: "second-encoding".into(),
                // A failed point is left out, not drawn at the floor.
                points: vec![
                    (6.0, FAILURE_FLOOR, FAILURE_FLOOR, 0.0),
                    (11.0, 0.02, 0.01, 0.03),
                ],
            },
        ];
        let path = dir.join("bands.svg");
        bands_svg(&path, &bands, "title", "distance (m)").unwrap();
        let svg = fs::read_to_string(&path).unwrap();
        assert!(svg.contains("first-encoding") && svg.contains("second-encoding"));
        assert!(svg.contains("<polygon"), "a band is drawn");
        assert!(
            !svg.contains("999999"),
            "the failure floor stretches no axis"
        );
        let path = dir.join("strip.svg");
        strip_svg(
            &path,
            &[("a".into(), vec![3.0, 5.0, 9.0]), ("b".into(), vec![1.0])],
            "parts",
            "title",
        )
        .unwrap();
        let svg = fs::read_to_string(&path).unwrap();
        // Four dots.
        assert_eq!(svg.matches("<circle").count(), 4, "{svg}");
        let _ = fs::remove_dir_all(dir);
    }
}
