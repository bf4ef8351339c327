//! The views of one run recorded together: an optional ParaView series and an optional
//! animation page, the shape sampled once per recorded state. What `hybeam run --vtk/--animate`
//! and the FMU's `visualization.directory` write.

use crate::animation::Recorder;
use crate::look::Look;
use crate::vtk::{Series, ViewError};
use hybeam::scene::Scene;
use hybeam::simulator::{AnyOutputs, AnySimulator, OutputId};
use std::path::{Path, PathBuf};

/// The views of one run.
#[derive(Debug)]
pub struct Views {
    series: Option<Series>,
    page: Option<(Recorder, PathBuf)>,
    /// The outputs shown on the page.
    tip: Vec<OutputId>,
    /// Centreline intervals per element.
    samples: usize,
}

impl Views {
    /// The views of a run of `scene`: a series in `series` = (directory, file stem), a page
    /// at `page` = (path, title) showing the outputs `tip` (name, id), `samples` intervals per
    /// element. Creates the series' directory; writes nothing yet.
    pub fn create(
        scene: &Scene,
        series: Option<(&Path, &str)>,
        page: Option<(PathBuf, String)>,
        tip: Vec<(String, OutputId)>,
        samples: usize,
    ) -> Result<Self, ViewError> {
        let look = Look::of(scene);
        let series = match series {
            Some((dir, stem)) => Some(Series::create(dir, stem, look.clone())?),
            None => None,
        };
        let (names, tip): (Vec<String>, Vec<OutputId>) = tip.into_iter().unzip();
        let page =
            page.map(|(path, title)| (Recorder::new(&title, &scene.gravity, look, names), path));
        Ok(Self {
            series,
            page,
            tip,
            samples,
        })
    }

    /// Records the simulator's current state (`outputs` its outputs) as the next piece and
    /// frame; a time not after the last one (a rollback) first drops the later ones. `Ok(false)`:
    /// the series has reached its byte limit ([`Views::set_limit`]) and no piece was written (the
    /// page, bounded by its frame count, still records).
    pub fn record(&mut self, sim: &AnySimulator, outputs: &AnyOutputs) -> Result<bool, ViewError> {
        if self.series.is_none() && self.page.is_none() {
            return Ok(true);
        }
        let shape = sim.shape(self.samples);
        let mut written = true;
        if let Some(series) = &mut self.series {
            written = series.write(sim.time(), &shape)?;
        }
        if let Some((rec, _)) = &mut self.page {
            let tip: Vec<f64> = self
                .tip
                .iter()
                .map(|&id| outputs.value(id).unwrap_or(f64::NAN))
                .collect();
            rec.push(sim.time(), &shape, &tip);
        }
        Ok(written)
    }

    /// At most `limit` bytes of series pieces on disk, from the next piece on.
    pub fn set_limit(&mut self, limit: u64) {
        if let Some(series) = &mut self.series {
            series.set_limit(limit);
        }
    }

    /// The first failure of a piece written in the background since the last call, if any.
    pub fn poll(&mut self) -> Result<(), ViewError> {
        self.series.as_mut().map_or(Ok(()), Series::poll)
    }

    /// Writes every pending piece, the `.pvd` collection and the page.
    pub fn finish(&mut self) -> Result<(), ViewError> {
        if let Some(series) = &mut self.series {
            series.finish()?;
        }
        if let Some((rec, path)) = &self.page {
            rec.write(path)?;
        }
        Ok(())
    }

    /// Bytes of the series' pieces on disk, as far as written (0 without a series).
    pub fn series_bytes(&self) -> u64 {
        self.series.as_ref().map_or(0, Series::bytes)
    }

    /// The series' `.pvd` collection and its number of pieces, if a series is written.
    pub fn collection(&self) -> Option<(PathBuf, usize)> {
        self.series.as_ref().map(|s| (s.collection(), s.len()))
    }

    /// The page's path, if a page is written.
    pub fn page(&self) -> Option<&Path> {
        self.page.as_ref().map(|(_, p)| p.as_path())
    }
}
