//! Every integration test in one binary (one link of rapier instead of one per file), one
//! module per area: `cargo test --test all <module>::` runs one area.

mod approx_batch;
mod bench;
mod capture_step_closed_loop;
mod capture_step_with_estimator;
mod cli;
mod config;
mod conformance_grid;
mod conformance_kernel_ridge;
mod conformance_lwpr;
mod conformance_rbf;
mod conformance_smoke;
mod estimator_scripted;
mod exact_kernel_ridge;
mod experiment_stability;
mod experiments_short;
mod fall_causes;
mod grid_properties;
mod index_page;
mod kernel_ridge_properties;
mod kinematics_round_trip;
mod learner;
mod learner_checkpoint;
mod learner_humanoid;
mod lipm_identities;
mod lwpr_accuracy;
mod lwpr_golden;
mod lwpr_properties;
mod model_files;
mod motion_generator;
mod rbf_properties;
mod sim_body;
mod sim_dynamics;
mod sim_picture;
mod sweep;
mod walker_humanoid;
