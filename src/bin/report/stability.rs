//! Stability suite.

/// Runs the stability suite.
pub fn run(_quick: bool) -> Result<(), String> {
    Ok(())
}
