//! The String parameter `visualization.directory`: the beam's shape at the communication points
//! as a ParaView series (`STEM_000000.vtu`, … and `STEM.pvd`) and the animation page
//! (`STEM.html`), written by the FMU itself whatever host runs it (`docs/fmu-variables.md`).
//!
//! One [`Views`] per instance (no global state): [`hybeam_view::Views`], as the command line's
//! `--vtk` and `--animate` use it, closed once (terminate, reset or drop).

use std::path::{Path, PathBuf};

use hybeam::scene::Scene;
use hybeam::simulator::{AnyOutputs, AnySimulator};

use super::variables::{Access, Table};

/// Centreline samples per element of the shape written (as the command line's default).
pub const SAMPLES_PER_ELEMENT: usize = 8;

/// The file stem of an instance's views: its name with every character outside
/// `[A-Za-z0-9_-]` replaced by `_`; `beam` for an empty name.
pub fn stem_of(instance_name: &str) -> String {
    if instance_name.is_empty() {
        return "beam".into();
    }
    instance_name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The views of one run being written.
#[derive(Debug)]
pub struct Views {
    views: hybeam_view::Views,
    /// The collection and the page were written (or the run was discarded): nothing to do on
    /// drop.
    closed: bool,
}

impl Views {
    /// Views in `dir` (created if missing) named `stem` (`STEM.pvd`, `STEM.html`), for the beam
    /// of `scene` and its variable `table` (the page shows its `tip.*` outputs). Writes nothing
    /// yet.
    pub fn open(dir: &Path, stem: &str, scene: &Scene, table: &Table) -> Result<Self, String> {
        let tip = (0..table.variables().len())
            .filter_map(|index| match table.access(index) {
                Access::Output(id) if table.variables()[index].name.starts_with("tip.") => {
                    Some((table.variables()[index].name.clone(), id))
                }
                _ => None,
            })
            .collect();
        let title = format!("{} (FMU instance {stem})", scene.name);
        let views = hybeam_view::Views::create(
            scene,
            Some((dir, stem)),
            Some((dir.join(format!("{stem}.html")), title)),
            tip,
            SAMPLES_PER_ELEMENT,
        )
        .map_err(|e| format!("cannot create the ParaView series: {e}"))?;
        Ok(Self {
            views,
            closed: false,
        })
    }

    /// Records the simulator's current state (time, shape, tip outputs) as the next piece and
    /// frame; a time not after the last one (a rollback) first drops the later ones.
    pub fn record(&mut self, sim: &AnySimulator, outputs: &AnyOutputs) -> Result<(), String> {
        // open again (after fmi2Terminate, a restored state that steps on)
        self.closed = false;
        self.views.record(sim, outputs).map_err(|e| e.to_string())
    }

    /// Writes the `.pvd` collection and the page (the views are then closed).
    pub fn finish(&mut self) -> Result<(), String> {
        self.closed = true;
        self.views.finish().map_err(|e| e.to_string())
    }

    /// Closes the views without writing the collection or the page (fmi2Reset: the run's
    /// frames are discarded; the pieces already written stay on disk until overwritten).
    pub fn discard(&mut self) {
        self.closed = true;
    }

    /// The `.pvd` collection's path.
    pub fn collection(&self) -> PathBuf {
        self.views
            .collection()
            .expect("the FMU's views write a series")
            .0
    }
}

/// fmi2FreeInstance without fmi2Terminate: the collection and the page of what was recorded
/// are still written (errors are ignored: there is no call left to report them).
impl Drop for Views {
    fn drop(&mut self) {
        if !self.closed {
            let _ = self.finish();
        }
    }
}
