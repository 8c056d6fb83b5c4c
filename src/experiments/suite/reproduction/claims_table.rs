//! The claims table of the README: each of the paper's claims as the main job judged it with
//! the paper's system and with the improved setup, one row per claim. A test keeps the
//! README's table equal to the one built from the stored main jobs.

use super::reproduce::Claims;
use crate::experiments::claim::Claim;
use crate::experiments::paired::{Paired, Verdict};

/// How one claim's headline figure is written.
#[derive(Debug, Clone, Copy)]
struct Row {
    number: u8,
    claim: &'static str,
    figure: &'static str,
    /// Writes a value of the headline (mean or interval end).
    value: fn(f64) -> String,
    /// Written after the interval.
    unit: &'static str,
}

const ROWS: [Row; 4] = [
    Row {
        number: 1,
        claim: "lower step-error std after a reference change",
        figure: "4",
        value: signed2,
        unit: " cm",
    },
    Row {
        number: 2,
        claim: "back at the reference step sooner after a push",
        figure: "5",
        value: signed2,
        unit: " s",
    },
    Row {
        number: 3,
        claim: "push recovery I50, learned / model",
        figure: "6",
        value: plain3,
        unit: "",
    },
    Row {
        number: 4,
        claim: "learns push recovery without initialisation (absorbed, over no learning)",
        figure: "7-8",
        value: signed1,
        unit: " of 15 pushes",
    },
];

fn signed2(v: f64) -> String {
    format!("{v:+.2}")
}

fn plain3(v: f64) -> String {
    format!("{v:.3}")
}

fn signed1(v: f64) -> String {
    format!("{v:+.1}")
}

/// A claim's headline as a cell: mean, 95% interval, verdict.
fn headline(row: &Row, claim: &Claim) -> String {
    let Some(p): Option<&Paired> = claim.over_seeds.first() else {
        return "no figure".into();
    };
    let verdict = match p.verdict {
        Some(Verdict::Better) => "**better**",
        Some(Verdict::Level) => "level",
        Some(Verdict::Worse) => "worse",
        None => "too few seeds",
    };
    let v = row.value;
    format!(
        "{} [{}, {}]{}, {verdict}",
        v(p.mean),
        v(p.ci95.0),
        v(p.ci95.1),
        row.unit
    )
}

/// How many seeds a claim holds on, strictly.
fn per_seed(claim: &Claim) -> String {
    let holds = claim.seeds.iter().filter(|s| s.1).count();
    format!("{holds} of {}", claim.seeds.len())
}

/// Claim `number` (1-4) of `claims`.
fn claim_of(claims: &Claims, number: u8) -> &Claim {
    match number {
        1 => &claims.tracking,
        2 => &claims.disturbance,
        3 => &claims.stability,
        _ => &claims.robustness,
    }
}

/// The README's claims table (Markdown): the paper's system (the default) and the improved
/// setup, each with its headline over seeds and the seeds on which the claim holds strictly.
pub fn claims_table(paper: &Claims, improved: &Claims) -> String {
    let mut out = String::from(
        "| # | The paper's claim | Fig. | Paper's system (default) | holds on seeds | Improved setup | holds on seeds |\n|---|---|---|---|---|---|---|\n",
    );
    for row in &ROWS {
        let (a, b) = (claim_of(paper, row.number), claim_of(improved, row.number));
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} |\n",
            row.number,
            row.claim,
            row.figure,
            headline(row, a),
            per_seed(a),
            headline(row, b),
            per_seed(b),
        ));
    }
    out
}

/// The README's robot table (Markdown): one row per robot with each claim's headline over
/// seeds (learned against the model, paired by seed), the model's I50 over the open-loop
/// walker's, and the robot's real-time factor (`speed`, as measured by `benches/robots.rs`).
pub fn robots_table(robots: &[(&str, &Claims, &str)]) -> String {
    let mut out = String::from(
        "| robot | seeds | claim 1 (cm) | claim 2 (s) | claim 3 | claim 4 (pushes) | model / open-loop I50 | real time |\n|---|---|---|---|---|---|---|---|\n",
    );
    for (name, claims, speed) in robots {
        let cells: Vec<String> = ROWS
            .iter()
            .map(|row| {
                let cell = headline(&Row { unit: "", ..*row }, claim_of(claims, row.number));
                cell.replace("**", "")
            })
            .collect();
        let open_loop = claims
            .stability
            .over_seeds
            .get(1)
            .map_or("no figure".to_string(), |p| {
                format!("{:.2} [{:.2}, {:.2}]", p.mean, p.ci95.0, p.ci95.1)
            });
        out.push_str(&format!(
            "| {name} | {} | {} | {} | {} | {} | {open_loop} | {speed} |\n",
            claims.stability.seeds.len(),
            cells[0],
            cells[1],
            cells[2],
            cells[3],
        ));
    }
    out
}
