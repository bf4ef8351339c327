//! `fmu-build`: packages a scene as an FMI 2.0 co-simulation FMU.
//!
//! ```text
//! fmu-build SCENE.toml [--out DIR] [--id NAME] [--xml-only] [--platforms linux64,win64]
//!           [--glibc 2.31|host]
//! ```
//!
//! 1. reads the scene and (unless `--xml-only`) builds the model with `from_resource`, so that
//!    a scene the FMU could not instantiate (bad values, an initial static solve that fails)
//!    fails here, with the scene's message and exit code 1, not in the host;
//! 2. writes modelDescription.xml (GUID, variable table, default experiment) from the scene
//!    alone (`BeamFmu::model_description`);
//! 3. for each platform, runs `cargo build --profile fmu-release -p hybeam-fmu --lib` in this
//!    workspace (release code, stripped; win64 cross-built, see `platform.rs`) and takes the
//!    cdylib that cargo reports (so `CARGO_TARGET_DIR` and cargo config are honoured);
//! 4. zips `modelDescription.xml`, `binaries/linux64/<id>.so`, `binaries/win64/<id>.dll`,
//!    `resources/scene.toml` into `DIR/<id>.fmu`;
//! 5. for a mounted scene, writes its OSP-IS port groups beside it,
//!    `DIR/<modelName>_OspModelDescription.xml` (`BeamFmu::osp_model_description`).
//!
//! Without `--platforms`, every platform whose toolchain is installed is built and each skipped
//! one is reported with how to install it (win64: `bash scripts/setup-win64.sh`); a platform
//! named in `--platforms` whose toolchain is missing is an error. The linux64 binary is linked
//! against glibc 2.31 when cargo-zigbuild is installed (`bash scripts/setup-glibc.sh`), else
//! against this machine's glibc (said so); `--glibc` chooses explicitly.
//!
//! `--xml-only` skips the model build of 1 (the scene is still read and validated) and 3–4, and
//! writes `DIR/<id>.xml` (the golden files in `modelDescription/`): the description is a
//! function of the scene alone.
//! `<id>` (modelIdentifier) defaults to the scene file stem made a C identifier.
//! Alias: `cargo fmu-build ...` (see `.cargo/config.toml`).

mod package;
mod platform;

use clap::Parser;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use fmi2::{xml, CoSimModel};
use hybeam_fmu::FmuModel;

/// Package a hybeam scene as an FMI 2.0 co-simulation FMU.
#[derive(Debug, Parser)]
#[command(name = "fmu-build", version)]
struct Args {
    /// Scene file (TOML); packaged as resources/scene.toml.
    scene: PathBuf,
    /// Output directory (created if missing).
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    /// modelIdentifier, a C identifier [default: the scene file stem made a C identifier].
    #[arg(long, value_name = "NAME")]
    id: Option<String>,
    /// Write only DIR/<id>.xml (the golden files in modelDescription/), no build, no .fmu.
    #[arg(long)]
    xml_only: bool,
    /// Comma-separated platforms to build: linux64, win64 [default: every platform whose
    /// toolchain is installed; skipped ones are reported].
    #[arg(long, value_name = "LIST")]
    platforms: Option<String>,
    /// glibc the linux64 binary is linked against: 2.31 (cargo-zigbuild) or host [default: 2.31
    /// when cargo-zigbuild is installed, else host].
    #[arg(long, value_name = "VERSION")]
    glibc: Option<String>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(path) => {
            println!("{}", path.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("fmu-build: error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> Result<PathBuf, String> {
    let scene_path = &args.scene;
    let scene = std::fs::read(scene_path)
        .map_err(|e| format!("cannot read {}: {e}", scene_path.display()))?;
    let text = std::str::from_utf8(&scene)
        .map_err(|_| format!("{} is not valid UTF-8", scene_path.display()))?;
    if !args.xml_only {
        FmuModel::from_resource(text)
            .map_err(|e| format!("invalid scene {}: {e}", scene_path.display()))?;
    }
    let id = match &args.id {
        Some(id) if xml::is_c_identifier(id) => id.clone(),
        Some(id) => return Err(format!("--id {id}: not a valid C identifier")),
        None => {
            let stem = scene_path.file_stem().unwrap_or_default().to_string_lossy();
            xml::model_identifier_from_stem(&stem)
        }
    };
    let description = FmuModel::model_description(text, &id)
        .map_err(|e| format!("invalid scene {}: {e}", scene_path.display()))?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    if args.xml_only {
        let path = args.out.join(format!("{id}.xml"));
        std::fs::write(&path, description)
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        return Ok(path);
    }
    let mut skipped = Vec::new();
    let platforms = platform::select(args.platforms.as_deref(), &mut skipped)?;
    for s in &skipped {
        eprintln!("fmu-build: {s}");
    }
    let root = workspace_root();
    let glibc = if platforms.contains(&platform::Platform::Linux64) {
        platform::Glibc::choose(args.glibc.as_deref(), &root)?
    } else {
        platform::Glibc::Host
    };
    let mut binaries = Vec::new();
    for p in platforms {
        binaries.push((p, p.build(&root, &glibc)?));
    }
    let path = args.out.join(format!("{id}.fmu"));
    package::write_fmu(&path, &description, &binaries, &id, &scene)?;
    // a mounted beam's port groups, where libcosim looks for them (beside the FMU)
    if let Some((name, osp)) = FmuModel::osp_model_description(text)? {
        let osp_path = args.out.join(name);
        std::fs::write(&osp_path, osp)
            .map_err(|e| format!("cannot write {}: {e}", osp_path.display()))?;
        eprintln!("fmu-build: wrote {}", osp_path.display());
    }
    Ok(path)
}

/// The workspace this tool was built from (the hybeam sources matching the linked library).
fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(a: &[&str]) -> Result<Args, clap::Error> {
        Args::try_parse_from(std::iter::once("fmu-build").chain(a.iter().copied()))
    }

    #[test]
    fn parses_options() {
        let a = args(&[
            "s.toml",
            "--out",
            "o",
            "--id",
            "x",
            "--xml-only",
            "--platforms",
            "win64",
        ])
        .unwrap();
        assert_eq!(a.platforms.as_deref(), Some("win64"));
        assert_eq!(a.scene, PathBuf::from("s.toml"));
        assert_eq!(a.out, PathBuf::from("o"));
        assert_eq!(a.id.as_deref(), Some("x"));
        assert!(a.xml_only);
        let a = args(&["scenes/case1.toml"]).unwrap();
        assert_eq!((a.out, a.id, a.xml_only), (PathBuf::from("."), None, false));
        assert_eq!(a.platforms, None);
        assert!(args(&[]).is_err());
        assert!(args(&["a", "b"]).is_err());
        assert!(args(&["a", "--bogus"]).is_err());
        assert!(args(&["a", "--out"]).is_err());
    }
}
