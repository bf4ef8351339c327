//! hybeam
