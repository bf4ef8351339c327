//! The platforms an FMU can carry, how each binary is built, and which toolchains are present.
//!
//! - `linux64`: `binaries/linux64/<id>.so`, built by the cargo that runs this tool (rustup's),
//!   linked against glibc 2.31 by `cargo zigbuild` (target `x86_64-unknown-linux-gnu.2.31`, own
//!   target directory `<target>/glibc231`) when cargo-zigbuild is installed
//!   (`scripts/setup-glibc.sh`: a venv in `<target>/zig/venv`), else against this machine's
//!   glibc (Debian 12: the .so then needs glibc ≥ 2.34). See [`Glibc`].
//! - `win64`: `binaries/win64/<id>.dll` for `x86_64-pc-windows-gnu` (Windows 10 and later),
//!   built by Debian's `/usr/bin/cargo` + `/usr/bin/rustc` (`rustc-web` 1.96) with
//!   `RUSTC_BOOTSTRAP=1 -Zbuild-std=std,panic_unwind` from the std sources of `rust-web-src`,
//!   linked by `x86_64-w64-mingw32-gcc`, in its own target directory `<target>/win64` (std is
//!   built once there and cached). `scripts/setup-win64.sh` installs the toolchain.
//!
//! Both binaries are built with `[profile.fmu-release]` (release code, no debug info) and then
//! stripped of their symbol tables by binutils (`strip --strip-all`, `x86_64-w64-mingw32-strip`
//! from binutils-mingw-w64-x86-64) into a copy beside cargo's output: the exported fmi2*
//! functions stay (they are in the dynamic symbol table or the export directory). Stripping
//! after the build keeps the profile, so cargo's cache is not invalidated.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// An FMI 2.0 platform folder under `binaries/`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Platform {
    /// `binaries/linux64/<id>.so`, x86_64 Linux (glibc).
    Linux64,
    /// `binaries/win64/<id>.dll`, x86_64 Windows 10 or later.
    Win64,
}

/// Every platform this tool can build, in archive order.
pub const ALL: [Platform; 2] = [Platform::Linux64, Platform::Win64];

/// Cargo profile of the shipped binaries (`[profile.fmu-release]`: no debug info, stripped).
const PROFILE: &str = "fmu-release";
/// The Rust target of the win64 binary.
const WIN64_TARGET: &str = "x86_64-pc-windows-gnu";
/// The mingw-w64 linker (the target's default linker; no cargo config needed).
const WIN64_LINKER: &str = "x86_64-w64-mingw32-gcc";
/// The binutils that strip the win64 DLL.
const WIN64_STRIP: &str = "x86_64-w64-mingw32-strip";
/// The zig-linked Linux target: glibc 2.31 (Ubuntu 20.04, Debian 11, RHEL 9 has 2.34).
const GLIBC_TARGET: &str = "x86_64-unknown-linux-gnu.2.31";
/// How to install the glibc-2.31 toolchain.
pub const GLIBC_SETUP: &str =
    "bash scripts/setup-glibc.sh (cargo-zigbuild + ziglang from PyPI in target/zig/venv)";
/// How to install the win64 toolchain.
pub const WIN64_SETUP: &str = "bash scripts/setup-win64.sh (Debian 12: apt rustc-web cargo-web \
                               rust-web-src gcc-mingw-w64-x86-64)";

/// How the linux64 binary is linked against glibc (`--glibc`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Glibc {
    /// `cargo-zigbuild` (this path) links against glibc 2.31's symbol versions: the .so loads on
    /// glibc ≥ 2.31 (2020 long-term-support distributions).
    Zig(PathBuf),
    /// The build machine's glibc: the .so needs the symbol versions found there.
    Host,
}

impl Glibc {
    /// `--glibc 2.31` (needs cargo-zigbuild), `--glibc host`, or `None`: 2.31 when
    /// cargo-zigbuild is installed, else host (with a note on what that means and how to get
    /// 2.31).
    pub fn choose(arg: Option<&str>, root: &Path) -> Result<Glibc, String> {
        let zig = zigbuild(root);
        match (arg, zig) {
            (Some("host"), _) => Ok(Glibc::Host),
            (Some("2.31") | None, Some(z)) => Ok(Glibc::Zig(z)),
            (Some("2.31"), None) => Err(format!(
                "--glibc 2.31 needs cargo-zigbuild; install with {GLIBC_SETUP}"
            )),
            (None, None) => {
                eprintln!(
                    "fmu-build: linux64 linked against this machine's glibc (the .so needs the \
                     glibc versions found here, 2.34 on Debian 12); for glibc 2.31: {GLIBC_SETUP}"
                );
                Ok(Glibc::Host)
            }
            (Some(other), _) => Err(format!("--glibc \"{other}\": expected 2.31 or host")),
        }
    }
}

