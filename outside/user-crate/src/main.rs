//! The whole `steplearn` command line with this crate's names (`knn`, `softsign-cart`,
//! `forward-pushes`): `cargo run -- bench --approx knn,lwpr ...`.

fn main() -> std::process::ExitCode {
    steplearn::cli::main_with(steplearn_user_crate::registry())
}
