//! Build script: the shared library exports exactly the 34 fmi2 functions.
//!
//! rustc's own version script for a cdylib lists every `#[no_mangle]` symbol of every linked
//! crate as global (e.g. `callback_log` of the `fmi-sys` header bindings), and a second version
//! script cannot narrow that list (the linker unites the global lists). Dependencies reach the
//! linker as archives (rlibs) while the fmi2* shims of `export_fmi2!` are in this crate's own
//! objects, so `--exclude-libs,ALL` keeps every dependency symbol out of the dynamic symbol
//! table. `tests/fmi_host.rs` (`exports_exactly_the_34_fmi2_functions`) reads the built
//! library's table and fails if anything else is exported (e.g. with LTO, which merges the
//! archives into one object).

fn main() {
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux") {
        println!("cargo:rustc-cdylib-link-arg=-Wl,--exclude-libs,ALL");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
