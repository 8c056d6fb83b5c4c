//! A mean over seeds with its two-sided 95% Student-t band, for the across-seed figures.

use super::ReportError;
use super::figures::{LinePlot, Series, line_plot_ticks};
use crate::stats::MeanStd;
use std::ops::Range;
use std::path::Path;

/// Means over seeds and the half-widths of their 95% intervals, point by point.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Band {
    /// The points that have at least one value.
    pub x: Vec<f64>,
    /// The mean of the values at each point.
    pub mean: Vec<f64>,
    /// Half-width of the two-sided 95% Student-t interval of the mean (0 with one value).
    pub half: Vec<f64>,
    /// The most values at any point (the seeds behind the figure).
    pub seeds: usize,
}

/// The band of `values[k]` (one value per seed, non-finite ones left out) at `x[k]`.
pub fn band(x: &[f64], values: &[Vec<f64>]) -> Band {
    let mut b = Band::default();
    for (&x, v) in x.iter().zip(values) {
        let s = MeanStd::of(v.iter().copied().filter(|v| v.is_finite()));
        let n = s.count();
        if n == 0 {
            continue;
        }
        let half = s.ci95_half_width().unwrap_or(0.0);
        b.x.push(x);
        b.mean.push(s.mean());
        b.half.push(half);
        b.seeds = b.seeds.max(n);
    }
    b
}

/// Labels of a band plot: title (the number of seeds is appended), x and y axis.
#[derive(Debug, Clone)]
pub struct Labels<'a> {
    /// The title.
    pub title: &'a str,
    /// The x axis.
    pub x: &'a str,
    /// The y axis.
    pub y: &'a str,
    /// Whether x counts something (labels at integer ticks only).
    pub integer_x: bool,
    /// The values the quantity can take; bands are clipped to them.
    pub y_range: Range<f64>,
}

/// A line plot of named bands (mean lines, 95% bands shaded). Bands without points are left
/// out; false if none has any.
pub fn band_plot(path: &Path, labels: Labels, bands: &[(&str, Band)]) -> Result<bool, ReportError> {
    let bands: Vec<&(&str, Band)> = bands.iter().filter(|b| !b.1.x.is_empty()).collect();
    let Some(seeds) = bands.iter().map(|b| b.1.seeds).max() else {
        return Ok(false);
    };
    let series: Vec<Series> = bands
        .iter()
        .map(|(name, b)| Series {
            name,
            x: &b.x,
            y: &b.mean,
            spread: Some(&b.half),
        })
        .collect();
    let title = format!("{} ({seeds} seeds, 95% band)", labels.title);
    line_plot_ticks(
        path,
        &LinePlot {
            title: &title,
            x_label: labels.x,
            y_label: labels.y,
            series: &series,
        },
        labels.integer_x,
        labels.y_range.clone(),
    )?;
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn student_t_half_width_and_empty_points() {
        let b = band(
            &[0.0, 1.0, 2.0],
            &[vec![1.0, 2.0, 3.0, 2.0], vec![], vec![5.0]],
        );
        assert_eq!(b.x, vec![0.0, 2.0]);
        assert_eq!(b.mean, vec![2.0, 5.0]);
        let half = 3.182446 * (2.0f64 / 3.0).sqrt() / 2.0;
        assert!((b.half[0] - half).abs() < 1e-5);
        assert_eq!(b.half[1], 0.0);
        assert_eq!(b.seeds, 4);
    }
}
