//! SVG figures in the style of the paper's Figures 4-8, from plain data.
//!
//! Drawn with plotters' SVG backend without any font library: text is written as SVG `<text>`
//! elements and rendered by the viewer (plotters only estimates its size for the layout).
//! Every figure is rendered to memory first and then written atomically, so a failed plot never
//! leaves a broken or clobbered file. Nothing here knows about experiments.
//!
//! - [`line_plot`]: several series vs time, each with an optional +-std band (Figs. 4, 5).
//! - [`event_plot`]: series with vertical event lines (pushes) and a second y axis (Fig. 7).
//! - [`fall_probability_plot`]: fall probability curves plus binned estimates (Fig. 6).
//! - [`heat_map_grid`]: small multiples of 2-D maps with data-point crosses (Fig. 8).
//! - [`polar_plot`]: values by push direction, seen from above.

use super::{ReportError, write_file};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// One curve: y against x, with an optional half-width of a band drawn as y +- spread
/// (e.g. the standard deviation).
#[derive(Debug, Clone, Copy)]
pub struct Series<'a> {
    /// Legend entry.
    pub name: &'a str,
    /// Abscissae.
    pub x: &'a [f64],
    /// Ordinates (same length as `x`).
    pub y: &'a [f64],
    /// Optional band half-width per point (same length as `x`, >= 0).
    pub spread: Option<&'a [f64]>,
}

/// A line plot of several series.
#[derive(Debug, Clone, Copy)]
pub struct LinePlot<'a> {
    /// Title above the plot.
    pub title: &'a str,
    /// x axis label.
    pub x_label: &'a str,
    /// y axis label.
    pub y_label: &'a str,
    /// The series, drawn in order with distinct colours.
    pub series: &'a [Series<'a>],
}

/// Series on a left axis, an optional series on a right axis, and vertical event lines.
#[derive(Debug, Clone, Copy)]
pub struct EventPlot<'a> {
    /// Title above the plot.
    pub title: &'a str,
    /// x axis label.
    pub x_label: &'a str,
    /// Left y axis label.
    pub y_label: &'a str,
    /// Series on the left axis.
    pub series: &'a [Series<'a>],
    /// Right y axis label and its series (drawn dashed-looking in grey-black).
    pub secondary: Option<(&'a str, Series<'a>)>,
    /// x positions of events (e.g. pushes), drawn as vertical lines.
    pub events: &'a [f64],
    /// Legend entry of the event lines.
    pub event_label: &'a str,
}

/// One controller's fall probability: a smooth curve and binned estimates.
#[derive(Debug, Clone, Copy)]
pub struct FallCurve<'a> {
    /// Legend entry.
    pub name: &'a str,
    /// Impulses of the curve.
    pub impulse: &'a [f64],
    /// Probabilities of the curve, in [0, 1].
    pub probability: &'a [f64],
    /// Binned estimates: (bin centre, fraction fallen in [0, 1]), drawn as markers.
    pub bins: &'a [(f64, f64)],
}

/// A fall probability figure.
#[derive(Debug, Clone, Copy)]
pub struct FallPlot<'a> {
    /// Title above the plot.
    pub title: &'a str,
    /// x axis label (e.g. "push impulse (Ns)").
    pub x_label: &'a str,
    /// One entry per controller.
    pub curves: &'a [FallCurve<'a>],
}

/// One 2-D map: values on a grid, plus data points marked with crosses.
#[derive(Debug, Clone, Copy)]
pub struct HeatPanel<'a> {
    /// Panel title.
    pub title: &'a str,
    /// Column coordinates (ascending, at least 2).
    pub xs: &'a [f64],
    /// Row coordinates (ascending, at least 2).
    pub ys: &'a [f64],
    /// Row-major values: `values[row * xs.len() + col]`.
    pub values: &'a [f64],
    /// Data points (x, y) drawn as black crosses (points outside the map are skipped).
    pub points: &'a [(f64, f64)],
}

/// Small multiples of heat maps sharing one symmetric colour scale (blue < 0 < red).
#[derive(Debug, Clone, Copy)]
pub struct HeatMapGrid<'a> {
    /// Title above all panels.
    pub title: &'a str,
    /// x axis label of every panel.
    pub x_label: &'a str,
    /// y axis label of every panel.
    pub y_label: &'a str,
    /// Label of the colour bar.
    pub value_label: &'a str,
    /// The panels, left to right, top to bottom.
    pub panels: &'a [HeatPanel<'a>],
    /// Panels per row (>= 1).
    pub columns: usize,
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

