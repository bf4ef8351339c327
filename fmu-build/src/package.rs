//! The FMU zip: `modelDescription.xml`, `binaries/<platform>/<id>.so`, `resources/scene.toml`.
//! Deterministic: fixed entry order, fixed timestamps (1980-01-01), fixed permissions.

use std::fs::File;
use std::io::Write;
use std::path::Path;

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// The FMI 2.0 platform folder of the machine that builds the binary.
pub fn platform() -> Result<&'static str, String> {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("linux", "x86_64") => Ok("linux64"),
        (os, arch) => Err(format!(
            "packaging for {os}/{arch} is not supported (only linux/x86_64 → binaries/linux64)"
        )),
    }
}

/// Writes the FMU archive to `path`.
pub fn write_fmu(
    path: &Path,
    model_description: &str,
    platform: &str,
    id: &str,
    library: &Path,
    scene: &[u8],
) -> Result<(), String> {
    let binary =
        std::fs::read(library).map_err(|e| format!("cannot read {}: {e}", library.display()))?;
    let file = File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut zip = ZipWriter::new(file);
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .last_modified_time(DateTime::default());
    let entries: [(String, &[u8], u32); 3] = [
        (
            "modelDescription.xml".into(),
            model_description.as_bytes(),
            0o644,
        ),
        (format!("binaries/{platform}/{id}.so"), &binary, 0o755),
        ("resources/scene.toml".into(), scene, 0o644),
    ];
    let fail = |e: &dyn std::fmt::Display| format!("writing {}: {e}", path.display());
    for (name, data, mode) in entries {
        zip.start_file(name, options.unix_permissions(mode))
            .map_err(|e| fail(&e))?;
        zip.write_all(data).map_err(|e| fail(&e))?;
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
        let lib = dir.join("libx.so");
        std::fs::write(&lib, b"\x7fELF").unwrap();
        let (a, b) = (dir.join("a.fmu"), dir.join("b.fmu"));
        for p in [&a, &b] {
            write_fmu(p, "<xml/>", "linux64", "x", &lib, b"scene").unwrap();
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
                "resources/scene.toml"
            ]
        );
        let mut s = String::new();
        std::io::Read::read_to_string(&mut zip.by_name("resources/scene.toml").unwrap(), &mut s)
            .unwrap();
        assert_eq!(s, "scene");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
