//! A bench over several robots: each robot's runs in a directory of their own (a whole bench
//! directory, with its own leaderboard), and one leaderboard over them all with one column per
//! robot.
//!
//! The leaderboard over the robots is written as `leaderboard.json` (the robots, then every
//! robot's rows, each naming its robot in `"robot"`), `leaderboard.md` (per experiment, one
//! line per combination, each robot's first comparison against the model in its column) and
//! `index.html`.

use super::BenchError;
use super::leaderboard::{Comparison, Leaderboard, describe_seeds};
use crate::experiments::config_file::ConfigFile;
use crate::experiments::robot_setup::{RobotRun, use_robot};
use crate::report::html::HtmlPage;
use crate::report::{ReportError, write_file};
use crate::robot::Feet;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One robot of a bench over several: where its runs are and what it is.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotColumn {
    /// Its column and directory name: the URDF file's name without `.urdf`.
    pub id: String,
    /// The URDF file, as given.
    pub file: PathBuf,
    /// The robot's name in its file.
    pub name: String,
    /// Its mass (kg).
    pub mass_kg: f64,
    /// The SHA-256 of the file.
    pub sha256: String,
}

/// The leaderboard of a bench over several robots: each robot's leaderboard, its rows naming
/// the robot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotLeaderboard {
    /// The robots, in the order given.
    pub robots: Vec<RobotColumn>,
    /// Every robot's leaderboard rows (each with its `robot`), robot after robot, with the
    /// baseline, scale, seeds and unfinished runs (as `robot/run-id`) of them all.
    pub leaderboard: Leaderboard,
}

/// The configuration of a run on the robot at `path` (its legs ending at `feet` where named):
/// `config` (resolved: every protocol table in full) with the robot named in its settings and its
/// protocols rewritten for it; beside it, the robot as loaded.
pub(crate) fn robot_config(
    path: &Path,
    feet: Option<&Feet>,
    config: &ConfigFile,
) -> Result<(ConfigFile, RobotRun), BenchError> {
    let mut config = config.clone();
    let refused = |source| BenchError::Robot {
        path: path.to_path_buf(),
        source,
    };
    let run =
        use_robot(path, feet, &mut config.settings, &mut config.protocols).map_err(refused)?;
    Ok((config, run))
}

/// The column of the robot at `path`, as [`robot_config`] loaded it (`run`) and named it in
/// `config`'s settings.
pub(crate) fn robot_column(
    path: &Path,
    run: &RobotRun,
    config: &ConfigFile,
) -> Result<RobotColumn, BenchError> {
    let id = path
        .file_name()
        .and_then(|n| n.to_str())
        .map(|n| n.strip_suffix(".urdf").unwrap_or(n).to_string())
        .filter(|n| !n.is_empty() && !n.starts_with('.'))
        .ok_or_else(|| {
            BenchError::Selection(format!(
                "robot {}: the file name must name its directory in the bench",
                path.display()
            ))
        })?;
    let sha256 = config
        .settings
        .sim
        .robot
        .as_ref()
        .map(|file| file.sha256.clone())
        .ok_or_else(|| {
            BenchError::Selection(format!(
                "robot {}: not named in the run's settings",
                path.display()
            ))
        })?;
    Ok(RobotColumn {
        id,
        file: path.to_path_buf(),
        name: run.description.name.clone(),
        mass_kg: run.description.mass(),
        sha256,
    })
}

/// Refuses two robots of the same directory name.
pub(crate) fn check_distinct(columns: &[RobotColumn]) -> Result<(), BenchError> {
    for (i, c) in columns.iter().enumerate() {
        if let Some(other) = columns[..i].iter().find(|o| o.id == c.id) {
            return Err(BenchError::Selection(format!(
                "robots {} and {} would share the directory {:?}; rename one file",
                other.file.display(),
                c.file.display(),
                c.id
            )));
        }
    }
    Ok(())
}

impl RobotLeaderboard {
    /// Joins each robot's leaderboard (`boards`, in the order of `robots`).
    pub(crate) fn join(robots: Vec<RobotColumn>, boards: Vec<Leaderboard>) -> Self {
        let mut leaderboard = boards[0].clone();
        leaderboard.rows.clear();
        leaderboard.missing.clear();
        for (robot, board) in robots.iter().zip(boards) {
            leaderboard.rows.extend(board.rows.into_iter().map(|mut r| {
                r.robot = Some(robot.id.clone());
                r
            }));
            leaderboard
                .missing
                .extend(board.missing.iter().map(|m| format!("{}/{m}", robot.id)));
        }
        RobotLeaderboard {
            robots,
            leaderboard,
        }
    }

