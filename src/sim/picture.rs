//! The run picture: an SVG of a recorded simulated run that a person can read at a glance.
//!
//! Four rows: a side-view (x-z) film strip of stick figures at regular time intervals, a
//! front-view (y-z) film strip, and the sagittal (x) and lateral (y) paths of the centre of
//! mass and both feet against time. Pushes are red arrows, falls red crosses, and optional
//! per-step controller annotations (ZMP `Z`, footstep `F`, step time `T`) are drawn on the
//! path plots. Left leg blue, right leg orange, CoM green. Plain SVG, text as `<text>`.

use std::fmt::Write as _;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{GroundTruth, Skeleton};

/// One recorded instant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RunFrame {
    /// Time (s).
    pub time: f64,
    /// Centre of mass (m).
    pub com: [f64; 3],
    /// Sole centres, left then right (m).
    pub soles: [[f64; 3]; 2],
    /// Stick-figure points.
    pub skeleton: Skeleton,
}

/// A push delivered during the run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PushMark {
    /// Time (s).
    pub time: f64,
    /// Impulse (N s, world frame).
    pub impulse: [f64; 3],
}

/// Controller annotation of one step (all optional), drawn at `time` on the path plots.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct StepAnnotation {
    /// Time of the annotation (s), e.g. the step's start.
    pub time: f64,
    /// ZMP `Z` (world x, y; m).
    pub zmp: Option<[f64; 2]>,
    /// Footstep `F` (world x, y; m).
    pub footstep: Option<[f64; 2]>,
    /// Step time `T` (s).
    pub step_time: Option<f64>,
}

/// A recorded run: frames, pushes, falls, annotations.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct RunRecord {
    /// Title drawn on top.
    pub title: String,
    /// Frames in time order.
    pub frames: Vec<RunFrame>,
    /// Pushes.
    pub pushes: Vec<PushMark>,
    /// Times of falls (s).
    pub falls: Vec<f64>,
    /// Per-step controller annotations.
    pub annotations: Vec<StepAnnotation>,
}

impl RunRecord {
    /// An empty record with a title.
    pub fn new(title: &str) -> Self {
        RunRecord {
            title: title.to_string(),
            ..RunRecord::default()
        }
    }

    /// Records the ground truth of one instant.
    pub fn record(&mut self, truth: &GroundTruth) {
        self.frames.push(RunFrame {
            time: truth.time,
            com: truth.com,
            soles: truth.soles.map(|s| s.position),
            skeleton: truth.skeleton,
        });
    }

    /// Records a push.
    pub fn push(&mut self, time: f64, impulse: [f64; 3]) {
        self.pushes.push(PushMark { time, impulse });
    }

    /// Records a fall.
    pub fn fall(&mut self, time: f64) {
        self.falls.push(time);
    }

    /// Adds a step annotation.
    pub fn annotate(&mut self, a: StepAnnotation) {
        self.annotations.push(a);
    }

    /// The picture as SVG text. `interval` is the time between stick figures (s); it is
    /// widened so that at most 48 figures are drawn per strip.
    pub fn to_svg(&self, interval: f64) -> String {
        Picture::new(self, interval).draw()
    }

    /// Writes the picture to `path`, creating its directory.
    pub fn write_svg(&self, path: &Path, interval: f64) -> std::io::Result<()> {
        if let Some(dir) = path.parent()
            && !dir.as_os_str().is_empty()
        {
            std::fs::create_dir_all(dir)?;
        }
        crate::atomic_file::write_atomic(path, self.to_svg(interval).as_bytes())
    }
}

const CELL: f64 = 64.0;
const STRIP_H: f64 = 190.0;
const PLOT_H: f64 = 150.0;
const MARGIN: f64 = 60.0;
const LEFT: &str = "#1f77b4";
const RIGHT: &str = "#ff7f0e";
const COM: &str = "#2ca02c";
const ALERT: &str = "#d62728";

struct Picture<'a> {
    rec: &'a RunRecord,
    picks: Vec<usize>,
    width: f64,
    t0: f64,
    t1: f64,
    out: String,
}

impl<'a> Picture<'a> {
    fn new(rec: &'a RunRecord, interval: f64) -> Self {
        let (t0, t1) = match (rec.frames.first(), rec.frames.last()) {
            (Some(a), Some(b)) => (a.time, b.time.max(a.time + 1e-6)),
            _ => (0.0, 1.0),
        };
        let interval = interval.max((t1 - t0) / 47.0).max(1e-6);
        let mut picks = Vec::new();
        let mut next = t0;
        for (i, f) in rec.frames.iter().enumerate() {
            if f.time >= next - 1e-9 {
                picks.push(i);
                next += interval;
            }
        }
        if let Some(last) = rec.frames.len().checked_sub(1)
            && picks.last() != Some(&last)
        {
            picks.push(last);
        }
        let width = (2.0 * MARGIN + picks.len() as f64 * CELL).max(900.0);
        Picture {
            rec,
            picks,
            width,
            t0,
            t1,
            out: String::new(),
        }
    }

