//! `[settings.lwpr]`: every setting of the built-in LWPR from a config file, checked like every
//! other value. Set, a key takes effect in the LWPR the settings build (`max_rfs` caps the
//! receptive fields); out of range, it is refused with an error naming it; absent, the
//! settings are exactly the built-in ones and a written config leaves the table out.

use steplearn::approx::{AnyApproximator, ApproxKind, FunctionApproximator, Kernel, Lwpr, Persist};
use steplearn::control::InputGrid;
use steplearn::experiments::config_file::ConfigFile;
use steplearn::experiments::settings::{LwprSettings, Settings};

fn lwpr_of(config: &str) -> Lwpr {
    let file = ConfigFile::parse_toml(config).unwrap();
    let bounds = InputGrid::default().input_box().unwrap();
    match file.settings.lwpr.build(&bounds).unwrap() {
        AnyApproximator::Lwpr(l) => l,
        other => panic!("{:?}", other.kind()),
    }
}

/// Trains `l` on inputs spread over the learner's input box, far more places than `max_rfs`
/// fields could cover.
fn train(l: &mut Lwpr) {
    let b = InputGrid::default().input_box().unwrap();
    for i in 0..2000 {
        let u = |k: u32| (i as f64 * [0.618_034, 0.414_214, 0.732_051][k as usize]) % 1.0;
        let x: Vec<f64> = (0..3)
            .map(|k| b.lo[k] + u(k as u32) * (b.hi[k] - b.lo[k]))
            .collect();
        l.update(&x, &[(3.0 * x[0]).sin() + 0.1 * x[1] - x[2]])
            .unwrap();
    }
}

#[test]
fn max_rfs_from_a_config_file_caps_the_receptive_fields() {
    let mut capped = lwpr_of("[settings.lwpr]\nmax_rfs = 4\n");
    assert_eq!(capped.config().max_rfs, Some(4));
    train(&mut capped);
    assert!(
        capped.num_receptive_fields() <= 4,
        "{} fields",
        capped.num_receptive_fields()
    );
    // The same training without the cap grows more fields: the cap is what held it.
    let mut free = lwpr_of("");
    train(&mut free);
    assert!(
        free.num_receptive_fields() > 4,
        "{} fields",
        free.num_receptive_fields()
    );
}

#[test]
fn every_key_reaches_the_lwpr_it_builds() {
    let l = lwpr_of(
        "[settings.lwpr]\ninit_d = 7.0\ninit_alpha = 20.0\nw_gen = 0.2\nw_prune = 0.9\n\
         meta = true\nmeta_rate = 100.0\npenalty = 1e-5\ndiag_only = true\nupdate_d = false\n\
         init_lambda = 0.99\nfinal_lambda = 0.9999\ntau_lambda = 0.999\ninit_s2 = 1e-9\n\
         add_threshold = 0.4\nkernel = \"BiSquare\"\nnorm_out = 2.0\ncutoff = 0.01\n\
         max_rfs = 50\n",
    );
    let c = l.config();
    assert_eq!(c.init_d, [7.0, 0.0, 0.0, 0.0, 7.0, 0.0, 0.0, 0.0, 7.0]);
    assert_eq!(
        (
            c.init_alpha,
            c.w_gen,
            c.w_prune,
            c.meta,
            c.meta_rate,
            c.penalty
        ),
        (20.0, 0.2, 0.9, true, 100.0, 1e-5)
    );
    assert_eq!(
        (
            c.diag_only,
            c.update_d,
            c.init_lambda,
            c.final_lambda,
            c.tau_lambda
        ),
        (true, false, 0.99, 0.9999, 0.999)
    );
    assert_eq!(
        (c.init_s2, c.add_threshold, c.kernel, c.cutoff, c.max_rfs),
        (1e-9, 0.4, Kernel::BiSquare, 0.01, Some(50))
    );
    assert_eq!(c.norm_out, [2.0]);
    // What the file cannot set follows from the learner's input box.
    let bounds = InputGrid::default().input_box().unwrap();
    let builtin = ApproxKind::lwpr_config(&bounds);
    assert_eq!((c.n_in, c.n_out), (3, 1));
    assert_eq!(c.norm_in, builtin.norm_in);
}

