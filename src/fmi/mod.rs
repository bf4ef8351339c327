//! FMI 2.0 co-simulation layer (placeholder on this branch; see the `fmi` branch).

pub mod model;
