//! The `fmuResourceLocation` URI of fmi2Instantiate and the model's resource file in it.

use std::path::PathBuf;

/// The local directory named by an FMI 2.0 resource location.
///
/// Accepted forms: `file:///abs/dir`, `file://localhost/abs/dir`, `file:/abs/dir` (each with or
/// without a trailing slash, percent-encoded bytes such as `%20` decoded; scheme and host
/// case-insensitive, RFC 3986), and, leniently, a plain absolute path `/abs/dir` (some hosts
/// pass one). On Windows the path may start with a drive, `file:///C:/dir` (RFC 8089 E.2;
/// Wine's `file:///Z:/...` alike) or a plain `C:\dir`. Anything else is refused with a message.
pub fn resource_dir(location: &str) -> Result<PathBuf, String> {
    resource_dir_for(location, cfg!(windows))
}

/// [`resource_dir`] with the platform's drive rule given (`windows`), so both are unit-tested.
fn resource_dir_for(location: &str, windows: bool) -> Result<PathBuf, String> {
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
    } else if location.starts_with('/') || (windows && is_drive(location)) {
        location
    } else {
        return Err(format!(
            "resource location \"{location}\" is not a file URI (expected file:///path/to/resources)"
        ));
    };
    // `/C:/dir` → `C:/dir`: the URI path's first segment is a drive letter.
    let path = match path.strip_prefix('/') {
        Some(rest) if windows && is_drive(rest) => rest,
        _ => path,
    };
    let bytes =
        percent_decode(path).map_err(|e| format!("resource location \"{location}\": {e}"))?;
    Ok(bytes_to_path(bytes))
}

/// Whether `s` starts with a Windows drive: a letter and `:`, then `/`, `\\` or nothing.
fn is_drive(s: &str) -> bool {
    let b = s.as_bytes();
    b.len() >= 2
        && b[0].is_ascii_alphabetic()
        && b[1] == b':'
        && matches!(b.get(2), None | Some(b'/') | Some(b'\\'))
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

    /// Windows hosts pass `file:///C:/...` (Wine: `file:///Z:/...`) or a plain drive path; the
    /// drive is kept and the URI's leading slash dropped. Elsewhere `/C:/x` stays a Unix path.
    #[test]
    fn windows_drive_forms() {
        for (uri, want) in [
            (
                "file:///C:/Users/a%20b/fmu/resources",
                "C:/Users/a b/fmu/resources",
            ),
            ("file:///z:/tmp/x/", "z:/tmp/x/"),
            ("file:/C:/x", "C:/x"),
            ("file://localhost/C:/x", "C:/x"),
            ("file:///C:", "C:"),
            ("C:\\Temp\\fmu\\resources", "C:\\Temp\\fmu\\resources"),
            ("/tmp/plain", "/tmp/plain"),
        ] {
            assert_eq!(
                resource_dir_for(uri, true).unwrap(),
                PathBuf::from(want),
                "{uri}"
            );
        }
        assert_eq!(
            resource_dir_for("file:///C:/x", false).unwrap(),
            PathBuf::from("/C:/x")
        );
        assert_eq!(
            resource_dir_for("file:///CD:/x", true).unwrap(),
            PathBuf::from("/CD:/x")
        );
        for uri in ["C:\\x", "C:relative", "file:C:/x"] {
            assert!(resource_dir_for(uri, false).is_err(), "{uri}");
        }
        assert!(resource_dir_for("C:relative", true).is_err());
    }
}