#[test]
fn out_of_range_values_are_refused_naming_the_key() {
    for (table, key, says) in [
        ("max_rfs = 0", "settings.lwpr.max_rfs", "at least 1"),
        ("max_rfs = -3", "settings.lwpr.max_rfs", "-3"),
        ("max_rfs = 2.5", "settings.lwpr.max_rfs", "2.5"),
        ("max_rfs = \"ten\"", "settings.lwpr.max_rfs", "ten"),
        ("w_gen = 1.5", "settings.lwpr.w_gen", "1.5"),
        ("w_prune = 0.05", "settings.lwpr.w_prune", "0.05"),
        ("init_d = -1.0", "settings.lwpr.init_d", "positive"),
        ("init_alpha = nan", "settings.lwpr.init_alpha", "NaN"),
        ("cutoff = 1.0", "settings.lwpr.cutoff", "[0, 1)"),
        ("kernel = \"box\"", "settings.lwpr.kernel", "box"),
        // Fields that follow from the input box are not keys; init_d is one number.
        ("n_in = 3", "settings.lwpr.n_in", "unknown field `n_in`"),
        (
            "norm_in = [1.0, 1.0, 1.0]",
            "settings.lwpr.norm_in",
            "unknown field",
        ),
        (
            "init_d = \"wide\"",
            "settings.lwpr.init_d",
            "must be a number",
        ),
        (
            "norm_out = [2.0]",
            "settings.lwpr.norm_out",
            "must be a number",
        ),
        (
            "max_rf = 3",
            "settings.lwpr.max_rf",
            "unknown field `max_rf`",
        ),
    ] {
        let err = ConfigFile::parse_toml(&format!("[settings.lwpr]\n{table}\n")).unwrap_err();
        assert_eq!(err.field, key, "{table}: {err}");
        assert!(err.reason.contains(says), "{table}: {err}");
    }
    // The same through a file, as the command line loads it: the message names the key.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, "[settings.lwpr]\nmax_rfs = 0\n").unwrap();
    let err = ConfigFile::load(&path).unwrap_err().to_string();
    assert!(err.contains("settings.lwpr.max_rfs"), "{err}");
}

#[test]
fn without_the_table_the_settings_are_the_builtin_ones_and_stay_unwritten() {
    let bounds = InputGrid::default().input_box().unwrap();
    let settings = Settings::default();
    assert!(settings.lwpr.is_default());
    assert_eq!(settings.lwpr, LwprSettings::default());
    assert_eq!(
        settings.lwpr.config(&bounds).unwrap(),
        ApproxKind::lwpr_config(&bounds)
    );
    // Bit for bit the approximator the built-in `lwpr` factory builds.
    assert_eq!(
        settings.lwpr.build(&bounds).unwrap().to_json().unwrap(),
        ApproxKind::Lwpr.build(&bounds).unwrap().to_json().unwrap()
    );
    // A written config (what a run records as its identity) has no lwpr table by default,
    // and one when a key is set.
    let toml = ConfigFile::default().to_toml().unwrap();
    assert!(!toml.contains("lwpr"), "{toml}");
    let set = ConfigFile::parse_toml("[settings.lwpr]\nmax_rfs = 4\n").unwrap();
    let written = set.to_toml().unwrap();
    assert!(
        written.contains("[settings.lwpr]\nmax_rfs = 4\n"),
        "{written}"
    );
    assert_eq!(ConfigFile::parse_toml(&written).unwrap(), set);
    // An empty table is the defaults.
    assert_eq!(
        ConfigFile::parse_toml("[settings.lwpr]\n").unwrap(),
        ConfigFile::default()
    );
}

/// The value of the first key `key` anywhere in `v`.
fn find_key<'a>(v: &'a serde_json::Value, key: &str) -> Option<&'a serde_json::Value> {
    match v {
        serde_json::Value::Object(m) => m
            .get(key)
            .or_else(|| m.values().find_map(|c| find_key(c, key))),
        serde_json::Value::Array(a) => a.iter().find_map(|c| find_key(c, key)),
        _ => None,
    }
}

#[test]
fn a_run_s_learners_take_the_table() {
    use steplearn::bench::Registry;
    use steplearn::control::LearnerConfig;
    let registry = Registry::builtin();
    let cap_of = |lwpr: &LwprSettings| {
        let build = registry
            .learner_builder("lwpr", "pendulum-cart", lwpr)
            .unwrap();
        let learner = build(LearnerConfig::default()).unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&learner.approximator().to_json().unwrap()).unwrap();
        find_key(&json, "max_rfs").cloned()
    };
    let file = ConfigFile::parse_toml("[settings.lwpr]\nmax_rfs = 4\n").unwrap();
    assert_eq!(cap_of(&file.settings.lwpr), Some(serde_json::json!(4)));
    // Without the table the run's LWPR is the built-in one: no cap.
    assert!(matches!(
        cap_of(&LwprSettings::default()),
        None | Some(serde_json::Value::Null)
    ));
}
