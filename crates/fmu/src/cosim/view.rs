//! The String parameter `visualization.directory`: the beam's shape at the communication points
//! as a ParaView series (`STEM_000000.vtu`, … and `STEM.pvd`) and the animation page
//! (`STEM.html`), written by the FMU itself whatever host runs it (`docs/fmu-variables.md`).
//!
//! One [`Views`] per instance (no global state): the series and the recorder of
//! [`hybeam_view`], as the command line's `--vtk` and `--animate` use them.

use std::path::{Path, PathBuf};

use hybeam::scene::Scene;
use hybeam::simulator::{AnyOutputs, AnySimulator, OutputId};

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
    series: hybeam_view::Series,
    page: hybeam_view::Recorder,
    html: PathBuf,
    /// The tip outputs shown on the page.
    tip: Vec<OutputId>,
    /// The collection and the page were written (or the run was discarded): nothing to do on
    /// drop.
    closed: bool,
}

impl Views {
    /// Views in `dir` (created if missing) named `stem`, for the beam of `scene` and its
    /// variable `table`. Writes nothing yet.
    pub fn open(dir: &Path, stem: &str, scene: &Scene, table: &Table) -> Result<Self, String> {
        let radii = hybeam_view::segment_radii(scene);
        let series = hybeam_view::Series::create(dir, stem, radii.clone())
            .map_err(|e| format!("cannot create the ParaView series: {e}"))?;
        let (mut names, mut tip) = (Vec::new(), Vec::new());
        for (index, v) in table.variables().iter().enumerate() {
            if let (Access::Output(id), true) = (table.access(index), v.name.starts_with("tip.")) {
                names.push(v.name.clone());
                tip.push(id);
            }
        }
        let title = format!("{} (FMU instance {stem})", scene.name);
        let page = hybeam_view::Recorder::new(&title, &scene.gravity, radii, names);
        Ok(Self {
            series,
            page,
            html: dir.join(format!("{stem}.html")),
            tip,
            closed: false,
        })
    }

    /// Records the simulator's current state (time, shape, tip outputs) as the next piece and
    /// frame; a time not after the last one (a rollback) first drops the later ones.
    pub fn record(&mut self, sim: &AnySimulator, outputs: &AnyOutputs) -> Result<(), String> {
        // open again (after fmi2Terminate, a restored state that steps on)
        self.closed = false;
        let shape = sim.shape(SAMPLES_PER_ELEMENT);
        let t = sim.time();
        self.series.write(t, &shape).map_err(|e| e.to_string())?;
        let tip: Vec<f64> = self
            .tip
            .iter()
            .map(|&id| outputs.value(id).unwrap_or(f64::NAN))
            .collect();
        self.page.push(t, &shape, &tip);
        Ok(())
    }

    /// Writes the `.pvd` collection and the page (the views are then closed).
    pub fn finish(&mut self) -> Result<(), String> {
        self.closed = true;
        self.series.finish().map_err(|e| e.to_string())?;
        self.page.write(&self.html).map_err(|e| e.to_string())
    }

    /// Closes the views without writing the collection or the page (fmi2Reset: the run's
    /// frames are discarded; the pieces already written stay on disk until overwritten).
    pub fn discard(&mut self) {
        self.closed = true;
    }

    /// The `.pvd` collection's path.
    pub fn collection(&self) -> PathBuf {
        self.series.collection()
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