/// cargo-zigbuild: `HYBEAM_ZIGBUILD`, else `<target>/zig/venv/bin/cargo-zigbuild` (what
/// `scripts/setup-glibc.sh` installs), else on PATH.
fn zigbuild(root: &Path) -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("HYBEAM_ZIGBUILD") {
        return Some(PathBuf::from(p));
    }
    let venv = target_dir(root).ok()?.join("zig/venv/bin/cargo-zigbuild");
    if venv.is_file() {
        return Some(venv);
    }
    std::env::var_os("PATH").and_then(|path| {
        std::env::split_paths(&path)
            .map(|d| d.join("cargo-zigbuild"))
            .find(|p| p.is_file())
    })
}

impl Platform {
    /// The folder name under `binaries/`.
    pub fn folder(self) -> &'static str {
        match self {
            Platform::Linux64 => "linux64",
            Platform::Win64 => "win64",
        }
    }

    /// The file name suffix of the shared library.
    pub fn suffix(self) -> &'static str {
        match self {
            Platform::Linux64 => ".so",
            Platform::Win64 => ".dll",
        }
    }

    /// Parses a folder name (`linux64`, `win64`).
    pub fn parse(name: &str) -> Result<Platform, String> {
        ALL.into_iter()
            .find(|p| p.folder() == name)
            .ok_or_else(|| format!("unknown platform \"{name}\" (known: linux64, win64)"))
    }

    /// `Ok` if this machine can build the platform's binary, else what is missing and how to
    /// install it.
    pub fn toolchain(self) -> Result<(), String> {
        match self {
            Platform::Linux64 => match (std::env::consts::OS, std::env::consts::ARCH) {
                ("linux", "x86_64") if on_path("strip") => Ok(()),
                ("linux", "x86_64") => Err("linux64 needs strip (apt install binutils)".into()),
                (os, arch) => Err(format!(
                    "linux64 is built natively on linux/x86_64, not on {os}/{arch}"
                )),
            },
            Platform::Win64 => {
                let tools = Win64Tools::from_env();
                let mut missing = Vec::new();
                if !tools.cargo.is_file() || !tools.rustc.is_file() {
                    missing.push(format!(
                        "{} and {} (cargo-web, rustc-web)",
                        tools.cargo.display(),
                        tools.rustc.display()
                    ));
                } else if !tools.std_sources().is_some_and(|s| s.is_dir()) {
                    missing.push(format!(
                        "the std sources of {} (rust-web-src)",
                        tools.rustc.display()
                    ));
                }
                if !on_path(WIN64_LINKER) {
                    missing.push(format!("{WIN64_LINKER} (gcc-mingw-w64-x86-64)"));
                }
                if !on_path(WIN64_STRIP) {
                    missing.push(format!("{WIN64_STRIP} (binutils-mingw-w64-x86-64)"));
                }
                if missing.is_empty() {
                    Ok(())
                } else {
                    Err(format!(
                        "win64 needs {}; install with {WIN64_SETUP}",
                        missing.join(" and ")
                    ))
                }
            }
        }
    }

    /// Builds the `hybeam-fmu` cdylib for this platform in the workspace `root` and strips it;
    /// returns the stripped copy (`stripped/` beside the library cargo reports).
    pub fn build(self, root: &Path, glibc: &Glibc) -> Result<PathBuf, String> {
        let library = self.cargo_build(root, glibc)?;
        let dir = library.parent().unwrap_or(Path::new(".")).join("stripped");
        std::fs::create_dir_all(&dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        let stripped = dir.join(library.file_name().unwrap_or_default());
        let tool = match self {
            Platform::Linux64 => "strip",
            Platform::Win64 => WIN64_STRIP,
        };
        let status = Command::new(tool)
            .arg("--strip-all")
            .arg("-o")
            .arg(&stripped)
            .arg(&library)
            .status()
            .map_err(|e| format!("cannot run {tool}: {e}"))?;
        if !status.success() {
            return Err(format!("{tool} {} failed ({status})", library.display()));
        }
        let size = |p: &Path| std::fs::metadata(p).map_or(0, |m| m.len());
        eprintln!(
            "fmu-build: {}: {} ({} bytes, {} stripped)",
            self.folder(),
            library.display(),
            size(&library),
            size(&stripped)
        );
        Ok(stripped)
    }

    /// `cargo build` of the cdylib; returns the library path cargo reports.
    fn cargo_build(self, root: &Path, glibc: &Glibc) -> Result<PathBuf, String> {
        let zig = match (self, glibc) {
            (Platform::Linux64, Glibc::Zig(z)) => Some(z),
            _ => None,
        };
        let cargo = match (self, zig) {
            (Platform::Linux64, Some(z)) => z.clone(),
            (Platform::Linux64, None) => {
                std::env::var_os("CARGO").map_or("cargo".into(), PathBuf::from)
            }
            (Platform::Win64, _) => Win64Tools::from_env().cargo,
        };
        let mut cmd = Command::new(&cargo);
        cmd.current_dir(root)
            .arg(if zig.is_some() { "zigbuild" } else { "build" });
        cmd.args(["--profile", PROFILE, "-p", "hybeam-fmu", "--lib"]);
        if self == Platform::Linux64 && zig.is_none() {
            // the same packages as `cargo fmu-build` built this tool with (`.cargo/config.toml`:
            // run --profile fmu-release -p fmu-build): the same unified features, so the engine
            // it compiled for the tool is the library's (no second compile)
            cmd.args(["-p", "fmu-build"]);
        }
        if let Some(z) = zig {
            // zig itself comes from the venv's ziglang (`python -m ziglang`): its bin first
            let mut path = vec![z.parent().unwrap_or(Path::new(".")).to_path_buf()];
            path.extend(std::env::split_paths(
                &std::env::var_os("PATH").unwrap_or_default(),
            ));
            cmd.env(
                "PATH",
                std::env::join_paths(path).map_err(|e| format!("PATH: {e}"))?,
            )
            .args(["--target", GLIBC_TARGET, "--target-dir"])
            .arg(target_dir(root)?.join("glibc231"));
        }
        if self == Platform::Win64 {
            let target_dir = target_dir(root)?.join("win64");
            cmd.env("RUSTC", Win64Tools::from_env().rustc)
                .env("RUSTC_BOOTSTRAP", "1")
                .args(["-Zbuild-std=std,panic_unwind", "--target", WIN64_TARGET])
                .arg("--target-dir")
                .arg(&target_dir);
        }
        cmd.arg("--message-format=json-render-diagnostics")
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit());
        eprintln!(
            "fmu-build: building the {} hybeam-fmu cdylib (profile {PROFILE}): {}",
            self.folder(),
            std::iter::once(cmd.get_program())
                .chain(cmd.get_args())
                .map(|a| a.to_string_lossy())
                .collect::<Vec<_>>()
                .join(" ")
        );
        let output = cmd
            .output()
            .map_err(|e| format!("cannot run {}: {e}", cargo.display()))?;
        if !output.status.success() {
            return Err(format!(
                "cargo build for {} failed ({})",
                self.folder(),
                output.status
            ));
        }
        cdylib_artifact(&String::from_utf8_lossy(&output.stdout), self.suffix())
            .ok_or_else(|| format!("cargo did not report a hybeam_fmu {} cdylib", self.suffix()))
    }
}

