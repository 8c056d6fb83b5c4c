//! Every key of a config file with its range and meaning, and the reference table built from
//! them and the defaults (`steplearn config --table`, docs/configuration.md).
//!
//! The defaults are not written here: the table reads them from
//! [`ConfigFile::default_toml`], so a changed default changes the table. A test checks that
//! [`PRINTED`] names exactly the keys `steplearn config` prints, and that no key of
//! [`ABSENT`], the keys a config may add that hold no value by default, is among them.

use super::config_file::ConfigFile;

/// One key of a config file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KeyDoc {
    /// The dotted path from the top of the file; `[]` marks each table of an array of tables.
    pub key: &'static str,
    /// The values a check accepts.
    pub range: &'static str,
    /// What the key sets.
    pub meaning: &'static str,
}

const fn k(key: &'static str, range: &'static str, meaning: &'static str) -> KeyDoc {
    KeyDoc {
        key,
        range,
        meaning,
    }
}

/// The keys `steplearn config` prints, in its order.
pub const PRINTED: &[KeyDoc] = &[
    k(
        "settings.scale",
        "(0, 1]",
        "length of every protocol as a share of the paper's (`--quick`: 0.1)",
    ),
    k(
        "settings.push_window_s",
        "> 0 s",
        "a push is absorbed if no fall follows within this time",
    ),
    k(
        "settings.recovery_s",
        ">= 0 s",
        "standing time after a fall's reset before walking resumes",
    ),
    k(
        "settings.resettle_s",
        ">= 0 s",
        "walking time after a reset before a delayed push is delivered",
    ),
    k("settings.sim.dt", "[0.0001, 0.005] s", "physics time step"),
    k(
        "settings.sim.steps_per_tick",
        "1 - 100",
        "physics steps per control tick",
    ),
    k(
        "settings.sim.solver_iterations",
        "1 - 10",
        "rapier's solver iterations per step",
    ),
    k(
        "settings.sim.pgs_iterations",
        "1 - 10",
        "rapier's PGS iterations per solver iteration",
    ),
    k(
        "settings.sim.friction",
        "[0, 10]",
        "ground and sole friction coefficient",
    ),
    k("settings.sim.gravity", ">= 0 m/s^2", "gravity"),
    k(
        "settings.sim.push_steps",
        "1 - 1000",
        "physics steps over which a push's impulse is spread",
    ),
    k(
        "settings.sim.fall_tilt",
        "> 0 rad",
        "trunk tilt at which the robot counts as fallen",
    ),
    k(
        "settings.sim.initial_joints",
        "12 angles in [-3.2, 3.2] rad",
        "joint angles of the initial pose",
    ),
    k(
        "settings.sim.initial_clearance",
        "[0, 10] m",
        "height of the soles above the ground at the start",
    ),
    k(
        "settings.sim.body.hip_half_width",
        "> 0 m",
        "half the distance between the hip joints",
    ),
    k(
        "settings.sim.body.gimbal_mass",
        "(0, a quarter of the lighter of thigh and foot] kg",
        "mass of each massless-joint gimbal link",
    ),
    k(
        "settings.sim.body.torso.mass",
        "> 0 kg",
        "trunk mass (with head and arms)",
    ),
    k("settings.sim.body.torso.length", "> 0 m", "trunk length"),
    k(
        "settings.sim.body.torso.com_height",
        ">= 0 m",
        "trunk centre of mass above the hips",
    ),
    k(
        "settings.sim.body.torso.inertia",
        "3 values > 0 kg m^2",
        "trunk principal inertia",
    ),
    k(
        "settings.sim.body.torso.depth",
        "> 0 m",
        "trunk collision box depth",
    ),
    k(
        "settings.sim.body.torso.width",
        "> 0 m",
        "trunk collision box width",
    ),
    k(
        "settings.sim.body.torso.head_radius",
        "> 0 m",
        "head sphere radius (drawing)",
    ),
    k(
        "settings.sim.body.torso.arm_length",
        "> 0 m",
        "arm length (drawing)",
    ),
    k(
        "settings.sim.body.torso.arm_radius",
        "> 0 m",
        "arm radius (drawing)",
    ),
    k("settings.sim.body.thigh.length", "> 0 m", "thigh length"),
    k("settings.sim.body.thigh.mass", "> 0 kg", "thigh mass"),
    k(
        "settings.sim.body.thigh.com_fraction",
        "[0, 1]",
        "thigh centre of mass as a share of its length from the hip",
    ),
    k(
        "settings.sim.body.thigh.gyration_fraction",
        "> 0",
        "thigh radius of gyration as a share of its length",
    ),
    k(
        "settings.sim.body.thigh.radius",
        "> 0 m",
        "thigh capsule radius",
    ),
    k("settings.sim.body.shank.length", "> 0 m", "shank length"),
    k("settings.sim.body.shank.mass", "> 0 kg", "shank mass"),
    k(
        "settings.sim.body.shank.com_fraction",
        "[0, 1]",
        "shank centre of mass as a share of its length from the knee",
    ),
    k(
        "settings.sim.body.shank.gyration_fraction",
        "> 0",
        "shank radius of gyration as a share of its length",
    ),
    k(
        "settings.sim.body.shank.radius",
        "> 0 m",
        "shank capsule radius",
    ),
    k("settings.sim.body.foot.mass", "> 0 kg", "foot mass"),
    k("settings.sim.body.foot.length", "> 0 m", "sole length"),
    k("settings.sim.body.foot.width", "> 0 m", "sole width"),
    k(
        "settings.sim.body.foot.ankle_height",
        "> 0 m",
        "ankle joint above the sole",
    ),
    k(
        "settings.sim.body.foot.sole_offset_x",
        "within +-half the sole length, m",
        "sole centre ahead of the ankle",
    ),
    k(
        "settings.sim.body.joints[].limits",
        "lo <= hi, rad",
        "range of one joint (six tables: hip yaw, roll, pitch, knee, ankle pitch, roll)",
    ),
    k(
        "settings.sim.body.joints[].stiffness",
        "> 0 Nm/rad",
        "position servo stiffness of one joint",
    ),
    k(
        "settings.sim.body.joints[].damping",
        ">= 0 Nms/rad",
        "position servo damping of one joint",
    ),
    k(
        "settings.sim.body.joints[].max_torque",
        "> 0 Nm",
        "torque limit of one joint",
    ),
    k(
        "settings.walker.mode",
        "`capture-step`, `open-loop`, `learner-only`",
        "the walker (each experiment sets its own)",
    ),
    k(
        "settings.walker.offset_in_gait",
        "bool",
        "the learned dF also drives the support leg's sweep (the authors' gait)",
    ),
    k(
        "settings.walker.learner_during_fade_in",
        "bool",
        "the learner acts while the gait fades in after a start or reset",
    ),
    k(
        "settings.walker.offset_target",
        "`footstep`, `reference`",
        "what a learned dF is added to",
    ),
    k(
        "settings.walker.start_ramp_s",
        ">= 0 s",
        "time over which the reference step ramps up after a start",
    ),
    k(
        "settings.walker.capture_step.c",
        "> 0 1/s",
        "the LIPM constant C = sqrt(g/h)",
    ),
    k(
        "settings.walker.capture_step.nominal_step_time",
        "> 0 s",
        "step time of the nominal gait",
    ),
    k(
        "settings.walker.capture_step.delta",
        "> 0 m",
        "half the nominal lateral foot distance",
    ),
    k(
        "settings.walker.capture_step.omega",
        ">= delta, m",
        "largest half lateral foot distance",
    ),
    k(
        "settings.walker.capture_step.zmp_x",
        "lo <= 0 <= hi, m",
        "sagittal ZMP range within the sole",
    ),
    k(
        "settings.walker.capture_step.zmp_y",
        "> 0 m",
        "lateral ZMP bound within the sole",
    ),
    k(
        "settings.walker.capture_step.max_com_x",
        "> 0 m",
        "largest sagittal CoM offset the controller plans",
    ),
    k(
        "settings.walker.capture_step.max_step_time",
        "> 0 s",
        "longest step time",
    ),
    k(
        "settings.walker.capture_step.min_step_duration",
        "[0, nominal_step_time] s",
        "shortest step",
    ),
    k(
        "settings.walker.capture_step.zmp_hold_time",
        ">= 0 s",
        "time the ZMP is held at the start of a step",
    ),
    k(
        "settings.walker.capture_step.max_reference_step",
        "> 0 m",
        "largest reference step F_R",
    ),
    k(
        "settings.walker.capture_step.max_step_x",
        "> 0 m",
        "largest commanded sagittal step (the legs' reach)",
    ),
    k(
        "settings.walker.capture_step.analytic_footstep",
        "bool",
        "use the analytic footstep F (false: the learner alone decides)",
    ),
    k(
        "settings.walker.estimator.com_offset",
        "3 finite values, m",
        "CoM in the trunk frame",
    ),
    k(
        "settings.walker.estimator.switch_fraction",
        "(0.5, 1]",
        "share of the load on a foot that makes it the support",
    ),
    k(
        "settings.walker.estimator.min_total_force",
        ">= 0 N",
        "least total sole force for a support decision",
    ),
    k(
        "settings.walker.estimator.min_support_time",
        ">= 0 s",
        "least time on a support before it may change",
    ),
    k(
        "settings.walker.estimator.velocity_time_constant",
        ">= 0 s",
        "low-pass filter of the CoM velocity",
    ),
    k(
        "settings.walker.motion.step_x_range",
        "lo <= 0 <= hi, lo < hi, hi - lo <= 2 m",
        "commanded sagittal steps are clamped to it (the paper's [-0.15, 0.45])",
    ),
    k(
        "settings.walker.motion.step_y_range",
        "0 < lo < hi <= 1 m",
        "lateral foot distance range",
    ),
    k(
        "settings.walker.motion.max_turn",
        "[0, 1.5] rad",
        "largest turn per step",
    ),
    k(
        "settings.walker.motion.period",
        "[0.05, 10] s",
        "step period of the open-loop walker",
    ),
    k(
        "settings.walker.motion.fade_in",
        "[0, 60] s",
        "time over which the step primitives fade in after a start",
    ),
    k(
        "settings.walker.motion.swing_step_scale",
        "(0, 2]",
        "share of the commanded step the legs realise (`configs/mismatch.toml`: 0.85)",
    ),
    k(
        "settings.walker.motion.swing",
        "`paper`, `tracking`",
        "the swing: the paper's open-loop swing, or one that tracks the footstep from the trunk's tilt (`configs/improved.toml`)",
    ),
    k(
        "settings.walker.motion.tilt_gain",
        "[0, 2]",
        "tracking swing: share of the tilt beyond the band it compensates",
    ),
    k(
        "settings.walker.motion.tilt_gain_band",
        "[0, 1] rad",
        "tracking swing: tilt compensated once, before the gain",
    ),
    k(
        "settings.walker.motion.tilt_settle_s",
        "> 0 s",
        "tracking swing: time constant of the settled tilt",
    ),
    k(
        "settings.walker.motion.tilt_dead_band",
        ">= 0 rad",
        "tracking swing: tilt left uncompensated",
    ),
    k(
        "settings.walker.motion.early_landing_phase",
        "[0, 1]",
        "a swing foot landing past this phase ends the step (1: every step on time, the paper's; `configs/improved.toml`: 0.5)",
    ),
    k(
        "settings.walker.motion.tilt_lift",
        "[0, 1] leg lengths/rad",
        "tracking swing: extra lift of the swing foot per radian of tilt",
    ),
    k(
        "settings.learner.eta",
        "> 0",
        "learning rate eta of eq. (6)",
    ),
    k(
        "settings.learner.max_samples_per_step",
        "2 - 100,000",
        "inputs kept per step",
    ),
    k(
        "settings.learner.max_gain",
        "> 0, or absent",
        "gain guard: largest dF per unit of G one touch-down applies (absent: eq. 6 unguarded)",
    ),
    k(
        "settings.learner.anti_windup",
        "bool",
        "targets stop where an offset can no longer change the step",
    ),
    k(
        "settings.learner.learn_from_falls",
        "bool",
        "the step under way at a fall teaches",
    ),
    k(
        "settings.learner.fall_theta_limit",
        "> 0 rad",
        "clamp on theta_E at a fall",
    ),
    k(
        "settings.learner.dead_zone",
        ">= 0",
        "G shrunk towards 0 by this before eq. (6) (`configs/improved.toml`: 0.06)",
    ),
    k(
        "settings.learner.leakage",
        "[0, 1)",
        "targets pulled back towards dF = 0 by this share",
    ),
    k(
        "settings.learner.trust_region",
        "> 0, or absent",
        "the offset acts within this many standard deviations of the trained inputs",
    ),
    k(
        "settings.learner.trust_fallback",
        "`zero`, `nominal`",
        "what the offset fades to outside the trust region",
    ),
    k(
        "settings.learner.train_share",
        "(0, 1]",
        "latest share of a step's inputs trained at touch-down",
    ),
    k(
        "settings.learner.prior.samples",
        "0 - 1,000,000",
        "points of dF = 0 trained in before learning",
    ),
    k(
        "settings.learner.prior.lo.theta_e",
        "< hi, rad",
        "prior box, lower theta_E",
    ),
    k(
        "settings.learner.prior.lo.theta_e_dot",
        "< hi, rad/s",
        "prior box, lower theta_E rate",
    ),
    k(
        "settings.learner.prior.lo.f_r",
        "< hi, m",
        "prior box, lower F_R",
    ),
    k(
        "settings.learner.prior.hi.theta_e",
        "> lo, rad",
        "prior box, upper theta_E",
    ),
    k(
        "settings.learner.prior.hi.theta_e_dot",
        "> lo, rad/s",
        "prior box, upper theta_E rate",
    ),
    k(
        "settings.learner.prior.hi.f_r",
        "> lo, m",
        "prior box, upper F_R",
    ),
    k(
        "protocols.disturbance.bin_s",
        ">= 0.01 s",
        "B: width of the time bins after a push",
    ),
    k(
        "protocols.disturbance.direction",
        "unit vector",
        "B: push direction",
    ),
    k(
        "protocols.disturbance.f_r",
        "[-1, 1] m",
        "B: reference step",
    ),
    k(
        "protocols.disturbance.gap_s",
        "0 < lo <= hi <= 600 s, lo > horizon",
        "B: time between pushes",
    ),
    k(
        "protocols.disturbance.horizon_s",
        "> 0 s",
        "B: statistics cover this long after a push",
    ),
    k(
        "protocols.disturbance.impulse",
        "[0, 1000] Ns",
        "B: push impulse",
    ),
    k(
        "protocols.disturbance.pushes",
        "1 - 10,000",
        "B: pushes per walker",
    ),
    k(
        "protocols.disturbance.tolerance_m",
        "(0, 1] m",
        "B: band around F_R within which the step counts as back",
    ),
    k(
        "protocols.disturbance.touch_down_share",
        "(0, 1]",
        "B: share of the pushes that must reach a touch-down for it to count in the return",
    ),
    k(
        "protocols.omnidirectional.gap_s",
        "0 < lo <= hi <= 600 s",
        "omnidirectional: time between pushes",
    ),
    k(
        "protocols.omnidirectional.impulse",
        "0 <= lo <= hi <= 1000 Ns",
        "omnidirectional: impulse range",
    ),
    k(
        "protocols.omnidirectional.pushes",
        "1 - 10,000",
        "omnidirectional: pushes per sector and walker",
    ),
    k(
        "protocols.omnidirectional.walk_hold_s",
        "0 < lo <= hi <= 600 s",
        "omnidirectional: time each reference of the walk is held",
    ),
    k(
        "protocols.omnidirectional.walk_radius",
        "[0, 1] m",
        "omnidirectional: radius of the disc of references",
    ),
    k(
        "protocols.omnidirectional.walk_s",
        "1 s - 1 day",
        "omnidirectional: time of the walk per walker",
    ),
    k(
        "protocols.robustness.direction",
        "unit vector",
        "D: push direction",
    ),
    k(
        "protocols.robustness.impulse",
        "[0, 1000] Ns",
        "D: push impulse (calibrated so that the walker without learning falls)",
    ),
    k(
        "protocols.robustness.learner_prior",
        "bool",
        "D's learner starts from its dF = 0 prior",
    ),
    k(
        "protocols.robustness.pushes",
        "1 - 10,000",
        "D: episodes, one push each",
    ),
    k(
        "protocols.robustness.settle_s",
        "0 < lo <= hi <= 600 s",
        "D: stepping time before each push",
    ),
    k(
        "protocols.stability.direction",
        "unit vector",
        "C: push direction",
    ),
    k(
        "protocols.stability.gap_s",
        "0 < lo <= hi <= 600 s",
        "C: time between pushes",
    ),
    k(
        "protocols.stability.impulse",
        "0 <= lo <= hi <= 1000 Ns",
        "C: impulse range",
    ),
    k(
        "protocols.stability.pushes",
        "1 - 10,000",
        "C: pushes per walker",
    ),
    k(
        "protocols.tracking.bin_s",
        ">= 0.01 s",
        "A: width of the time bins after a reference change",
    ),
    k(
        "protocols.tracking.duration_s",
        "0.01 s - 1 day",
        "A: trial length",
    ),
    k(
        "protocols.tracking.hold_s",
        "0 < lo <= hi <= 600 s, lo >= horizon",
        "A: time each reference is held",
    ),
    k(
        "protocols.tracking.horizon_s",
        "> 0 s",
        "A: statistics cover this long after a change",
    ),
    k(
        "protocols.tracking.reference",
        "lo <= hi within [-1, 1] m",
        "A: range of the random reference steps",
    ),
];

