//! Build script (`package.build` in `Cargo.toml`): links the `stickslip`
//! binary as a position-dependent executable on Linux.
//!
//! A position-independent executable has its absolute addresses (vtables,
//! string tables, the command-line definitions) relocated by the dynamic
//! loader at every start, which touches about 60 pages of the binary: on a
//! virtual machine about 1 ms of a `stickslip run` that otherwise takes
//! 2-3 ms in all for a small scene (`examples/throughput.rs`, whole
//! processes). Linked with `-no-pie` those addresses are fixed at link time.
//! The library, the tests and the examples are unaffected; other platforms
//! keep their default.

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    if os == "linux" && env == "gnu" {
        println!("cargo:rustc-link-arg-bin=stickslip=-no-pie");
    }
    println!("cargo:rerun-if-changed=src/build.rs");
}
