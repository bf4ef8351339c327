//! A car as an FMI 2.0 co-simulation FMU archive: the `car-fmu` and `car3d-fmu` commands
//!
//! ```text
//! car-fmu LIBRARY RESOURCE OUT.fmu
//! ```
//!
//! `LIBRARY` is the built cdylib (built with `--features export`, which holds the FMI entry
//! points), `RESOURCE` the car's TOML (packaged as `resources/<M::RESOURCE>`); the
//! modelIdentifier is `OUT`'s file stem. modelDescription.xml comes from the model itself (the
//! generic layer's generator), so it cannot disagree with the binary. Deterministic zip (fixed
//! order, timestamps, permissions). Beside it, the car's OSP-IS port groups
//! (`<modelName>_OspModelDescription.xml`).

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

use fmi2::CoSimModel;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// The OSP-IS port groups of a model: file name and text.
pub type Osp<M> = fn(&M) -> Result<(String, String), String>;

/// The command `name LIBRARY RESOURCE OUT.fmu` for the model `M`: prints the FMU's path, or the
/// error and fails.
pub fn command<M: CoSimModel>(name: &str, osp: Osp<M>) -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [library, resource, out] = args.as_slice() else {
        eprintln!("usage: {name} LIBRARY RESOURCE OUT.fmu");
        return ExitCode::FAILURE;
    };
    match package::<M>(Path::new(library), Path::new(resource), Path::new(out), osp) {
        Ok(()) => {
            println!("{out}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{name}: error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Writes the FMU `out` of the model `M` from its `library` and `resource`, and its port groups
/// beside it.
pub fn package<M: CoSimModel>(
    library: &Path,
    resource: &Path,
    out: &Path,
    osp: Osp<M>,
) -> Result<(), String> {
    let read = |p: &Path| std::fs::read(p).map_err(|e| format!("cannot read {}: {e}", p.display()));
    let text = String::from_utf8(read(resource)?).map_err(|e| format!("{e}"))?;
    let model = M::from_resource(&text)?;
    let id = out
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or_else(|| format!("{}: no file name", out.display()))?;
    let guid = fmi2::guid::guid::<M>(text.as_bytes());
    let xml = fmi2::xml::model_description_of(&model, id, &guid)?;
    let entries: [(String, Vec<u8>, u32); 3] = [
        ("modelDescription.xml".into(), xml.into_bytes(), 0o644),
        (format!("binaries/linux64/{id}.so"), read(library)?, 0o755),
        (
            format!("resources/{}", M::RESOURCE),
            text.into_bytes(),
            0o644,
        ),
    ];
    let file = std::fs::File::create(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut zip = ZipWriter::new(file);
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .last_modified_time(DateTime::default());
    for (name, data, mode) in entries {
        zip.start_file(name, options.unix_permissions(mode))
            .map_err(|e| e.to_string())?;
        zip.write_all(&data).map_err(|e| e.to_string())?;
    }
    zip.finish().map_err(|e| e.to_string())?;
    // the port groups, where libcosim looks for them (beside the FMU)
    let (name, osp) = osp(&model)?;
    let osp_path = out.with_file_name(name);
    std::fs::write(&osp_path, osp).map_err(|e| format!("{}: {e}", osp_path.display()))?;
    Ok(())
}