/// Parses `--platforms linux64,win64`; `None` (option absent) means every platform whose
/// toolchain is installed, and the skipped ones are reported through `skipped`.
pub fn select(list: Option<&str>, skipped: &mut Vec<String>) -> Result<Vec<Platform>, String> {
    let Some(list) = list else {
        let mut chosen = Vec::new();
        for p in ALL {
            match p.toolchain() {
                Ok(()) => chosen.push(p),
                Err(why) => skipped.push(format!("{} skipped: {why}", p.folder())),
            }
        }
        if chosen.is_empty() {
            return Err(format!(
                "no platform can be built here: {}",
                skipped.join("; ")
            ));
        }
        return Ok(chosen);
    };
    let mut chosen = Vec::new();
    for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let p = Platform::parse(name).map_err(|e| format!("--platforms {list}: {e}"))?;
        if !chosen.contains(&p) {
            chosen.push(p);
        }
    }
    if chosen.is_empty() {
        return Err(format!(
            "--platforms \"{list}\" names no platform (e.g. --platforms linux64,win64)"
        ));
    }
    // archive order, whatever the order given
    chosen.sort_by_key(|p| ALL.iter().position(|q| q == p));
    for p in &chosen {
        p.toolchain()
            .map_err(|e| format!("--platforms {list}: {e}"))?;
    }
    Ok(chosen)
}

/// Debian's cargo and rustc for the win64 build (`HYBEAM_WIN64_CARGO`/`HYBEAM_WIN64_RUSTC`
/// override `/usr/bin/cargo`, `/usr/bin/rustc`; rustup's proxies come first on PATH, so the
/// absolute paths matter).
struct Win64Tools {
    cargo: PathBuf,
    rustc: PathBuf,
}

