//! The FMU's views: the String parameter `visualization.directory` and the Real parameters
//! `visualization.interval` and `visualization.max_bytes`. The beam's shape at the
//! communication points as a ParaView series (`STEM_000000.vtu`, … and `STEM.pvd`) and the
//! animation page (`STEM.html`), written by the FMU itself whatever host runs it
//! (`docs/fmu-variables.md`, `docs/view.md`).
//!
//! One [`ViewState`] per instance (no global state). Every file is written whole or not at all,
//! never through a symlink ([`hybeam_view::vtk::write_atomic`]). The directory a host sets (or
//! an FMU state restores) takes effect at the next state recorded, so a restore that the model
//! refuses changes nothing; the series of a directory left in a run is kept, and continues if
//! the run comes back to it.

use std::path::Path;

use hybeam::scene::Scene;
use hybeam::simulator::{AnyOutputs, AnySimulator, OutputId};

/// Centreline samples per element of the shape written (as the command line's default).
pub const SAMPLES_PER_ELEMENT: usize = 8;

/// The longest file stem [characters]: a longer instance name is cut and ends in a hash of
/// the whole name (file names stay far below the usual 255-byte limit).
pub const MAX_STEM: usize = 64;

/// Series of directories left in a run kept to continue, at most (the oldest is dropped).
const KEPT_SERIES: usize = 4;

/// The default of `visualization.max_bytes` [bytes]: 1 GB of pieces.
pub const DEFAULT_MAX_BYTES: f64 = 1e9;

/// The file stem of an instance's views: its name with every character outside
/// `[A-Za-z0-9_-]` replaced by `_`; `beam` for an empty name. A name longer than
/// [`MAX_STEM`] keeps its first characters and ends in `_` and 16 hex digits of the FNV-1a
/// hash of the whole name, so that two long names differing late get different stems.
pub fn stem_of(instance_name: &str) -> String {
    if instance_name.is_empty() {
        return "beam".into();
    }
    let clean: String = instance_name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if clean.len() <= MAX_STEM {
        return clean;
    }
    use std::hash::Hasher as _;
    let mut h = fnv::FnvHasher::default();
    h.write(instance_name.as_bytes());
    format!("{}_{:016x}", &clean[..MAX_STEM - 17], h.finish())
}

/// The Real parameters of the views (tunable: they apply from the next state recorded).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// `visualization.interval` [s]: a state is recorded when at least this long after the
    /// last one recorded (0: every communication point).
    pub interval: f64,
    /// `visualization.max_bytes` [bytes]: the series' pieces on disk at most; the piece that
    /// could pass it is not written, with one warning, and none after it in the run.
    pub max_bytes: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            interval: 0.0,
            max_bytes: DEFAULT_MAX_BYTES,
        }
    }
}

/// A Real parameter of the views.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Setting {
    /// [`Settings::interval`].
    Interval,
    /// [`Settings::max_bytes`].
    MaxBytes,
}

impl Settings {
    /// The value of `s`.
    pub fn get(&self, s: Setting) -> f64 {
        match s {
            Setting::Interval => self.interval,
            Setting::MaxBytes => self.max_bytes,
        }
    }

    /// Sets `s` to `x`, or says why not (name, value and the fix).
    pub fn set(&mut self, s: Setting, x: f64) -> Result<(), String> {
        match s {
            Setting::Interval if x >= 0.0 && x.is_finite() => self.interval = x,
            Setting::Interval => {
                return Err(format!(
                    "visualization.interval = {x}: must be a finite time >= 0 [s] (0 records \
                     every communication point)"
                ))
            }
            Setting::MaxBytes if x >= 0.0 && x.is_finite() => self.max_bytes = x,
            Setting::MaxBytes => {
                return Err(format!(
                    "visualization.max_bytes = {x}: must be a finite size >= 0 [bytes] (the \
                     default is {DEFAULT_MAX_BYTES:e})"
                ))
            }
        }
        Ok(())
    }

    fn limit(&self) -> u64 {
        // f64 to u64 saturates
        self.max_bytes as u64
    }
}