fn colour(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// The colour of a series: one fixed colour per controller in every figure (model blue,
/// learned red, open-loop green, learner only purple, the reference black), otherwise the
/// palette's `i`-th.
pub fn series_colour(name: &str, i: usize) -> RGBColor {
    let name = name.to_ascii_lowercase();
    if name.starts_with("reference") {
        RGBColor(0, 0, 0)
    } else if name.starts_with("model") {
        PALETTE[0]
    } else if name.starts_with("learned") {
        PALETTE[1]
    } else if name.starts_with("open-loop") || name.starts_with("open loop") {
        PALETTE[2]
    } else if name.starts_with("learner only") {
        PALETTE[4]
    } else if name.starts_with("no learning") {
        PALETTE[5]
    } else {
        colour(i)
    }
}

pub(crate) fn plot_err<E: std::fmt::Display>(e: E) -> ReportError {
    ReportError::Plot(e.to_string())
}

fn check_finite(what: &str, v: &[f64]) -> Result<(), ReportError> {
    match v.iter().find(|x| !x.is_finite()) {
        Some(x) => Err(ReportError::invalid(format!("{what} holds {x}"))),
        None => Ok(()),
    }
}

impl Series<'_> {
    fn validate(&self) -> Result<(), ReportError> {
        let n = self.x.len();
        if n == 0 || self.y.len() != n || self.spread.is_some_and(|s| s.len() != n) {
            return Err(ReportError::invalid(format!(
                "series {:?}: x, y (and spread) must have the same non-zero length",
                self.name
            )));
        }
        check_finite(self.name, self.x)?;
        check_finite(self.name, self.y)?;
        if let Some(s) = self.spread {
            check_finite(self.name, s)?;
            if s.iter().any(|v| *v < 0.0) {
                return Err(ReportError::invalid(format!(
                    "series {:?}: negative spread",
                    self.name
                )));
            }
        }
        Ok(())
    }

    /// (x range, y range) covered, bands included.
    fn bounds(&self) -> (Range<f64>, Range<f64>) {
        let spread = |i: usize| self.spread.map_or(0.0, |s| s[i]);
        let mut xr = f64::INFINITY..f64::NEG_INFINITY;
        let mut yr = f64::INFINITY..f64::NEG_INFINITY;
        for i in 0..self.x.len() {
            xr = xr.start.min(self.x[i])..xr.end.max(self.x[i]);
            yr = yr.start.min(self.y[i] - spread(i))..yr.end.max(self.y[i] + spread(i));
        }
        (xr, yr)
    }
}

fn union(a: Range<f64>, b: Range<f64>) -> Range<f64> {
    a.start.min(b.start)..a.end.max(b.end)
}

/// Widens a range by 5% (or by 1 if it is empty) so nothing sits on the frame.
fn padded(r: Range<f64>) -> Range<f64> {
    let w = r.end - r.start;
    if w > 0.0 {
        r.start - 0.05 * w..r.end + 0.05 * w
    } else {
        r.start - 1.0..r.end + 1.0
    }
}

fn series_bounds(series: &[Series]) -> Result<(Range<f64>, Range<f64>), ReportError> {
    let mut it = series.iter();
    let first = it
        .next()
        .ok_or_else(|| ReportError::invalid("a plot needs at least one series"))?;
    first.validate()?;
    let (mut xr, mut yr) = first.bounds();
    for s in it {
        s.validate()?;
        let (x, y) = s.bounds();
        xr = union(xr, x);
        yr = union(yr, y);
    }
    Ok((xr, yr))
}

/// Renders into an in-memory SVG, then writes it atomically.
pub(crate) fn render(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend, Shift>) -> Result<(), ReportError>,
) -> Result<(), ReportError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        draw(&root)?;
        root.present().map_err(plot_err)?;
    }
    write_file(path, svg.as_bytes())
}