/// The keys that hold no value by default (`steplearn config` leaves them out).
pub const ABSENT: &[KeyDoc] = &[
    k(
        "settings.sim.robot",
        "`{ path, sha256, feet }` of a URDF that loads (`feet = { left, right }` link names optional), or absent",
        "a robot from a URDF file instead of the built-in humanoid (`--robot PATH` and `--feet LEFT,RIGHT` set it)",
    ),
    k(
        "settings.learner.max_offset",
        "> 0, or absent",
        "clamp on the queried offset",
    ),
    k(
        "settings.learner.offset_range",
        "lo <= 0 <= hi, lo < hi, or absent",
        "the offsets the learner may apply",
    ),
    k(
        "settings.learner.max_step_error",
        "> 0 m, or absent",
        "a touch-down the model missed by more than this teaches nothing",
    ),
    k(
        "settings.learner.learn",
        "non-empty set of `step-x`, `step-y`, `step-time`, `ankle-pitch`, `ankle-roll`",
        "the learned step parameters (absent: `[\"step-x\"]`, the paper's)",
    ),
    k(
        "settings.learner.<parameter>.eta",
        "> 0",
        "the parameter's own eta (tables `step-x`, `step-y`, `step-time`, `ankle-pitch`, `ankle-roll`)",
    ),
    k(
        "settings.learner.<parameter>.dead_zone",
        ">= 0",
        "the parameter's own dead zone",
    ),
    k(
        "settings.learner.<parameter>.leakage",
        "[0, 1)",
        "the parameter's own leakage",
    ),
    k(
        "settings.learner.<parameter>.max_offset",
        "> 0",
        "the parameter's own clamp",
    ),
    k(
        "settings.learner.<parameter>.offset_range",
        "lo <= 0 <= hi, lo < hi",
        "the parameter's own range (`configs/heel_pitch.toml`)",
    ),
    k(
        "settings.learner.<parameter>.gate",
        "`off`, `rate-share`, `with-the-fall`",
        "what the offset is weighted by each tick",
    ),
    k(
        "settings.learner.step-time.plane",
        "`sagittal`, `frontal`, `both`",
        "the plane the step time is learned from",
    ),
    k(
        "settings.learner.step-time.frontal.dead_zone",
        ">= 0",
        "with `plane = \"both\"`, the frontal part's dead zone",
    ),
    k(
        "settings.lwpr.<field>",
        "as `LwprConfig` checks it",
        "the built-in LWPR's settings: `init_d`, `init_alpha`, `w_gen`, `w_prune`, `meta`, `meta_rate`, `penalty`, `diag_only`, `update_d`, `init_lambda`, `final_lambda`, `tau_lambda`, `init_s2`, `add_threshold`, `kernel`, `norm_out`, `cutoff`, `max_rfs`",
    ),
    k(
        "protocols.omnidirectional.both_planes",
        "`uncoupled`, `coupled`",
        "how the walker `both` learns the two planes",
    ),
];

