//! The `steplearn` command: the whole command line over the built-in registry.

fn main() -> std::process::ExitCode {
    steplearn::cli::main_with(steplearn::bench::Registry::builtin())
}