    fn line(&mut self, a: (f64, f64), b: (f64, f64), color: &str, w: f64) {
        let _ = writeln!(
            self.out,
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{color}" stroke-width="{w}" stroke-linecap="round"/>"#,
            a.0, a.1, b.0, b.1
        );
    }

    fn text(&mut self, x: f64, y: f64, size: f64, color: &str, s: &str) {
        let _ = writeln!(
            self.out,
            r#"<text x="{x:.1}" y="{y:.1}" font-family="sans-serif" font-size="{size}" fill="{color}">{s}</text>"#
        );
    }

    fn arrow(&mut self, a: (f64, f64), b: (f64, f64)) {
        self.line(a, b, ALERT, 2.5);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let n = (dx * dx + dy * dy).sqrt().max(1e-9);
        let (ux, uy) = (dx / n, dy / n);
        for s in [1.0, -1.0] {
            let p = (b.0 - 7.0 * ux + s * 4.0 * uy, b.1 - 7.0 * uy - s * 4.0 * ux);
            self.line(b, p, ALERT, 2.5);
        }
    }

    fn cross(&mut self, x: f64, y: f64, r: f64) {
        self.line((x - r, y - r), (x + r, y + r), ALERT, 3.0);
        self.line((x - r, y + r), (x + r, y - r), ALERT, 3.0);
    }

    /// Film strip of stick figures; `axis` 0 = side view (x), 1 = front view (y).
    fn strip(&mut self, top: f64, axis: usize) {
        let name = if axis == 0 {
            "side view (x forward to the right, z up)"
        } else {
            "front view (y left to the left, z up; seen from the front)"
        };
        self.text(MARGIN, top + 14.0, 13.0, "black", name);
        let ground = top + STRIP_H - 22.0;
        let scale = (STRIP_H - 50.0) / 2.2; // px per metre
        // Front view seen from the front: +y (left) is drawn to the viewer's right... we draw
        // from the robot's front, so the robot's left appears on the viewer's right.
        let sign = if axis == 0 { 1.0 } else { -1.0 };
        self.line(
            (MARGIN - 10.0, ground),
            (MARGIN + self.picks.len() as f64 * CELL, ground),
            "#888",
            1.0,
        );
        let picks = self.picks.clone();
        for (k, &i) in picks.iter().enumerate() {
            let f = self.rec.frames[i];
            let cx = MARGIN + (k as f64 + 0.5) * CELL;
            let origin = f.com[axis];
            let p = |q: [f64; 3]| {
                (
                    cx + sign * (q[axis] - origin) * scale,
                    ground - q[2] * scale,
                )
            };
            let s = f.skeleton;
            for (leg, color) in [(0, LEFT), (1, RIGHT)] {
                let pts = s.legs[leg];
                self.line(p(pts[0]), p(pts[1]), color, 2.0);
                self.line(p(pts[1]), p(pts[2]), color, 2.0);
                self.line(p(pts[2]), p(pts[3]), color, 2.0);
                self.line(p(pts[3]), p(pts[4]), color, 2.0);
                self.line(p(pts[2]), p(pts[4]), color, 1.0);
                self.line(p(pts[0]), p(s.pelvis), "black", 2.0);
            }
            self.line(p(s.pelvis), p(s.neck), "black", 3.0);
            let h = p(s.head);
            let _ = writeln!(
                self.out,
                r#"<circle cx="{:.1}" cy="{:.1}" r="{:.1}" fill="none" stroke="black" stroke-width="1.5"/>"#,
                h.0,
                h.1,
                s.head_radius * scale
            );
            let c = p(f.com);
            let _ = writeln!(
                self.out,
                r#"<circle cx="{:.1}" cy="{:.1}" r="3" fill="{COM}"/>"#,
                c.0, c.1
            );
            self.text(
                cx - 14.0,
                ground + 12.0,
                9.0,
                "#444",
                &format!("{:.1}s", f.time),
            );
            self.text(
                cx - 14.0,
                ground + 21.0,
                8.0,
                "#888",
                &format!("{:+.2}", origin),
            );
            let next_t = picks
                .get(k + 1)
                .map(|&j| self.rec.frames[j].time)
                .unwrap_or(f64::INFINITY);
            let pushes: Vec<_> = self
                .rec
                .pushes
                .iter()
                .filter(|m| m.time >= f.time && m.time < next_t && m.impulse[axis].abs() > 1e-9)
                .copied()
                .collect();
            for m in pushes {
                let len = 6.0 * (m.impulse[axis].abs()).sqrt().min(6.0);
                let dir = sign * m.impulse[axis].signum();
                let y = ground - f.com[2] * scale - 20.0;
                self.arrow(
                    (cx - dir * len - dir * 8.0, y),
                    (cx - dir * 8.0 + dir * 0.1, y),
                );
                self.text(
                    cx - 20.0,
                    y - 6.0,
                    9.0,
                    ALERT,
                    &format!("{:.1}Ns", m.impulse[axis]),
                );
            }
            let fallen = self.rec.falls.iter().any(|&t| t >= f.time && t < next_t);
            if fallen {
                self.cross(cx, ground - 1.0 * scale, 10.0);
                self.text(cx - 10.0, ground - 1.0 * scale - 14.0, 10.0, ALERT, "fall");
            }
        }
    }