/// `toml`, a config as [`ConfigFile::default_toml_for`] writes it, with each [`ABSENT`] key
/// listed as a comment under its table: what `steplearn config` prints.
pub fn with_absent_keys(toml: &str) -> String {
    let mut out = String::new();
    for line in toml.lines() {
        out.push_str(line);
        out.push('\n');
        for doc in ABSENT.iter().filter(|d| !d.key.contains('<')) {
            let Some((table, name)) = doc.key.rsplit_once('.') else {
                continue;
            };
            if line == format!("[{table}]") {
                out.push_str(&format!(
                    "# {name}: optional, unset by default ({}): {}\n",
                    doc.range, doc.meaning
                ));
            }
        }
    }
    out
}

/// Every key a TOML document holds, as [`KeyDoc::key`] writes them.
pub fn keys_of(value: &toml::Value) -> Vec<(String, toml::Value)> {
    fn walk(v: &toml::Value, path: &str, out: &mut Vec<(String, toml::Value)>) {
        let join = |k: &str| {
            if path.is_empty() {
                k.to_string()
            } else {
                format!("{path}.{k}")
            }
        };
        match v {
            toml::Value::Table(t) => {
                for (k, child) in t {
                    walk(child, &join(k), out);
                }
            }
            toml::Value::Array(a) if a.first().is_some_and(toml::Value::is_table) => {
                // An array of tables: one row per key, the first table's value.
                walk(&a[0], &format!("{path}[]"), out);
            }
            other => out.push((path.to_string(), other.clone())),
        }
    }
    let mut out = Vec::new();
    walk(value, "", &mut out);
    out
}