/// The views of one run in one directory.
#[derive(Debug)]
struct Views {
    dir: String,
    views: hybeam_view::Views,
    /// The time of the last state recorded [s].
    last: Option<f64>,
    /// The byte limit stopped the pieces (and was reported).
    full: bool,
    /// Recorded since the collection and page were last written.
    dirty: bool,
}

impl Views {
    /// Views in `dir` (created if missing) named `stem` (`STEM.pvd`, `STEM.html`), for the beam
    /// of `scene`, the page showing the outputs `tip` (name, id). Writes nothing yet.
    fn open(
        dir: &str,
        stem: &str,
        scene: &Scene,
        tip: Vec<(String, OutputId)>,
    ) -> Result<Self, String> {
        let title = format!("{} (FMU instance {stem})", scene.name);
        let path = Path::new(dir);
        let views = hybeam_view::Views::create(
            scene,
            Some((path, stem)),
            Some((path.join(format!("{stem}.html")), title)),
            tip,
            SAMPLES_PER_ELEMENT,
        )
        .map_err(|e| format!("cannot create the ParaView series: {e}"))?;
        Ok(Self {
            dir: dir.to_owned(),
            views,
            last: None,
            full: false,
            dirty: false,
        })
    }
}

/// The views' state of one instance.
#[derive(Debug)]
pub struct ViewState {
    /// `visualization.directory` (empty: no views); takes effect at the next state recorded.
    dir: String,
    settings: Settings,
    /// The file stem: the instance name, shortened and sanitized ([`stem_of`]).
    stem: String,
    /// The views being written.
    open: Option<Views>,
    /// The (finished) views of directories left in this run, newest last.
    kept: Vec<Views>,
    /// Directories whose views failed in this run: no more views there until the next run.
    failed: Vec<String>,
    /// Warnings for the FMI layer's next report.
    warnings: Vec<String>,
}

impl Default for ViewState {
    /// No views yet; the stem of an unnamed instance.
    fn default() -> Self {
        Self {
            dir: String::new(),
            settings: Settings::default(),
            stem: stem_of(""),
            open: None,
            kept: Vec::new(),
            failed: Vec::new(),
            warnings: Vec::new(),
        }
    }
}

impl ViewState {
    /// No views yet; the stem of an unnamed instance.
    pub fn new() -> Self {
        Self::default()
    }

    /// `visualization.directory`.
    pub fn dir(&self) -> &str {
        &self.dir
    }

    /// Sets `visualization.directory`: only stored; the views switch at the next state recorded.
    pub fn set_dir(&mut self, value: &str) {
        value.clone_into(&mut self.dir);
    }

    /// The Real parameters.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Sets a Real parameter (checked).
    pub fn set(&mut self, s: Setting, x: f64) -> Result<(), String> {
        self.settings.set(s, x)
    }

    /// The instance's name gives the files' stem.
    pub fn set_instance_name(&mut self, name: &str) {
        self.stem = stem_of(name);
    }

    /// A new run (fmi2ExitInitializationMode, fmi2Reset): the earlier run's views are discarded
    /// (no collection or page written; the new series overwrites its pieces).
    pub fn new_run(&mut self) {
        for v in self.open.iter_mut().chain(&mut self.kept) {
            v.dirty = false;
        }
        self.open = None;
        self.kept.clear();
        self.failed.clear();
    }

    /// fmi2Reset: the run's views are discarded, the parameters back to their start values (no
    /// directory); the instance's stem stays.
    pub fn reset(&mut self) {
        self.new_run();
        self.dir.clear();
        self.settings = Settings::default();
    }