type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Draws bands (clipped to `clip`) then lines of `series` with legend entries, colours from
/// `offset`.
fn draw_series(
    chart: &mut Chart,
    series: &[Series],
    offset: usize,
    clip: Range<f64>,
) -> Result<(), ReportError> {
    for (i, s) in series.iter().enumerate() {
        let c = series_colour(s.name, i + offset);
        if let Some(spread) = s.spread {
            let y = |v: f64| v.clamp(clip.start, clip.end);
            let upper = (0..s.x.len()).map(|k| (s.x[k], y(s.y[k] + spread[k])));
            let lower = (0..s.x.len())
                .rev()
                .map(|k| (s.x[k], y(s.y[k] - spread[k])));
            chart
                .draw_series(std::iter::once(Polygon::new(
                    upper.chain(lower).collect::<Vec<_>>(),
                    c.mix(0.2).filled(),
                )))
                .map_err(plot_err)?;
        }
    }
    for (i, s) in series.iter().enumerate() {
        let c = series_colour(s.name, i + offset);
        chart
            .draw_series(LineSeries::new(
                s.x.iter().copied().zip(s.y.iter().copied()),
                c.stroke_width(2),
            ))
            .map_err(plot_err)?
            .label(s.name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    Ok(())
}

fn draw_legend<'a>(chart: &mut Chart<'a, 'a>) -> Result<(), ReportError> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(plot_err)
}

/// Line plot of several series with optional +-spread bands (Figs. 4, 5).
pub fn line_plot(path: &Path, plot: &LinePlot) -> Result<(), ReportError> {
    line_plot_ticks(path, plot, false, f64::NEG_INFINITY..f64::INFINITY)
}

/// [`line_plot`] with labels only at integer x ticks when `integer_x` (a count on the x
/// axis), and bands clipped to the range `y_clip` (the values a quantity can take).
pub fn line_plot_ticks(
    path: &Path,
    plot: &LinePlot,
    integer_x: bool,
    y_clip: Range<f64>,
) -> Result<(), ReportError> {
    let (xr, yr) = series_bounds(plot.series)?;
    let yr = yr.start.max(y_clip.start)..yr.end.min(y_clip.end);
    let x_tick = |v: &f64| {
        if integer_x && (v - v.round()).abs() > 1e-9 {
            String::new()
        } else {
            tick(v)
        }
    };
    render(path, (800, 500), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(plot.title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(padded(xr), padded(yr))
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .x_label_formatter(&x_tick)
            .y_label_formatter(&tick)
            .x_desc(plot.x_label)
            .y_desc(plot.y_label)
            .draw()
            .map_err(plot_err)?;
        draw_series(&mut chart, plot.series, 0, y_clip)?;
        draw_legend(&mut chart)
    })
}

/// Series with vertical event lines and an optional second y axis (Fig. 7).
pub fn event_plot(path: &Path, plot: &EventPlot) -> Result<(), ReportError> {
    let (mut xr, yr) = series_bounds(plot.series)?;
    check_finite("events", plot.events)?;
    for &e in plot.events {
        xr = union(xr, e..e);
    }
    let secondary = match plot.secondary {
        Some((label, s)) => {
            let (x2, y2) = series_bounds(std::slice::from_ref(&s))?;
            xr = union(xr, x2);
            Some((label, s, padded(y2)))
        }
        None => None,
    };
    let (xr, yr) = (padded(xr), padded(yr));
    // Draws the mesh, event lines and left-axis series on the primary coordinates.
    let draw_primary = |chart: &mut Chart| -> Result<(), ReportError> {
        chart
            .configure_mesh()
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .x_desc(plot.x_label)
            .y_desc(plot.y_label)
            .draw()
            .map_err(plot_err)?;
        let event_style = RGBColor(120, 120, 120).stroke_width(1);
        if !plot.events.is_empty() {
            chart
                .draw_series(
                    plot.events
                        .iter()
                        .map(|&e| PathElement::new(vec![(e, yr.start), (e, yr.end)], event_style)),
                )
                .map_err(plot_err)?
                .label(plot.event_label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x + 10, y - 6), (x + 10, y + 6)], event_style)
                });
        }
        draw_series(chart, plot.series, 0, f64::NEG_INFINITY..f64::INFINITY)
    };
    render(path, (900, 500), |root| {
        let chart = ChartBuilder::on(root)
            .caption(plot.title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .right_y_label_area_size(if secondary.is_some() { 65 } else { 0 })
            .build_cartesian_2d(xr.clone(), yr.clone())
            .map_err(plot_err)?;
        let Some((label, s, y2)) = secondary else {
            let mut chart = chart;
            draw_primary(&mut chart)?;
            return draw_legend(&mut chart);
        };
        // The secondary coordinates must be attached before the mesh is drawn, or the
        // primary labels are drawn on the right axis too.
        let mut chart = chart.set_secondary_coord(xr, y2);
        draw_primary(&mut chart)?;
        chart
            .configure_secondary_axes()
            .y_label_formatter(&tick)
            .y_desc(label)
            .draw()
            .map_err(plot_err)?;
        let c = BLACK;
        chart
            .draw_secondary_series(LineSeries::new(
                s.x.iter().copied().zip(s.y.iter().copied()),
                c.stroke_width(2),
            ))
            .map_err(plot_err)?
            .label(s.name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(plot_err)
    })
}

/// Fall probability vs impulse for several controllers: curves and binned markers (Fig. 6).
pub fn fall_probability_plot(path: &Path, plot: &FallPlot) -> Result<(), ReportError> {
    if plot.curves.is_empty() {
        return Err(ReportError::invalid("a fall plot needs at least one curve"));
    }
    let mut xr = f64::INFINITY..f64::NEG_INFINITY;
    for c in plot.curves {
        let s = Series {
            name: c.name,
            x: c.impulse,
            y: c.probability,
            spread: None,
        };
        s.validate()?;
        if c.probability.iter().any(|p| !(0.0..=1.0).contains(p))
            || c.bins
                .iter()
                .any(|b| !b.0.is_finite() || !(0.0..=1.0).contains(&b.1))
        {
            return Err(ReportError::invalid(format!(
                "{:?}: probabilities must lie in [0, 1] and bin centres be finite",
                c.name
            )));
        }
        xr = union(xr, s.bounds().0);
        for b in c.bins {
            xr = union(xr, b.0..b.0);
        }
    }
    render(path, (800, 500), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(plot.title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(padded(xr), -0.02..1.02)
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .x_desc(plot.x_label)
            .y_desc("fall probability")
            .draw()
            .map_err(plot_err)?;
        for (i, c) in plot.curves.iter().enumerate() {
            let col = series_colour(c.name, i);
            chart
                .draw_series(LineSeries::new(
                    c.impulse.iter().copied().zip(c.probability.iter().copied()),
                    col.stroke_width(2),
                ))
                .map_err(plot_err)?
                .label(c.name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(2))
                });
            chart
                .draw_series(
                    c.bins
                        .iter()
                        .map(|&(x, p)| Circle::new((x, p), 4, col.filled())),
                )
                .map_err(plot_err)?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(plot_err)
    })
}

