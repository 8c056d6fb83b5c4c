//! A forest plot: estimates with their intervals, one row per label, in panels stacked
//! vertically, each with a line at its no-difference value.

use super::ReportError;
use super::figures::{plot_err, render};
use plotters::prelude::*;

/// One row of a panel: an estimate and its interval (NaN where unknown: drawn as a gap).
#[derive(Debug, Clone)]
pub struct ForestRow {
    /// Label on the left.
    pub label: String,
    /// The estimate.
    pub mean: f64,
    /// Lower end of its interval.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

/// One panel: a quantity over several rows.
#[derive(Debug, Clone)]
pub struct ForestPanel {
    /// Title above the panel.
    pub title: String,
    /// The x axis label (the quantity and its unit).
    pub x_label: String,
    /// The no-difference value (a vertical line).
    pub null: f64,
    /// The rows, top to bottom.
    pub rows: Vec<ForestRow>,
}

/// Writes the panels as one SVG figure (at least one panel, each with at least one row).
pub fn forest_plot(path: &std::path::Path, panels: &[ForestPanel]) -> Result<(), ReportError> {
    if panels.is_empty() || panels.iter().any(|p| p.rows.is_empty()) {
        return Err(ReportError::invalid(
            "a forest plot needs panels with at least one row each",
        ));
    }
    let heights: Vec<u32> = panels
        .iter()
        .map(|p| 90 + 26 * p.rows.len() as u32)
        .collect();
    let total: u32 = heights.iter().sum();
    render(path, (900, total), |root| {
        let mut rest = root.clone();
        for (panel, h) in panels.iter().zip(&heights) {
            let (area, below) = rest.split_vertically(*h);
            rest = below;
            let n = panel.rows.len() as i32;
            let mut xs: Vec<f64> = vec![panel.null];
            for r in &panel.rows {
                xs.extend([r.mean, r.lo, r.hi].into_iter().filter(|v| v.is_finite()));
            }
            let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let pad = if hi > lo { 0.08 * (hi - lo) } else { 1.0 };
            let labels: Vec<String> = panel.rows.iter().map(|r| r.label.clone()).collect();
            let mut chart = ChartBuilder::on(&area)
                .caption(&panel.title, ("sans-serif", 17))
                .margin(8)
                .x_label_area_size(38)
                .y_label_area_size(260)
                .build_cartesian_2d((lo - pad)..(hi + pad), (0..n).into_segmented())
                .map_err(plot_err)?;
            chart
                .configure_mesh()
                .disable_y_mesh()
                .x_desc(panel.x_label.as_str())
                .y_label_formatter(&|v| match v {
                    SegmentValue::CenterOf(i) => labels
                        .get((n - 1 - *i).max(0) as usize)
                        .cloned()
                        .unwrap_or_default(),
                    _ => String::new(),
                })
                .y_labels(n as usize)
                .draw()
                .map_err(plot_err)?;
            let grey = RGBColor(120, 120, 120);
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![
                        (panel.null, SegmentValue::Exact(0)),
                        (panel.null, SegmentValue::Exact(n)),
                    ],
                    grey.stroke_width(1),
                )))
                .map_err(plot_err)?;
            let blue = RGBColor(31, 119, 180);
            for (k, r) in panel.rows.iter().enumerate() {
                let y = SegmentValue::CenterOf(n - 1 - k as i32);
                if r.lo.is_finite() && r.hi.is_finite() {
                    chart
                        .draw_series(std::iter::once(PathElement::new(
                            vec![(r.lo, y.clone()), (r.hi, y.clone())],
                            blue.stroke_width(2),
                        )))
                        .map_err(plot_err)?;
                }
                if r.mean.is_finite() {
                    chart
                        .draw_series(std::iter::once(Circle::new((r.mean, y), 4, blue.filled())))
                        .map_err(plot_err)?;
                }
            }
        }
        Ok(())
    })
}