    /// Records the simulator's current state, if a directory is set, the directory's views have
    /// not failed in this run, and `visualization.interval` has passed since the last state
    /// recorded (or the time went back: a rollback). Switches to the directory set first. The
    /// page shows the outputs `tip` gives (name, id; asked when views are opened).
    pub fn record(
        &mut self,
        sim: &AnySimulator,
        outputs: &AnyOutputs,
        scene: &Scene,
        tip: impl FnOnce() -> Vec<(String, OutputId)>,
    ) {
        if self.open.as_ref().is_some_and(|v| v.dir != self.dir) {
            self.leave();
        }
        if self.dir.is_empty() || self.failed.contains(&self.dir) {
            return;
        }
        if self.open.is_none() {
            let back = self.kept.iter().position(|v| v.dir == self.dir);
            self.open = match back.map(|k| self.kept.remove(k)) {
                Some(v) => Some(v),
                None => match Views::open(&self.dir, &self.stem, scene, tip()) {
                    Ok(v) => Some(v),
                    Err(e) => return self.failure(e),
                },
            };
        }
        let (settings, time) = (self.settings, sim.time());
        let Some(v) = &mut self.open else { return };
        let due = v.last.is_none_or(|last| {
            // to rounding of the host's time sums (1e-9 of the interval)
            time <= last || time - last >= settings.interval * (1.0 - 1e-9)
        });
        if !due {
            return;
        }
        v.views.set_limit(settings.limit());
        match v.views.record(sim, outputs) {
            Ok(written) => {
                v.last = Some(time);
                v.dirty = true;
                if !written && !v.full {
                    v.full = true;
                    let message = format!(
                        "visualization.max_bytes = {:e}: the ParaView series in \"{}\" holds \
                         {:.3e} bytes and the next piece could pass it, so no more pieces are \
                         written in this run (the collection lists those written, the page goes \
                         on); raise visualization.max_bytes or visualization.interval",
                        settings.max_bytes,
                        v.dir,
                        v.views.series_bytes() as f64,
                    );
                    self.warnings.push(message);
                }
            }
            Err(e) => self.failure(e.to_string()),
        }
    }

    /// Finishes the open views and keeps them, to continue if the run comes back.
    fn leave(&mut self) {
        if let Some(mut v) = self.open.take() {
            match v.views.finish() {
                Ok(()) => {
                    v.dirty = false;
                    if self.kept.len() == KEPT_SERIES {
                        self.kept.remove(0);
                    }
                    self.kept.push(v);
                }
                Err(e) => {
                    let dir = std::mem::take(&mut v.dir);
                    self.failed_in(dir, e.to_string());
                }
            }
        }
    }

    /// The open views failed: the warning, and no more views in their directory this run.
    fn failure(&mut self, e: String) {
        // dropping the views tries to write the collection and page of what was recorded
        let dir = self
            .open
            .take()
            .map_or_else(|| self.dir.clone(), |v| v.dir.clone());
        self.failed_in(dir, e);
    }

    fn failed_in(&mut self, dir: String, e: String) {
        self.warnings.push(format!(
            "visualization.directory = \"{dir}\": {e}; visualization is off for the rest of \
             this run (until fmi2Reset)"
        ));
        self.failed.push(dir);
    }

    /// Writes the open views' collection and page (fmi2Terminate; a later step after
    /// fmi2SetFMUstate continues them, and the next fmi2Terminate or fmi2FreeInstance rewrites
    /// them).
    pub fn finish(&mut self) {
        if let Some(v) = &mut self.open {
            match v.views.finish() {
                Ok(()) => v.dirty = false,
                Err(e) => self.failure(e.to_string()),
            }
        }
    }

    /// The warnings since the last call, with the failure of a piece written in the background
    /// since then (one message).
    pub fn take_warning(&mut self) -> Option<String> {
        if let Some(v) = &mut self.open {
            if let Err(e) = v.views.poll() {
                self.failure(e.to_string());
            }
        }
        if self.warnings.is_empty() {
            return None;
        }
        let all = self.warnings.join("; ");
        self.warnings.clear();
        Some(all)
    }
}

/// fmi2FreeInstance without fmi2Terminate: the collection and the page of what was recorded
/// are still written (errors are ignored: there is no call left to report them).
impl Drop for Views {
    fn drop(&mut self) {
        if self.dirty {
            let _ = self.views.finish();
        }
    }
}
