//! Packages the pitch-plane car as an FMI 2.0 co-simulation FMU (`hybeam_vehicle::package`):
//!
//! ```text
//! car-fmu target/release/libhybeam_vehicle.so examples/vehicle/vehicle.toml out/car.fmu
//! ```
//!
//! after `cargo build --release -p hybeam-vehicle --lib --features export`; writes
//! `vehicle_OspModelDescription.xml` beside it ([`Vehicle::osp_model_description`]).

use std::process::ExitCode;

use hybeam_vehicle::Vehicle;

fn main() -> ExitCode {
    hybeam_vehicle::package::command::<Vehicle>("car-fmu", Vehicle::osp_model_description)
}