impl Win64Tools {
    fn from_env() -> Self {
        let get = |var: &str, default: &str| {
            std::env::var_os(var).map_or_else(|| PathBuf::from(default), PathBuf::from)
        };
        Self {
            cargo: get("HYBEAM_WIN64_CARGO", "/usr/bin/cargo"),
            rustc: get("HYBEAM_WIN64_RUSTC", "/usr/bin/rustc"),
        }
    }

    /// `<sysroot>/lib/rustlib/src/rust/library/std`, where `-Zbuild-std` looks.
    fn std_sources(&self) -> Option<PathBuf> {
        let out = Command::new(&self.rustc)
            .args(["--print", "sysroot"])
            .output()
            .ok()
            .filter(|o| o.status.success())?;
        let sysroot = String::from_utf8(out.stdout).ok()?;
        Some(Path::new(sysroot.trim()).join("lib/rustlib/src/rust/library/std"))
    }
}

/// Whether an executable `name` is on PATH.
fn on_path(name: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|path| std::env::split_paths(&path).any(|dir| dir.join(name).is_file()))
}

/// The workspace's cargo target directory (`cargo metadata`, so `CARGO_TARGET_DIR` and cargo
/// config are honoured).
fn target_dir(root: &Path) -> Result<PathBuf, String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(root)
        .args(["metadata", "--format-version", "1", "--no-deps"])
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo metadata: {e}"))?;
    let meta: serde_json::Value = serde_json::from_slice(&out.stdout)
        .map_err(|e| format!("cargo metadata: unreadable output: {e}"))?;
    meta["target_directory"]
        .as_str()
        .map(PathBuf::from)
        .ok_or_else(|| "cargo metadata: no target_directory".into())
}

/// The `hybeam_fmu` cdylib file ending in `suffix` in cargo's JSON messages.
fn cdylib_artifact(stdout: &str, suffix: &str) -> Option<PathBuf> {
    stdout.lines().find_map(|line| {
        let msg = serde_json::from_str::<serde_json::Value>(line).ok()?;
        let is_lib = msg["reason"] == "compiler-artifact"
            && msg["target"]["name"] == "hybeam_fmu"
            && msg["target"]["kind"]
                .as_array()
                .is_some_and(|k| k.iter().any(|k| k == "cdylib"));
        if !is_lib {
            return None;
        }
        msg["filenames"]
            .as_array()?
            .iter()
            .filter_map(|f| f.as_str())
            .find(|f| f.ends_with(suffix))
            .map(PathBuf::from)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_orders_platform_lists() {
        assert_eq!(Platform::parse("win64"), Ok(Platform::Win64));
        assert!(Platform::parse("win32")
            .unwrap_err()
            .contains("linux64, win64"));
        let mut skipped = Vec::new();
        for bad in ["", ",", "linux64,darwin64"] {
            assert!(select(Some(bad), &mut skipped).is_err(), "{bad:?}");
        }
        // linux64 is always buildable here (the tests run on linux/x86_64)
        assert_eq!(
            select(Some(" linux64 ,linux64"), &mut skipped),
            Ok(vec![Platform::Linux64])
        );
        let default = select(None, &mut skipped).unwrap();
        assert_eq!(default[0], Platform::Linux64);
        assert_eq!(default.len() + skipped.len(), ALL.len(), "{skipped:?}");
        match Platform::Win64.toolchain() {
            Ok(()) => assert_eq!(
                select(Some("win64,linux64"), &mut skipped),
                Ok(vec![Platform::Linux64, Platform::Win64])
            ),
            Err(why) => {
                assert!(why.contains("scripts/setup-win64.sh"), "{why}");
                assert!(select(Some("win64"), &mut skipped).is_err());
            }
        }
    }

    #[test]
    fn finds_the_cdylib_among_cargo_messages() {
        let lines = [
            r#"{"reason":"compiler-artifact","target":{"name":"hybeam","kind":["lib"]},"filenames":["/t/libhybeam.rlib"]}"#,
            r#"{"reason":"compiler-artifact","target":{"name":"hybeam_fmu","kind":["rlib","cdylib"]},"filenames":["/t/libhybeam_fmu.rlib","/t/hybeam_fmu.dll","/t/libhybeam_fmu.dll.a"]}"#,
            "not json",
        ]
        .join("\n");
        assert_eq!(
            cdylib_artifact(&lines, ".dll"),
            Some(PathBuf::from("/t/hybeam_fmu.dll"))
        );
        assert_eq!(cdylib_artifact(&lines, ".so"), None);
    }
}
