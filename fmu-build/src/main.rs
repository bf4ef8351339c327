//! `fmu-build`: packages a scene as an FMI 2.0 co-simulation FMU.
//!
//! ```text
//! fmu-build SCENE.toml [--out DIR] [--id NAME] [--xml-only]
//! ```
//!
//! 1. reads the scene and (unless `--xml-only`) builds the model with `from_resource`, so that
//!    a scene the FMU could not instantiate (bad values, an initial static solve that fails)
//!    fails here, with the scene's message and exit code 1, not in the host;
//! 2. writes modelDescription.xml (GUID, variable table, default experiment) from the scene
//!    alone (`BeamFmu::model_description`);
//! 3. runs `cargo build --profile fmu-release -p hybeam-fmu --lib` in this workspace (release
//!    code without debug info) and takes the cdylib that cargo reports (so `CARGO_TARGET_DIR`
//!    and cargo config are honoured);
//! 4. zips `modelDescription.xml`, `binaries/linux64/<id>.so`, `resources/scene.toml` into
//!    `DIR/<id>.fmu`.
//!
//! `--xml-only` skips the model build of 1 (the scene is still read and validated) and 3–4, and
//! writes `DIR/<id>.xml` (the golden files in `modelDescription/`): the description is a
//! function of the scene alone.
//! `<id>` (modelIdentifier) defaults to the scene file stem made a C identifier.
//! Alias: `cargo fmu-build ...` (see `.cargo/config.toml`).

mod package;

use clap::Parser;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};

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
    let platform = package::platform()?;
    let library = build_cdylib()?;
    let path = args.out.join(format!("{id}.fmu"));
    package::write_fmu(&path, &description, platform, &id, &library, &scene)?;
    Ok(path)
}

/// The workspace this tool was built from (the hybeam sources matching the linked library).
fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."))
}

/// Cargo profile of the shipped binary (`[profile.fmu-release]`: release without debug info).
const PROFILE: &str = "fmu-release";

/// Runs `cargo build --profile fmu-release -p hybeam-fmu --lib` and returns the cdylib path
/// cargo reports.
fn build_cdylib() -> Result<PathBuf, String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let root = workspace_root();
    eprintln!(
        "fmu-build: building the hybeam-fmu cdylib (profile {PROFILE}) in {}",
        root.display()
    );
    let output = Command::new(&cargo)
        .current_dir(&root)
        .args(["build", "--profile", PROFILE, "-p", "hybeam-fmu", "--lib"])
        .arg("--message-format=json-render-diagnostics")
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run {}: {e}", Path::new(&cargo).display()))?;
    if !output.status.success() {
        return Err(format!("cargo build failed ({})", output.status));
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let suffix = std::env::consts::DLL_SUFFIX;
    for line in stdout.lines() {
        let Ok(msg) = serde_json::from_str::<serde_json::Value>(line) else {
            continue;
        };
        let is_lib = msg["reason"] == "compiler-artifact"
            && msg["target"]["name"] == "hybeam_fmu"
            && msg["target"]["kind"]
                .as_array()
                .is_some_and(|k| k.iter().any(|k| k == "cdylib"));
        if !is_lib {
            continue;
        }
        let files = msg["filenames"].as_array().into_iter().flatten();
        if let Some(f) = files
            .filter_map(|f| f.as_str())
            .find(|f| f.ends_with(suffix))
        {
            return Ok(PathBuf::from(f));
        }
    }
    Err("cargo did not report a hybeam_fmu cdylib artifact".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(a: &[&str]) -> Result<Args, clap::Error> {
        Args::try_parse_from(std::iter::once("fmu-build").chain(a.iter().copied()))
    }

    #[test]
    fn parses_options() {
        let a = args(&["s.toml", "--out", "o", "--id", "x", "--xml-only"]).unwrap();
        assert_eq!(a.scene, PathBuf::from("s.toml"));
        assert_eq!(a.out, PathBuf::from("o"));
        assert_eq!(a.id.as_deref(), Some("x"));
        assert!(a.xml_only);
        let a = args(&["scenes/case1.toml"]).unwrap();
        assert_eq!((a.out, a.id, a.xml_only), (PathBuf::from("."), None, false));
        assert!(args(&[]).is_err());
        assert!(args(&["a", "b"]).is_err());
        assert!(args(&["a", "--bogus"]).is_err());
        assert!(args(&["a", "--out"]).is_err());
    }
}