/// Diverging colour map: -1 blue, 0 white, +1 red.
pub fn diverging_colour(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(-1.0, 1.0)
    } else {
        0.0
    };
    let (r, g, b) = if t >= 0.0 {
        (1.0, 1.0 - 0.8 * t, 1.0 - 0.85 * t)
    } else {
        (1.0 + 0.85 * t, 1.0 + 0.6 * t, 1.0)
    };
    let byte = |v: f64| (v * 255.0).round() as u8;
    RGBColor(byte(r), byte(g), byte(b))
}

impl HeatPanel<'_> {
    fn validate(&self) -> Result<(), ReportError> {
        let ascending = |v: &[f64]| v.len() >= 2 && v.windows(2).all(|w| w[0] < w[1]);
        if !ascending(self.xs) || !ascending(self.ys) {
            return Err(ReportError::invalid(format!(
                "panel {:?}: xs and ys need >= 2 strictly ascending values",
                self.title
            )));
        }
        if self.values.len() != self.xs.len() * self.ys.len() {
            return Err(ReportError::invalid(format!(
                "panel {:?}: {} values for a {} x {} grid",
                self.title,
                self.values.len(),
                self.xs.len(),
                self.ys.len()
            )));
        }
        check_finite(self.title, self.xs)?;
        check_finite(self.title, self.ys)?;
        check_finite(self.title, self.values)
    }
}

/// Tick label: integers without a decimal point, others with at most 3 decimals, never "-0".
pub(crate) fn tick(v: &f64) -> String {
    let s = format!("{:.3}", v + 0.0);
    let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
    if s == "-0" { "0".into() } else { s }
}

/// Cell edges around grid points: midpoints between neighbours, half a cell beyond the ends.
fn cell_edges(v: &[f64]) -> Vec<f64> {
    let n = v.len();
    let mut e = Vec::with_capacity(n + 1);
    e.push(v[0] - 0.5 * (v[1] - v[0]));
    for w in v.windows(2) {
        e.push(0.5 * (w[0] + w[1]));
    }
    e.push(v[n - 1] + 0.5 * (v[n - 1] - v[n - 2]));
    e
}

