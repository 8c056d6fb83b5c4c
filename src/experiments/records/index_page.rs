//! `index.html`: one self-contained page per output directory of `reproduce`, `experiment`
//! and `merge`, with its tables (claims, ablation, summary), every figure of the run with a
//! one-line caption, and the command and configuration that produced it.

use crate::report::ReportError;
use crate::report::html::HtmlPage;
use std::path::{Path, PathBuf};

/// The page's file name.
pub const INDEX_FILE: &str = "index.html";

/// Inlined figures beyond this many bytes in all are linked instead, keeping the page small.
pub(crate) const INLINE_BUDGET_BYTES: usize = 1_500_000;

/// A single figure larger than this is linked, not inlined.
pub const INLINE_MAX_BYTES: usize = 300_000;

/// A one-line caption for a figure file written by this crate, citing the paper's figure and,
/// where the paper states them, its values.
pub(crate) fn caption(file_name: &str) -> &'static str {
    match file_name {
        "tracking_std_over_seeds.svg" => {
            "Experiment A (paper Fig. 4, left), claim 1: std of the step size error F_E after a reference change, mean over seeds with its 95% band (clipped at 0; model vs learned). The paper: lower with learning at all times (1000 steps, F_R drawn from [-10, 20] cm)."
        }
        "disturbance_by_step_over_seeds.svg" => {
            "Experiment B (paper Fig. 5, left), claim 2: step size of the k-th touch-down after an 8 Ns push, mean over seeds with its 95% band (model vs learned). The paper: the learned walker returns to F_R = 20 cm sooner."
        }
        "stability_fall_probability_over_seeds.svg" => {
            "Experiment C (paper Fig. 6), claim 3: fall probability per 2 Ns impulse bin combined over seeds (mean of the per-seed shares with its 95% band clipped to [0, 1]; open-loop, model, learned). The paper: the model far above open-loop, learned above the model (400 pushes, 0-20 Ns)."
        }
        "robustness_absorbed_over_seeds.svg" => {
            "Experiment D (paper Fig. 7), claim 4: pushes absorbed so far against the push number, learning from scratch vs the same walker without learning, mean over seeds with its 95% band. The paper: falls on pushes 1 and 2, absorbs from the 3rd (8 Ns)."
        }
        "tracking_std.svg" => {
            "Experiment A (paper Fig. 4, left): std of F_E per time bin after a reference change (model vs learned)."
        }
        "tracking_series.svg" => {
            "Experiment A (paper Fig. 4, right): reference step F_R and measured steps over time (model vs learned)."
        }
        "disturbance_step.svg" => {
            "Experiment B (paper Fig. 5, left): mean step size after a push, aligned on the push (model vs learned)."
        }
        "disturbance_by_step.svg" => {
            "Experiment B (paper Fig. 5, left): mean step size of the k-th touch-down after a push (model vs learned)."
        }
        "disturbance_tda.svg" => {
            "Experiment B (paper Fig. 5, right): mean trunk deviation angle θ_E after a push (model vs learned); the paper's tolerance p_θ is 0.15 rad."
        }
        "fall_probability.svg" => {
            "Experiment C (paper Fig. 6): fall probability against push impulse, 2 Ns bins and logistic fits (open-loop, model, learned)."
        }
        "learning_metric.svg" => {
            "Experiment D (paper Fig. 7): the learning metric over time, learning from scratch; the paper's settles after the 3rd push."
        }
        "df_maps.svg" => {
            "Experiment D (paper Fig. 8): the learned offset ΔF over (θ_E, θ̇_E) at each push."
        }
        _ => "A figure of this run.",
    }
}

/// The built-in suite's order of the experiments (the paper's A-D, then those beyond it) for a
/// run directory or figure file name that starts with the experiment's name; others after
/// them.
pub fn experiment_rank(name: &str) -> usize {
    let suite = crate::experiments::suite::builtin();
    suite
        .iter()
        .position(|e| name.starts_with(e.name()))
        .unwrap_or(suite.len())
}

