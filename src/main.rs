//! `stickslip`: the command-line front end. Everything happens in
//! [`stickslip::cli`]; with no arguments it runs the paper's default scene.

fn main() -> std::process::ExitCode {
    stickslip::cli::main()
}