/// Small multiples of heat maps with crosses at data points and a shared colour bar (Fig. 8).
pub fn heat_map_grid(path: &Path, grid: &HeatMapGrid) -> Result<(), ReportError> {
    if grid.panels.is_empty() || grid.columns == 0 {
        return Err(ReportError::invalid(
            "a heat map grid needs at least one panel and one column",
        ));
    }
    for p in grid.panels {
        p.validate()?;
    }
    let scale = grid
        .panels
        .iter()
        .flat_map(|p| p.values.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let columns = grid.columns.min(grid.panels.len());
    let rows = grid.panels.len().div_ceil(columns);
    let (panel_w, panel_h, bar_w) = (330u32, 300u32, 110u32);
    let size = (panel_w * columns as u32 + bar_w, panel_h * rows as u32 + 50);
    render(path, size, |root| {
        let body = root
            .titled(grid.title, ("sans-serif", 24))
            .map_err(plot_err)?;
        let (maps, bar) = body.split_horizontally(panel_w * columns as u32);
        for (panel, area) in grid.panels.iter().zip(maps.split_evenly((rows, columns))) {
            let (xe, ye) = (cell_edges(panel.xs), cell_edges(panel.ys));
            let xr = xe[0]..xe[xe.len() - 1];
            let yr = ye[0]..ye[ye.len() - 1];
            let mut chart = ChartBuilder::on(&area)
                .caption(panel.title, ("sans-serif", 16))
                .margin(8)
                .x_label_area_size(38)
                .y_label_area_size(48)
                .build_cartesian_2d(xr.clone(), yr.clone())
                .map_err(plot_err)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_labels(5)
                .y_labels(5)
                .x_label_formatter(&tick)
                .y_label_formatter(&tick)
                .x_desc(grid.x_label)
                .y_desc(grid.y_label)
                .draw()
                .map_err(plot_err)?;
            let nx = panel.xs.len();
            chart
                .draw_series(panel.values.iter().enumerate().map(|(k, v)| {
                    let (row, col) = (k / nx, k % nx);
                    Rectangle::new(
                        [(xe[col], ye[row]), (xe[col + 1], ye[row + 1])],
                        diverging_colour(v / scale).filled(),
                    )
                }))
                .map_err(plot_err)?;
            chart
                .draw_series(
                    panel
                        .points
                        .iter()
                        .filter(|(x, y)| xr.contains(x) && yr.contains(y))
                        .map(|&p| Cross::new(p, 3, BLACK.stroke_width(1))),
                )
                .map_err(plot_err)?;
        }
        let mut chart = ChartBuilder::on(&bar)
            .margin_top(30)
            .margin_bottom(45)
            .margin_right(10)
            .y_label_area_size(55)
            .build_cartesian_2d(0.0..1.0, -scale..scale)
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_labels(7)
            .y_label_formatter(&tick)
            .y_label_style(("sans-serif", 12))
            .axis_desc_style(("sans-serif", 14))
            .y_desc(grid.value_label)
            .draw()
            .map_err(plot_err)?;
        let steps = 64;
        chart
            .draw_series((0..steps).map(|i| {
                let lo = -scale + 2.0 * scale * i as f64 / steps as f64;
                let hi = -scale + 2.0 * scale * (i + 1) as f64 / steps as f64;
                Rectangle::new(
                    [(0.0, lo), (1.0, hi)],
                    diverging_colour((lo + hi) / (2.0 * scale)).filled(),
                )
            }))
            .map_err(plot_err)?;
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_have_no_trailing_zeros_and_no_negative_zero() {
        assert_eq!(tick(&2.0), "2");
        assert_eq!(tick(&14.0), "14");
        assert_eq!(tick(&-0.0), "0");
        assert_eq!(tick(&-0.0001), "0");
        assert_eq!(tick(&0.25), "0.25");
        assert_eq!(tick(&-1.5), "-1.5");
    }

    #[test]
    fn each_controller_has_one_colour_in_every_figure() {
        for i in 0..4 {
            assert_eq!(series_colour("model", i), PALETTE[0]);
            assert_eq!(series_colour("learned", i), PALETTE[1]);
            assert_eq!(series_colour("open-loop", i), PALETTE[2]);
            assert_eq!(series_colour("reference F_R", i), RGBColor(0, 0, 0));
        }
        assert_ne!(series_colour("model", 0), series_colour("learned", 0));
        assert_eq!(series_colour("something else", 3), PALETTE[3]);
    }

    /// A minimal XML well-formedness check: one root `<svg>`, every tag closed in order,
    /// attributes quoted, no stray `<`, `&` only in entities.
    fn assert_well_formed_svg(svg: &str) {
        let body = svg.trim_start();
        let body = if body.starts_with("<?xml") {
            &body[body.find("?>").unwrap() + 2..]
        } else {
            body
        };
        let mut stack: Vec<String> = Vec::new();
        let mut rest = body.trim();
        assert!(rest.starts_with("<svg"), "no svg root");
        let mut roots = 0;
        while let Some(open) = rest.find('<') {
            let text = &rest[..open];
            assert!(!text.contains('>'), "stray '>' in text");
            for (i, _) in text.match_indices('&') {
                let ent = &text[i..text[i..].find(';').map_or(text.len(), |j| i + j + 1)];
                assert!(
                    ["&lt;", "&gt;", "&amp;", "&quot;", "&apos;"].contains(&ent)
                        || ent.starts_with("&#"),
                    "bad entity {ent}"
                );
            }
            let close = rest[open..].find('>').expect("unterminated tag") + open;
            let tag = &rest[open + 1..close];
            assert_eq!(
                tag.matches('"').count() % 2,
                0,
                "unbalanced quotes in <{tag}>"
            );
            if let Some(name) = tag.strip_prefix('/') {
                assert_eq!(
                    stack.pop().as_deref(),
                    Some(name.trim()),
                    "mismatched </{name}>"
                );
            } else if !tag.ends_with('/') && !tag.starts_with('!') {
                if stack.is_empty() {
                    roots += 1;
                }
                stack.push(tag.split_whitespace().next().unwrap().to_string());
            }
            rest = &rest[close + 1..];
        }
        assert!(stack.is_empty(), "unclosed tags {stack:?}");
        assert_eq!(roots, 1);
        assert!(rest.trim().is_empty());
    }

    /// The contents of every `<text>` element.
    fn texts(svg: &str) -> Vec<String> {
        svg.split("<text")
            .skip(1)
            .map(|t| {
                let start = t.find('>').unwrap() + 1;
                t[start..t.find("</text>").unwrap()].trim().to_string()
            })
            .collect()
    }

    fn temp_dir(name: &str) -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("steplearn-fig-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// Removes a test directory unless `KEEP_FIGS` is set (to look at the figures).
    fn cleanup(dir: &Path) {
        if std::env::var_os("KEEP_FIGS").is_none() {
            std::fs::remove_dir_all(dir).unwrap();
        }
    }

    fn check(path: &Path, labels: &[&str]) {
        let svg = std::fs::read_to_string(path).unwrap();
        assert_well_formed_svg(&svg);
        let t = texts(&svg);
        for l in labels {
            assert!(
                t.iter().any(|x| x == l),
                "no <text>{l}</text> in {path:?}: {t:?}"
            );
        }
    }

    #[test]
    fn line_plot_with_bands() {
        let dir = temp_dir("line");
        let x: Vec<f64> = (0..50).map(|i| i as f64 * 0.1).collect();
        let m: Vec<f64> = x.iter().map(|t| 0.1 * (-t).exp()).collect();
        let s: Vec<f64> = x.iter().map(|t| 0.05 * (-0.5 * t).exp()).collect();
        let l: Vec<f64> = m.iter().map(|v| v * 0.5).collect();
        let series = [
            Series {
                name: "model",
                x: &x,
                y: &m,
                spread: Some(&s),
            },
            Series {
                name: "learned",
                x: &x,
                y: &l,
                spread: Some(&s),
            },
        ];
        let path = dir.join("fig4.svg");
        line_plot(
            &path,
            &LinePlot {
                title: "Step error after a reference change",
                x_label: "time since change (s)",
                y_label: "F_E (m) <mean ± std>",
                series: &series,
            },
        )
        .unwrap();
        check(
            &path,
            &[
                "Step error after a reference change",
                "time since change (s)",
                "F_E (m) &lt;mean ± std&gt;",
                "model",
                "learned",
            ],
        );
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.matches("<polygon").count() >= 2, "two bands");
        // bad input is an error and leaves the file as it was
        let bad = [Series {
            name: "bad",
            x: &x,
            y: &m[..10],
            spread: None,
        }];
        let plot = LinePlot {
            title: "t",
            x_label: "x",
            y_label: "y",
            series: &bad,
        };
        assert!(matches!(
            line_plot(&path, &plot),
            Err(ReportError::Invalid(_))
        ));
        let nan = [f64::NAN; 50];
        let bad = [Series {
            name: "nan",
            x: &x,
            y: &nan,
            spread: None,
        }];
        let plot = LinePlot {
            series: &bad,
            ..plot
        };
        assert!(line_plot(&path, &plot).is_err());
        let plot = LinePlot {
            series: &[],
            ..plot
        };
        assert!(line_plot(&path, &plot).is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), svg);
        cleanup(&dir);
    }

    #[test]
    fn event_plot_with_second_axis() {
        let dir = temp_dir("event");
        let t: Vec<f64> = (0..300).map(|i| i as f64 * 0.1).collect();
        let th: Vec<f64> = t.iter().map(|v| 0.2 * (v * 2.0).sin()).collect();
        let metric: Vec<f64> = t.iter().map(|v| v.sqrt()).collect();
        let series = [Series {
            name: "TDA (rad)",
            x: &t,
            y: &th,
            spread: None,
        }];
        let path = dir.join("fig7.svg");
        event_plot(
            &path,
            &EventPlot {
                title: "Learning without initialisation",
                x_label: "time (s)",
                y_label: "trunk angle (rad)",
                series: &series,
                secondary: Some((
                    "learning metric",
                    Series {
                        name: "metric",
                        x: &t,
                        y: &metric,
                        spread: None,
                    },
                )),
                events: &[5.0, 12.0, 20.0],
                event_label: "push",
            },
        )
        .unwrap();
        check(
            &path,
            &[
                "Learning without initialisation",
                "trunk angle (rad)",
                "learning metric",
                "push",
                "metric",
            ],
        );
        let svg = std::fs::read_to_string(&path).unwrap();
        // three event lines + their legend mark, plus series lines
        assert!(svg.matches("<polyline").count() >= 3 + 2);
        cleanup(&dir);
    }

    #[test]
    fn fall_plot_with_bins() {
        let dir = temp_dir("fall");
        let x: Vec<f64> = (0..=40).map(|i| i as f64 * 0.5).collect();
        let curve =
            |c: f64| -> Vec<f64> { x.iter().map(|v| 1.0 / (1.0 + (-(v - c)).exp())).collect() };
        let (a, b, c) = (curve(4.0), curve(9.0), curve(12.0));
        let bins = [(1.0, 0.0), (3.0, 0.25), (5.0, 0.75)];
        let curves = [
            FallCurve {
                name: "open-loop",
                impulse: &x,
                probability: &a,
                bins: &bins,
            },
            FallCurve {
                name: "model",
                impulse: &x,
                probability: &b,
                bins: &bins,
            },
            FallCurve {
                name: "learned",
                impulse: &x,
                probability: &c,
                bins: &[],
            },
        ];
        let path = dir.join("fig6.svg");
        let plot = FallPlot {
            title: "Fall probability",
            x_label: "push impulse (Ns)",
            curves: &curves,
        };
        fall_probability_plot(&path, &plot).unwrap();
        check(
            &path,
            &[
                "Fall probability",
                "push impulse (Ns)",
                "fall probability",
                "open-loop",
                "learned",
            ],
        );
        assert_eq!(
            std::fs::read_to_string(&path)
                .unwrap()
                .matches("<circle")
                .count(),
            6
        );
        let bad_bins = [(1.0, 1.5)];
        let curves = [FallCurve {
            bins: &bad_bins,
            ..curves[0]
        }];
        assert!(
            fall_probability_plot(
                &path,
                &FallPlot {
                    curves: &curves,
                    ..plot
                }
            )
            .is_err()
        );
        cleanup(&dir);
    }

    #[test]
    fn heat_map_small_multiples() {
        let dir = temp_dir("heat");
        let xs: Vec<f64> = (0..11).map(|i| -0.5 + 0.1 * i as f64).collect();
        let ys: Vec<f64> = (0..9).map(|i| -2.0 + 0.5 * i as f64).collect();
        let maps: Vec<Vec<f64>> = (0..6)
            .map(|k| {
                ys.iter()
                    .flat_map(|y| xs.iter().map(move |x| k as f64 * 0.02 * (x + 0.1 * y)))
                    .collect()
            })
            .collect();
        let titles: Vec<String> = (1..=6).map(|k| format!("push {k}")).collect();
        let points = [(0.0, 0.0), (0.1, 0.5), (3.0, 0.0)];
        let panels: Vec<HeatPanel> = maps
            .iter()
            .zip(&titles)
            .map(|(v, t)| HeatPanel {
                title: t,
                xs: &xs,
                ys: &ys,
                values: v,
                points: &points,
            })
            .collect();
        let path = dir.join("fig8.svg");
        let grid = HeatMapGrid {
            title: "Learned step offset dF",
            x_label: "theta_E (rad)",
            y_label: "theta_E_dot (rad/s)",
            value_label: "dF (m)",
            panels: &panels,
            columns: 3,
        };
        heat_map_grid(&path, &grid).unwrap();
        check(
            &path,
            &[
                "Learned step offset dF",
                "push 1",
                "push 6",
                "theta_E (rad)",
                "dF (m)",
            ],
        );
        let svg = std::fs::read_to_string(&path).unwrap();
        // 6 panels x 99 cells + 64 colour-bar cells (+ background rects)
        assert!(svg.matches("<rect").count() >= 6 * 99 + 64);
        // two of the three points are inside each panel; a cross is two lines
        assert!(
            svg.matches("<line").count() >= 6 * 2 * 2
                || svg.matches("<polyline").count() >= 6 * 2 * 2
        );
        let bad = [HeatPanel {
            values: &maps[0][..5],
            ..panels[0]
        }];
        assert!(
            heat_map_grid(
                &path,
                &HeatMapGrid {
                    panels: &bad,
                    ..grid
                }
            )
            .is_err()
        );
        assert_eq!(diverging_colour(0.0), RGBColor(255, 255, 255));
        assert_eq!(diverging_colour(1.0).0, 255);
        assert_eq!(diverging_colour(-1.0).2, 255);
        cleanup(&dir);
    }
}

/// A polar plot of values by direction, seen from above: azimuth 0 points up (forward) and
/// azimuths grow counter-clockwise (to the left), in degrees; each series is a closed line
/// through its (azimuth, value) points, values >= 0 as radii.
#[derive(Debug, Clone, Copy)]
pub struct PolarPlot<'a> {
    /// Title above the plot.
    pub title: &'a str,
    /// The radius's label, with its unit, written beside the rings.
    pub radius_label: &'a str,
    /// The series: `x` azimuths (degrees), `y` radii (finite, >= 0); `spread` is ignored.
    pub series: &'a [Series<'a>],
}

