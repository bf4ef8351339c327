//! Packages the spatial car as an FMI 2.0 co-simulation FMU (`hybeam_vehicle::package`):
//!
//! ```text
//! car3d-fmu target/release/libhybeam_vehicle3d.so examples/vehicle3d/vehicle3d.toml out/car3d.fmu
//! ```
//!
//! after `cargo build --release -p hybeam-vehicle3d --lib --features export`; writes
//! `vehicle3d_OspModelDescription.xml` beside it ([`Vehicle3d::osp_model_description`]).

use std::process::ExitCode;

use hybeam_vehicle3d::Vehicle3d;

fn main() -> ExitCode {
    hybeam_vehicle::package::command::<Vehicle3d>("car3d-fmu", Vehicle3d::osp_model_description)
}