/// A default as the table shows it.
fn shown(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => format!("`{s}`"),
        toml::Value::Array(a) => format!(
            "[{}]",
            a.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        other => other.to_string(),
    }
}

/// The reference table (Markdown) of every key: its default, range and meaning.
pub fn key_table() -> String {
    let defaults = toml::from_str::<toml::Value>(&ConfigFile::default_toml()).map(|v| keys_of(&v));
    let defaults = defaults.unwrap_or_default();
    let mut out = String::from("| key | default | range | meaning |\n|---|---|---|---|\n");
    for doc in PRINTED.iter().chain(ABSENT) {
        let default = defaults
            .iter()
            .find(|(key, _)| key == doc.key)
            .map_or_else(|| "absent".to_string(), |(_, v)| shown(v));
        out.push_str(&format!(
            "| `{}` | {} | {} | {} |\n",
            doc.key, default, doc.range, doc.meaning
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_absent_key_of_a_printed_table_is_listed_once_under_it() {
        let printed = with_absent_keys(&ConfigFile::default_toml());
        // Still the defaults when parsed: the added lines are comments.
        assert_eq!(
            ConfigFile::parse_toml(&printed).unwrap(),
            ConfigFile::parse_toml(&ConfigFile::default_toml()).unwrap()
        );
        let lines: Vec<&str> = printed.lines().collect();
        for doc in ABSENT.iter().filter(|d| !d.key.contains('<')) {
            let (table, name) = doc.key.rsplit_once('.').unwrap();
            let header = format!("[{table}]");
            if !lines.contains(&header.as_str()) {
                continue;
            }
            let comment = format!("# {name}: optional");
            let at: Vec<usize> = (0..lines.len())
                .filter(|&i| lines[i].starts_with(&comment))
                .collect();
            assert_eq!(at.len(), 1, "{}", doc.key);
            let above = lines[..at[0]].iter().rev().find(|l| l.starts_with('['));
            assert_eq!(above, Some(&header.as_str()), "{}", doc.key);
            assert!(lines[at[0]].contains(doc.meaning), "{}", doc.key);
        }
    }

    /// The table names exactly the keys the default config holds, and after them only keys
    /// absent from it.
    #[test]
    fn the_table_names_every_printed_key_and_no_other() {
        let value: toml::Value = toml::from_str(&ConfigFile::default_toml()).unwrap();
        let mut printed: Vec<String> = keys_of(&value).into_iter().map(|(k, _)| k).collect();
        let mut documented: Vec<String> = PRINTED.iter().map(|k| k.key.to_string()).collect();
        printed.sort();
        documented.sort();
        assert_eq!(documented, printed);
        for doc in ABSENT {
            assert!(!printed.iter().any(|p| p == doc.key), "{}", doc.key);
        }
        let table = key_table();
        assert_eq!(table.lines().count(), PRINTED.len() + ABSENT.len() + 2);
        assert!(
            table.contains("| `settings.walker.motion.swing` | `paper` |"),
            "{table}"
        );
    }
}
