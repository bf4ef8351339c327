//! Library part of the hybeam report crate: the stability suite, shared by the `report`
//! binary (`report stability`) and this crate's `tests/stability.rs` (its fast subset), so both
//! run exactly the same cases. The binary's other modules (accuracy, paper, statics, plots)
//! live beside `main.rs` and are not part of the library.

pub mod suite;
