//! The `fmuResourceLocation` URI of fmi2Instantiate and the model's resource file in it.

use std::path::PathBuf;

/// The local directory named by an FMI 2.0 resource location.
///
/// Accepted forms: `file:///abs/dir`, `file://localhost/abs/dir`, `file:/abs/dir` (each with or
/// without a trailing slash, percent-encoded bytes such as `%20` decoded; scheme and host
/// case-insensitive, RFC 3986), and, leniently, a plain absolute path `/abs/dir` (some hosts
/// pass one). Anything else is refused with a message.
pub fn resource_dir(location: &str) -> Result<PathBuf, String> {
    let scheme = location
        .get(..5)
        .filter(|s| s.eq_ignore_ascii_case("file:"));
    let path = if let Some(rest) = scheme.map(|_| &location[5..]) {
        if let Some(after) = rest.strip_prefix("//") {
            // Authority: empty or "localhost".
            let slash = after.find('/').ok_or_else(|| {
                format!("resource location \"{location}\" has no path after the authority")
            })?;
            let host = &after[..slash];
            if !(host.is_empty() || host.eq_ignore_ascii_case("localhost")) {
                return Err(format!(
                    "resource location \"{location}\" names the remote host \"{host}\"; \
                     only local file URIs are supported"
                ));
            }
            &after[slash..]
        } else if rest.starts_with('/') {
            rest
        } else {
            return Err(format!(
                "resource location \"{location}\" is not an absolute file URI \
                 (expected file:///path/to/resources)"
            ));
        }
    } else if location.starts_with('/') {
        location
    } else {
        return Err(format!(
            "resource location \"{location}\" is not a file URI (expected file:///path/to/resources)"
        ));
    };
    let bytes =
        percent_decode(path).map_err(|e| format!("resource location \"{location}\": {e}"))?;
    Ok(bytes_to_path(bytes))
}

fn percent_decode(s: &str) -> Result<Vec<u8>, String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = b
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("invalid percent escape at byte {i}"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    Ok(out)
}

#[cfg(unix)]
fn bytes_to_path(bytes: Vec<u8>) -> PathBuf {
    use std::os::unix::ffi::OsStringExt;
    PathBuf::from(std::ffi::OsString::from_vec(bytes))
}

#[cfg(not(unix))]
fn bytes_to_path(bytes: Vec<u8>) -> PathBuf {
    PathBuf::from(String::from_utf8_lossy(&bytes).into_owned())
}

/// Reads the file `name` from the resource directory named by `location`.
pub fn read_resource(location: &str, name: &str) -> Result<Vec<u8>, String> {
    let dir = resource_dir(location)?;
    if !dir.is_dir() {
        return Err(format!(
            "resource directory {} (from \"{location}\") does not exist or is not a directory",
            dir.display()
        ));
    }
    let file = dir.join(name);
    std::fs::read(&file).map_err(|e| format!("cannot read {}: {e}", file.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepted_forms() {
        for (uri, want) in [
            ("file:///tmp/x/resources", "/tmp/x/resources"),
            ("file:///tmp/x/resources/", "/tmp/x/resources/"),
            ("file://localhost/tmp/x", "/tmp/x"),
            ("file:/tmp/x", "/tmp/x"),
            ("file:///tmp/my%20dir/r", "/tmp/my dir/r"),
            ("FILE:///tmp/x", "/tmp/x"),
            ("File://LocalHost/tmp/x", "/tmp/x"),
            ("/tmp/plain", "/tmp/plain"),
        ] {
            assert_eq!(resource_dir(uri).unwrap(), PathBuf::from(want), "{uri}");
        }
    }

    #[test]
    fn refused_forms() {
        for uri in [
            "http://x/y",
            "file://server/share",
            "file:relative",
            "relative/path",
            "file:///a%2",
            "file:///a%zz",
            "",
        ] {
            assert!(resource_dir(uri).is_err(), "{uri}");
        }
    }
}