/// Sort key of a run directory name: the experiment's rank, the name without its seed, the
/// seed as a number (so `s10` follows `s9`).
fn run_key(name: &str) -> (usize, String, u64) {
    let (stem, seed) = match name.rsplit_once("__s") {
        Some((stem, seed)) => (stem, seed.parse().unwrap_or(u64::MAX)),
        None => (name, u64::MAX),
    };
    (experiment_rank(name), stem.to_string(), seed)
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Every `.svg` in `dir` (the first value) and in its immediate subdirectories (the second,
/// by directory), each in the paper's order of the experiments, then by name and seed.
#[allow(clippy::type_complexity)]
fn figures(dir: &Path) -> Result<(Vec<PathBuf>, Vec<(String, Vec<PathBuf>)>), ReportError> {
    let read = |d: &Path| -> Result<Vec<PathBuf>, ReportError> {
        Ok(std::fs::read_dir(d)
            .map_err(|e| ReportError::io(d, e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect())
    };
    let svg = |p: &PathBuf| p.is_file() && p.extension().is_some_and(|x| x == "svg");
    let mut top: Vec<PathBuf> = Vec::new();
    let mut runs = Vec::new();
    for p in read(dir)? {
        if p.is_dir() {
            let mut v: Vec<PathBuf> = read(&p)?.into_iter().filter(svg).collect();
            v.sort();
            if !v.is_empty() {
                runs.push((file_name(&p), v));
            }
        } else if svg(&p) {
            top.push(p);
        }
    }
    top.sort_by_key(|p| (experiment_rank(&file_name(p)), file_name(p)));
    runs.sort_by_key(|(name, _)| run_key(name));
    Ok((top, runs))
}

/// A replay page beside `index.html` (written by the command line's layer, which calls
/// `crate::replay`), linked from its experiment's part of the page.
#[derive(Debug, Clone, PartialEq)]
pub struct ReplayLink {
    /// The experiment's name (`tracking`, `disturbance`, ...).
    pub experiment: String,
    /// The page, relative to the directory of `index.html`.
    pub file: String,
    /// What it shows, one line.
    pub caption: String,
}

/// Writes `dir/index.html`: `title`, the files `tables` of `dir` that exist (Markdown such as
/// `claims.md` and `ablation.md` rendered, others such as `summary.json` shown as text), the
/// figures in `dir` (across seeds), then each run directory's figures, experiments in the
/// paper's order A-D, each figure with its caption, and the `command` and `config` (TOML)
/// that produced them. Figures are inlined while they fit a budget of 1.5 MB (the top
/// level ones always), the others linked by relative path.
pub fn write_index(
    dir: &Path,
    title: &str,
    tables: &[&str],
    command: &str,
    config: Option<&str>,
) -> Result<(), ReportError> {
    write_index_with_replays(dir, title, tables, command, config, &[])
}

/// [`write_index`], with a link to each of `replays` after its experiment's figures across
/// seeds (experiments in the paper's order A-D). The replays are linked, never inlined.
pub fn write_index_with_replays(
    dir: &Path,
    title: &str,
    tables: &[&str],
    command: &str,
    config: Option<&str>,
    replays: &[ReplayLink],
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
    let (top, runs) = figures(dir)?;
    let mut inlined = 0usize;
    if !top.is_empty() || !replays.is_empty() {
        page.heading(2, "Figures across seeds");
    }
    let mut replays: Vec<&ReplayLink> = replays.iter().collect();
    replays.sort_by_key(|r| experiment_rank(&r.experiment));
    let mut next_replay = 0;
    for f in &top {
        let file = file_name(f);
        // The replays of the experiments before this figure's.
        while let Some(r) = replays
            .get(next_replay)
            .filter(|r| experiment_rank(&r.experiment) < experiment_rank(&file))
        {
            page.link(&r.file, &format!("Replay in 3D: {}", r.caption));
            next_replay += 1;
        }
        let svg = std::fs::read_to_string(f).map_err(|e| ReportError::io(f, e))?;
        inlined += svg.len();
        page.figure(&svg, &format!("{} ({file})", caption(&file)));
    }
    for r in &replays[next_replay..] {
        page.link(&r.file, &format!("Replay in 3D: {}", r.caption));
    }
    if !runs.is_empty() {
        page.heading(2, "Figures per run");
    }
    for (run, files) in &runs {
        page.heading(3, run);
        for f in files {
            let file = file_name(f);
            let text = format!("{} ({run}/{file})", caption(&file));
            let size = std::fs::metadata(f)
                .map_err(|e| ReportError::io(f, e))?
                .len() as usize;
            if size <= INLINE_MAX_BYTES && inlined + size <= INLINE_BUDGET_BYTES {
                let svg = std::fs::read_to_string(f).map_err(|e| ReportError::io(f, e))?;
                inlined += svg.len();
                page.figure(&svg, &text);
            } else {
                page.figure_link(&format!("{run}/{file}"), &text);
            }
        }
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
