//! A user's own approximator, rule and experiment, registered beside steplearn's built-ins.

pub mod forward_pushes;
pub mod knn;
pub mod softsign;

use steplearn::approx::InputBox;
use steplearn::bench::Registry;

/// The built-ins plus this crate's `knn`, `softsign-cart` and `forward-pushes`.
pub fn registry() -> Registry {
    Registry::builtin()
        .approximator("knn", |bounds: &InputBox| knn::Knn::new(bounds))
        .rule("softsign-cart", softsign::SoftsignCart::default)
        .experiment(forward_pushes::ForwardPushes)
}