    /// Path plot of coordinate `axis` (0 = x, 1 = y) of CoM and feet against time.
    fn paths(&mut self, top: f64, axis: usize) {
        let label = if axis == 0 {
            "sagittal path x (m): CoM green, left foot blue, right foot orange"
        } else {
            "lateral path y (m): CoM green, left foot blue, right foot orange"
        };
        self.text(MARGIN, top + 14.0, 13.0, "black", label);
        let frames = &self.rec.frames;
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for f in frames {
            for v in [f.com[axis], f.soles[0][axis], f.soles[1][axis]] {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        for a in &self.rec.annotations {
            for v in [a.zmp, a.footstep].into_iter().flatten() {
                lo = lo.min(v[axis]);
                hi = hi.max(v[axis]);
            }
        }
        if !lo.is_finite() {
            return;
        }
        let pad = ((hi - lo) * 0.1).max(0.05);
        let (lo, hi) = (lo - pad, hi + pad);
        let (x0, x1) = (MARGIN, self.width - MARGIN);
        let (y0, y1) = (top + 24.0, top + PLOT_H - 16.0);
        let (t0, t1) = (self.t0, self.t1);
        let px = move |t: f64| x0 + (t - t0) / (t1 - t0) * (x1 - x0);
        let py = move |v: f64| y1 - (v - lo) / (hi - lo) * (y1 - y0);
        let _ = writeln!(
            self.out,
            r##"<rect x="{x0:.1}" y="{y0:.1}" width="{:.1}" height="{:.1}" fill="none" stroke="#bbb"/>"##,
            x1 - x0,
            y1 - y0
        );
        for v in [lo, (lo + hi) / 2.0, hi] {
            self.text(x0 - 48.0, py(v) + 4.0, 10.0, "#444", &format!("{v:+.2}"));
        }
        let steps = 8;
        for k in 0..=steps {
            let t = t0 + (t1 - t0) * k as f64 / steps as f64;
            self.text(px(t) - 10.0, y1 + 13.0, 10.0, "#444", &format!("{t:.1}s"));
        }
        let stride = (frames.len() / 1500).max(1);
        // Which point of a frame each series follows: sole 0, sole 1, CoM.
        for (color, which) in [(LEFT, 0), (RIGHT, 1), (COM, 2)] {
            let get = |f: &RunFrame| {
                if which == 2 {
                    f.com[axis]
                } else {
                    f.soles[which][axis]
                }
            };
            let mut d = String::new();
            for (k, f) in frames.iter().step_by(stride).enumerate() {
                let _ = write!(
                    d,
                    "{}{:.1},{:.1} ",
                    if k == 0 { "M" } else { "L" },
                    px(f.time),
                    py(get(f))
                );
            }
            let _ = writeln!(
                self.out,
                r#"<path d="{d}" fill="none" stroke="{color}" stroke-width="1.5"/>"#
            );
        }
        let pushes = self.rec.pushes.clone();
        for m in pushes {
            let x = px(m.time);
            self.line((x, y0), (x, y1), ALERT, 1.0);
            self.text(
                x + 2.0,
                y0 + 10.0,
                9.0,
                ALERT,
                &format!("{:.1}Ns", m.impulse[axis]),
            );
        }
        let falls = self.rec.falls.clone();
        for t in falls {
            self.cross(px(t), (y0 + y1) / 2.0, 8.0);
        }
        let notes = self.rec.annotations.clone();
        for a in notes {
            let x = px(a.time);
            if let Some(z) = a.zmp {
                self.text(x - 3.0, py(z[axis]) + 4.0, 9.0, "#9467bd", "Z");
            }
            if let Some(f) = a.footstep {
                self.text(x - 3.0, py(f[axis]) + 4.0, 9.0, "#8c564b", "F");
            }
            if let Some(t) = a.step_time {
                self.text(x - 8.0, y1 - 3.0, 8.0, "#666", &format!("T{t:.2}"));
            }
        }
    }

    fn draw(mut self) -> String {
        let height = 40.0 + 2.0 * STRIP_H + 2.0 * PLOT_H + 20.0;
        let _ = writeln!(
            self.out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{:.0}" height="{height:.0}" viewBox="0 0 {:.0} {height:.0}">"#,
            self.width, self.width
        );
        let _ = writeln!(
            self.out,
            r#"<rect width="100%" height="100%" fill="white"/>"#
        );
        let title = format!(
            "{} ({:.1} s to {:.1} s, {} pushes, {} falls)",
            self.rec.title,
            self.t0,
            self.t1,
            self.rec.pushes.len(),
            self.rec.falls.len()
        );
        self.text(MARGIN, 24.0, 16.0, "black", &title);
        self.strip(40.0, 0);
        self.strip(40.0 + STRIP_H, 1);
        self.paths(40.0 + 2.0 * STRIP_H, 0);
        self.paths(40.0 + 2.0 * STRIP_H + PLOT_H, 1);
        self.out.push_str("</svg>\n");
        self.out
    }
}
