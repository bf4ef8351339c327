//! The FMU's GUID: a deterministic UUID of the resource bytes and the model's build identity.
//!
//! `guid = UUIDv5(namespace, BUILD_ID + "\n" + resource bytes)`, where the namespace is itself
//! `UUIDv5(NAMESPACE_OID, GUID_NAMESPACE)` ([`CoSimModel`] constants). The same resource
//! packaged by another build gets another GUID, so a host cannot pair an XML with the wrong
//! binary. The packager writes it into modelDescription.xml; fmi2Instantiate recomputes it from
//! the resource file and refuses a mismatch.

use uuid::Uuid;

use super::model::CoSimModel;

/// The GUID of `resource` (exact bytes of the resource file) for the model `M`, formatted as
/// `{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}` (lower case, with braces as in most FMUs).
pub fn guid<M: CoSimModel>(resource: &[u8]) -> String {
    guid_in(M::GUID_NAMESPACE, M::BUILD_ID, resource)
}

/// The GUID of `resource` for a namespace name and build identity.
pub fn guid_in(namespace: &str, build_id: &str, resource: &[u8]) -> String {
    let namespace = Uuid::new_v5(&Uuid::NAMESPACE_OID, namespace.as_bytes());
    let mut name = Vec::with_capacity(resource.len() + build_id.len() + 1);
    name.extend_from_slice(build_id.as_bytes());
    name.push(b'\n');
    name.extend_from_slice(resource);
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

    fn g(resource: &[u8]) -> String {
        guid_in("test.fmi2", "test/1.0", resource)
    }

    #[test]
    fn deterministic_and_resource_sensitive() {
        let a = g(b"x = 1\n");
        assert_eq!(a, g(b"x = 1\n"));
        assert_ne!(a, g(b"x = 2\n"));
        assert_ne!(a, guid_in("test.fmi2", "test/1.1", b"x = 1\n"));
        assert_ne!(a, guid_in("other.fmi2", "test/1.0", b"x = 1\n"));
        assert_eq!(a.len(), 38);
        assert!(a.starts_with('{') && a.ends_with('}'));
    }

    #[test]
    fn comparison_ignores_braces_and_case() {
        let a = g(b"s");
        assert!(same_guid(&a.to_uppercase(), &a));
        assert!(same_guid(a.trim_matches(|c| c == '{' || c == '}'), &a));
        assert!(!same_guid(&g(b"t"), &a));
        assert!(!same_guid("", &a));
    }
}