    /// The first comparison against the model of `robot`'s row for this combination and
    /// experiment, if it has one.
    pub fn cell(
        &self,
        robot: &str,
        experiment: &str,
        approx: &str,
        rule: &str,
        learn: crate::control::LearnSet,
    ) -> Option<&Comparison> {
        self.leaderboard
            .rows
            .iter()
            .find(|r| {
                r.robot.as_deref() == Some(robot)
                    && r.experiment == experiment
                    && r.approx == approx
                    && r.rule == rule
                    && r.learn == learn
            })
            .and_then(|r| r.vs_model.first())
    }

    /// The leaderboard in Markdown: the robots, then per experiment one line per combination
    /// with each robot's first comparison against the model in its column.
    pub fn to_markdown(&self) -> String {
        let board = &self.leaderboard;
        let mut md = format!(
            "# Leaderboard over {} robots\n\nSeeds {}, protocols at scale {} (each robot's \
             scaled to its size); baseline **{} + {}**. Each cell is the learned walker's first \
             comparison with the model, paired by seed: the mean, its 95% Student-t interval \
             and the verdict. Each robot's directory holds its whole leaderboard.\n\n",
            self.robots.len(),
            describe_seeds(&board.seeds),
            board.scale,
            board.baseline.approx,
            board.baseline.rule
        );
        md.push_str("| robot | name | mass (kg) | file | sha256 |\n|---|---|---|---|---|\n");
        for r in &self.robots {
            md.push_str(&format!(
                "| {} | {} | {:.2} | {} | {} |\n",
                r.id,
                r.name,
                r.mass_kg,
                r.file.display(),
                &r.sha256[..r.sha256.len().min(12)]
            ));
        }
        md.push('\n');
        for name in board.experiments() {
            md.push_str(&format!("## {name}\n\n"));
            let quantity = board
                .rows
                .iter()
                .filter(|r| r.experiment == name)
                .find_map(|r| r.vs_model.first().map(|c| c.quantity.clone()))
                .unwrap_or_else(|| "-".into());
            md.push_str(&format!(
                "First comparison against the model: {quantity}.\n\n"
            ));
            md.push_str("| approx | rule | learn |");
            for r in &self.robots {
                md.push_str(&format!(" {} |", r.id));
            }
            md.push_str("\n|");
            md.push_str(&"---|".repeat(self.robots.len() + 3));
            md.push('\n');
            let first = self.robots.first().map(|r| r.id.as_str());
            for row in board
                .rows
                .iter()
                .filter(|r| r.experiment == name && r.robot.as_deref() == first)
            {
                md.push_str(&format!(
                    "| {} | {} | {} |",
                    row.approx, row.rule, row.learn
                ));
                for robot in &self.robots {
                    let cell = self.cell(&robot.id, name, &row.approx, &row.rule, row.learn);
                    md.push_str(&format!(" {} |", cell.map_or("-".into(), Comparison::cell)));
                }
                md.push('\n');
            }
            md.push('\n');
        }
        if !board.missing.is_empty() {
            md.push_str(&format!(
                "{} runs of the selection have not finished (not in the table).\n",
                board.missing.len()
            ));
        }
        md
    }

    /// Writes `leaderboard.json`, `leaderboard.md` and `index.html` (with the `command` that
    /// produced it) into `dir`.
    pub fn write(&self, dir: &Path, command: &str) -> Result<(), BenchError> {
        let json =
            serde_json::to_string_pretty(self).map_err(|e| ReportError::invalid(e.to_string()))?;
        write_file(&dir.join("leaderboard.json"), json.as_bytes())?;
        let md = self.to_markdown();
        write_file(&dir.join("leaderboard.md"), md.as_bytes())?;
        let mut page = HtmlPage::new("steplearn bench: the leaderboard over robots");
        page.markdown(&md);
        for r in &self.robots {
            page.link(
                &format!("{}/index.html", r.id),
                &format!("{}: its whole leaderboard", r.id),
            );
        }
        page.heading(2, "How this page was made");
        page.code(command);
        page.write(&dir.join("index.html"))?;
        Ok(())
    }
}
