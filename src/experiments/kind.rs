//! The paper's four experiments by name.

crate::names::named_choices! {
    /// One of the paper's experiments (section V), named as on the command line, in run ids and
    /// in `summary.json`, in the paper's order.
    pub enum ExperimentKind {
        /// A: reference tracking.
        Tracking => "tracking",
        /// B: disturbance rejection.
        Disturbance => "disturbance",
        /// C: stability (fall probability vs impulse).
        Stability => "stability",
        /// D: robustness (learning without initialisation).
        Robustness => "robustness",
    }
}
