//! The engine's transcendental functions come from `src/math.rs` (the `libm` crate, the same
//! bits on every target), never from std's `f64` methods, which call the platform's C library
//! and made the win64 and linux64 FMUs differ (docs/platforms.md). Scans `src/` outside test
//! modules (an inline one closes its file; an out-of-line one is a `tests.rs`). Code generic
//! over num-dual numbers uses `math::sin_cos_dual`.

use std::path::Path;

const FORBIDDEN: [&str; 17] = [
    ".sin(",
    ".cos(",
    ".tan(",
    ".sin_cos(",
    ".exp(",
    ".exp_m1(",
    ".ln(",
    ".ln_1p(",
    ".log2(",
    ".log10(",
    ".powf(",
    ".atan2(",
    ".atan(",
    ".asin(",
    ".acos(",
    ".sinh(",
    ".cosh(",
];
const MORE: [&str; 4] = [".tanh(", ".hypot(", ".cbrt(", ".mul_add("];

fn scan(dir: &Path, found: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            scan(&path, found);
            continue;
        }
        // `tests.rs`: a test module in its own file (`#[cfg(test)] mod tests;`)
        if path.extension().is_none_or(|e| e != "rs")
            || path.ends_with("math.rs")
            || path.ends_with("tests.rs")
        {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            if line.trim_start().starts_with("#[cfg(test)]") {
                break; // test modules close each file
            }
            let code = line.split("//").next().unwrap_or("");
            if FORBIDDEN.iter().chain(&MORE).any(|f| code.contains(f)) {
                found.push(format!("{}:{}: {}", path.display(), i + 1, line.trim()));
            }
        }
    }
}

#[test]
fn engine_uses_portable_transcendental_functions() {
    let mut found = Vec::new();
    scan(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &mut found,
    );
    assert!(
        found.is_empty(),
        "std's platform-dependent functions in the engine (use crate::math):\n{}",
        found.join("\n")
    );
}