/// Draws a [`PolarPlot`].
pub fn polar_plot(path: &Path, plot: &PolarPlot) -> Result<(), ReportError> {
    for s in plot.series {
        s.validate()?;
        if s.y.iter().any(|v| *v < 0.0) {
            return Err(ReportError::invalid(format!(
                "polar series {} has a negative radius",
                s.name
            )));
        }
    }
    let max = plot
        .series
        .iter()
        .flat_map(|s| s.y.iter().copied())
        .fold(0.0, f64::max);
    // Rings at a round step, at least one beyond the largest value.
    let step = if max > 0.0 {
        let raw = max / 4.0;
        let p = 10f64.powf(raw.log10().floor());
        [1.0, 2.0, 2.5, 5.0, 10.0]
            .iter()
            .map(|m| m * p)
            .find(|s| *s >= raw)
            .unwrap_or(10.0 * p)
    } else {
        1.0
    };
    let rings = (max / step).floor() as usize + 1;
    let r = step * rings as f64;
    let at = |azimuth_deg: f64, radius: f64| {
        let a = azimuth_deg.to_radians();
        (-radius * a.sin(), radius * a.cos())
    };
    render(path, (640, 640), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(plot.title, ("sans-serif", 22))
            .margin(30)
            .build_cartesian_2d(-1.15 * r..1.15 * r, -1.15 * r..1.15 * r)
            .map_err(plot_err)?;
        let grey = BLACK.mix(0.25);
        for k in 1..=rings {
            let radius = step * k as f64;
            let ring: Vec<(f64, f64)> = (0..=72).map(|i| at(5.0 * i as f64, radius)).collect();
            chart
                .draw_series(std::iter::once(PathElement::new(ring, grey)))
                .map_err(plot_err)?;
            let (x, y) = at(22.5, radius);
            chart
                .draw_series(std::iter::once(Text::new(
                    tick(&radius),
                    (x, y),
                    ("sans-serif", 13).into_font().color(&BLACK.mix(0.6)),
                )))
                .map_err(plot_err)?;
        }
        for (k, name) in ["forward", "left", "backward", "right"].iter().enumerate() {
            let az = 90.0 * k as f64;
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(0.0, 0.0), at(az, r)],
                    grey,
                )))
                .map_err(plot_err)?;
            let (x, y) = at(az, 1.08 * r);
            chart
                .draw_series(std::iter::once(Text::new(
                    name.to_string(),
                    (x - 0.06 * r, y),
                    ("sans-serif", 15).into_font(),
                )))
                .map_err(plot_err)?;
        }
        let (x, y) = at(0.0, -1.1 * r);
        chart
            .draw_series(std::iter::once(Text::new(
                plot.radius_label.to_string(),
                (x - 0.1 * r, y),
                ("sans-serif", 14).into_font(),
            )))
            .map_err(plot_err)?;
        for (i, s) in plot.series.iter().enumerate() {
            let c = series_colour(s.name, i);
            let mut points: Vec<(f64, f64)> =
                s.x.iter().zip(s.y).map(|(a, v)| at(*a, *v)).collect();
            if let Some(first) = points.first().copied() {
                points.push(first);
            }
            chart
                .draw_series(std::iter::once(PathElement::new(
                    points.clone(),
                    c.stroke_width(2),
                )))
                .map_err(plot_err)?
                .label(s.name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
            chart
                .draw_series(points.iter().map(|p| Circle::new(*p, 3, c.filled())))
                .map_err(plot_err)?;
        }
        draw_legend(&mut chart)
    })
}
