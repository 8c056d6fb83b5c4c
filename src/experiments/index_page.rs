//! `index.html`: one self-contained page per output directory of `reproduce`, `experiment`
//! and `merge`, with its tables (claims, ablation, summary), every figure of the run with a
//! one-line caption, and the command and configuration that produced it.

use crate::report::ReportError;
use crate::report::html::HtmlPage;
use std::path::{Path, PathBuf};

/// The page's file name.
pub const INDEX_FILE: &str = "index.html";

/// A one-line caption for a figure file written by this crate.
pub fn caption(file_name: &str) -> &'static str {
    match file_name {
        "tracking_std_over_seeds.svg" => {
            "Claim 1: std of the step size error F_E after a reference change, mean over seeds (model vs learned)."
        }
        "tracking_std.svg" => {
            "Experiment A: std of F_E per time bin after a reference change (model vs learned)."
        }
        "tracking_series.svg" => {
            "Experiment A: reference step F_R and measured steps over time (model vs learned)."
        }
        "disturbance_step.svg" => {
            "Experiment B: mean step size after a push, aligned on the push (model vs learned)."
        }
        "disturbance_by_step.svg" => {
            "Experiment B: mean step size of the k-th touch-down after a push (model vs learned)."
        }
        "disturbance_tda.svg" => {
            "Experiment B: mean trunk deviation angle after a push (model vs learned)."
        }
        "fall_probability.svg" => {
            "Experiment C: fall probability against push impulse, 2 Ns bins and logistic fits (open-loop, model, learned)."
        }
        "learning_metric.svg" => {
            "Experiment D: the learning metric over time, learning from scratch."
        }
        "df_maps.svg" => "Experiment D: the learned offset dF over (theta_E, theta_E_dot).",
        _ => "A figure of this run.",
    }
}

/// Every `.svg` in `dir` and its immediate subdirectories, top level first, then by path.
fn figures(dir: &Path) -> Result<Vec<PathBuf>, ReportError> {
    let mut top = Vec::new();
    let mut nested = Vec::new();
    let read = |d: &Path| -> Result<Vec<PathBuf>, ReportError> {
        let mut v: Vec<PathBuf> = std::fs::read_dir(d)
            .map_err(|e| ReportError::io(d, e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect();
        v.sort();
        Ok(v)
    };
    for p in read(dir)? {
        if p.is_dir() {
            nested.extend(
                read(&p)?
                    .into_iter()
                    .filter(|q| q.extension().is_some_and(|x| x == "svg")),
            );
        } else if p.extension().is_some_and(|x| x == "svg") {
            top.push(p);
        }
    }
    top.extend(nested);
    Ok(top)
}

/// Writes `dir/index.html`: `title`, the files `tables` of `dir` that exist (Markdown such as
/// `claims.md` and `ablation.md` rendered, others such as `summary.json` shown as text), every figure under `dir` with its caption, grouped by run
/// directory, and the `command` and `config` (TOML) that produced them.
pub fn write_index(
    dir: &Path,
    title: &str,
    tables: &[&str],
    command: &str,
    config: Option<&str>,
) -> Result<(), ReportError> {
    let mut page = HtmlPage::new(title);
    for name in tables {
        let path = dir.join(name);
        if path.is_file() {
            let text = std::fs::read_to_string(&path).map_err(|e| ReportError::io(&path, e))?;
            if name.ends_with(".md") {
                page.markdown(&text);
            } else {
                page.heading(2, name);
                page.code(&text);
            }
        }
    }
    let figures = figures(dir)?;
    if !figures.is_empty() {
        page.heading(2, "Figures");
    }
    let mut group: Option<PathBuf> = None;
    for f in &figures {
        let parent = f.parent().map(Path::to_path_buf);
        if parent.as_deref() != Some(dir) && parent != group {
            let name = parent
                .as_deref()
                .and_then(Path::file_name)
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            page.heading(3, &name);
            group = parent.clone();
        }
        let svg = std::fs::read_to_string(f).map_err(|e| ReportError::io(f, e))?;
        let file = f
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        page.figure(&svg, &format!("{} ({file})", caption(&file)));
    }
    page.heading(2, "How this page was made");
    page.code(command);
    if let Some(config) = config {
        page.paragraph("The configuration (`steplearn config` format):");
        page.code(config);
    }
    page.write(&dir.join(INDEX_FILE))
}

/// The command line of this process, quoted for a shell where needed.
pub fn command_line() -> String {
    std::env::args()
        .map(|a| {
            if !a.is_empty()
                && a.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_./=,:+".contains(c))
            {
                a
            } else {
                format!("'{}'", a.replace('\'', "'\\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}
