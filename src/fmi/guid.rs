//! The FMU's GUID: a deterministic UUID of the scene text and the crate version.
//!
//! `guid = UUIDv5(namespace, "hybeam/" + CARGO_PKG_VERSION + "\n" + scene bytes)`, where the
//! namespace is itself `UUIDv5(NAMESPACE_OID, "hybeam.fmi2")`. The same scene packaged by another
//! version of the crate gets another GUID, so a host cannot pair an XML with the wrong binary.
//! fmu-build writes it into modelDescription.xml; fmi2Instantiate recomputes it from
//! `resources/scene.toml` and refuses a mismatch.

use uuid::Uuid;

/// The crate version baked into every GUID.
pub const CRATE_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The GUID of `scene` (exact bytes of the scene file) for this crate version, formatted as
/// `{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}` (lower case, with braces as in most FMUs).
pub fn guid(scene: &[u8]) -> String {
    let namespace = Uuid::new_v5(&Uuid::NAMESPACE_OID, b"hybeam.fmi2");
    let mut name = Vec::with_capacity(scene.len() + 32);
    name.extend_from_slice(b"hybeam/");
    name.extend_from_slice(CRATE_VERSION.as_bytes());
    name.push(b'\n');
    name.extend_from_slice(scene);
    format!("{{{}}}", Uuid::new_v5(&namespace, &name).hyphenated())
}

/// True if `given` (from the host) names the same GUID as `expected`: braces optional,
/// case-insensitive.
pub fn same_guid(given: &str, expected: &str) -> bool {
    fn core(s: &str) -> &str {
        let s = s.trim();
        s.strip_prefix('{')
            .and_then(|s| s.strip_suffix('}'))
            .unwrap_or(s)
    }
    core(given).eq_ignore_ascii_case(core(expected))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deterministic_and_scene_sensitive() {
        let a = guid(b"x = 1\n");
        assert_eq!(a, guid(b"x = 1\n"));
        assert_ne!(a, guid(b"x = 2\n"));
        assert_eq!(a.len(), 38);
        assert!(a.starts_with('{') && a.ends_with('}'));
    }

    #[test]
    fn comparison_ignores_braces_and_case() {
        let a = guid(b"s");
        assert!(same_guid(&a.to_uppercase(), &a));
        assert!(same_guid(a.trim_matches(|c| c == '{' || c == '}'), &a));
        assert!(!same_guid(&guid(b"t"), &a));
        assert!(!same_guid("", &a));
    }
}
