//! The FMU zip: `modelDescription.xml`, `binaries/<platform>/<id>.<so|dll>` for each platform,
//! `resources/scene.toml`. Deterministic: fixed entry order, fixed timestamps (1980-01-01),
//! fixed permissions.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::platform::Platform;

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// Writes the FMU archive to `path`: one binary per `(platform, library file)`, in the order
/// given.
pub fn write_fmu(
    path: &Path,
    model_description: &str,
    binaries: &[(Platform, PathBuf)],
    id: &str,
    scene: &[u8],
) -> Result<(), String> {
    let mut entries: Vec<(String, Vec<u8>, u32)> = vec![(
        "modelDescription.xml".into(),
        model_description.as_bytes().to_vec(),
        0o644,
    )];
    for (platform, library) in binaries {
        let binary = std::fs::read(library)
            .map_err(|e| format!("cannot read {}: {e}", library.display()))?;
        let name = format!("binaries/{}/{id}{}", platform.folder(), platform.suffix());
        entries.push((name, binary, 0o755));
    }
    entries.push(("resources/scene.toml".into(), scene.to_vec(), 0o644));
    let file = File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut zip = ZipWriter::new(file);
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .last_modified_time(DateTime::default());
    let fail = |e: &dyn std::fmt::Display| format!("writing {}: {e}", path.display());
    for (name, data, mode) in entries {
        zip.start_file(name, options.unix_permissions(mode))
            .map_err(|e| fail(&e))?;
        zip.write_all(&data).map_err(|e| fail(&e))?;
    }
    zip.finish().map_err(|e| fail(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_and_determinism() {
        let dir = std::env::temp_dir().join(format!("fmu-build-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (so, dll) = (dir.join("libx.so"), dir.join("x.dll"));
        std::fs::write(&so, b"\x7fELF").unwrap();
        std::fs::write(&dll, b"MZ").unwrap();
        let binaries = [(Platform::Linux64, so), (Platform::Win64, dll)];
        let (a, b) = (dir.join("a.fmu"), dir.join("b.fmu"));
        for p in [&a, &b] {
            write_fmu(p, "<xml/>", &binaries, "x", b"scene").unwrap();
        }
        let bytes = std::fs::read(&a).unwrap();
        assert_eq!(bytes, std::fs::read(&b).unwrap(), "byte-identical archives");
        let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
        let names: Vec<String> = zip.file_names().map(|n| n.unwrap().into_owned()).collect();
        assert_eq!(
            names,
            [
                "modelDescription.xml",
                "binaries/linux64/x.so",
                "binaries/win64/x.dll",
                "resources/scene.toml"
            ]
        );
        let mut s = String::new();
        std::io::Read::read_to_string(&mut zip.by_name("resources/scene.toml").unwrap(), &mut s)
            .unwrap();
        assert_eq!(s, "scene");
        let mut dll = Vec::new();
        std::io::Read::read_to_end(&mut zip.by_name("binaries/win64/x.dll").unwrap(), &mut dll)
            .unwrap();
        assert_eq!(dll, b"MZ");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
