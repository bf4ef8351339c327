//! A self-contained animation page of a run: the frames recorded here, serialized as JSON into
//! `viewer/page.html` together with the viewer script (`viewer/dist/viewer.js`: three.js and
//! `viewer/src/main.js` bundled by esbuild from the npm registry's packages), so the page opens
//! offline in any browser.
//!
//! Per frame: the centreline points [m], the section y axis (twist), what colours the tube (the
//! largest von Mises stress over the section from the strains, `hybeam::model::strain_stress`;
//! a page made from a series read back: the largest fibre strain |ε| + |κ|·c, c the section's
//! outer radius), the root frame and the tip values. Positions, axes and strains are stored as 32-bit floats (display only),
//! times and tip values as 64-bit (shown as numbers).

use crate::look::Look;
use crate::vtk::ViewError;
use base64::Engine as _;
use hybeam::model::Shape;
use serde::Serialize;
use std::path::Path;

/// The page template (placeholders `__TITLE__`, `__DATA__`, `__VIEWER__`).
const PAGE: &str = include_str!("../../../viewer/page.html");
/// The bundled viewer (three.js + viewer/src/main.js), built by `npm run build` in `viewer/`.
const VIEWER: &str = include_str!("../../../viewer/dist/viewer.js");

/// The most frames a page holds (at 40 points, ~5 MB of data per 1000 frames).
pub const MAX_FRAMES: usize = 5000;

/// A rigid body drawn as a box carried by the root (mount) frame: a vehicle's body.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BodyBox {
    /// Edge lengths along the frame's x, y, z [m].
    pub size: [f64; 3],
    /// The box centre in the root frame [m].
    pub centre: [f64; 3],
}

/// Frames of a run being recorded for the page.
#[derive(Debug, Clone)]
pub struct Recorder {
    title: String,
    up: [f64; 3],
    tip_names: Vec<String>,
    /// The tube's radius along the segments and the attached masses.
    look: Look,
    /// Outer radius at each point [m] (from the first frame).
    radius: Vec<f32>,
    /// The attached masses' centres per frame [m] (3 per mass).
    masses: Vec<f32>,
    segments: Vec<[usize; 2]>,
    points: usize,
    times: Vec<f64>,
    positions: Vec<f32>,
    section: Vec<f32>,
    strain: Vec<f32>,
    root: Vec<f32>,
    tip: Vec<f64>,
    body: Option<BodyBox>,
}

/// The page's data (viewer/src/main.js reads these fields).
#[derive(Serialize)]
struct PageData<'a> {
    title: &'a str,
    up: [f64; 3],
    points: usize,
    segments: &'a [[usize; 2]],
    radius: String,
    times: String,
    positions: String,
    section: String,
    strain: String,
    strain_label: &'a str,
    root: String,
    tip: TipData<'a>,
    body: Option<BodyBox>,
    /// The attached masses' sphere radii [m] and their centres per frame.
    mass_radius: Vec<f64>,
    masses: String,
}

#[derive(Serialize)]
struct TipData<'a> {
    names: &'a [String],
    values: String,
}

impl Recorder {
    /// A recorder titled `title`, `gravity` (world axes, 2 or 3 components) giving the up
    /// direction (−g; y up without gravity in the plane, z in space), the beam dressed by
    /// `look` (the tube's radius, the attached masses), tip values named `tip_names` given with
    /// each frame.
    pub fn new(title: &str, gravity: &[f64], look: Look, tip_names: Vec<String>) -> Self {
        let g: [f64; 3] = std::array::from_fn(|k| gravity.get(k).copied().unwrap_or(0.0));
        let norm = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        let up = if norm > 0.0 {
            g.map(|c| -c / norm)
        } else if gravity.len() == 2 {
            [0.0, 1.0, 0.0]
        } else {
            [0.0, 0.0, 1.0]
        };
        Self {
            title: title.to_string(),
            up,
            tip_names,
            look,
            radius: Vec::new(),
            masses: Vec::new(),
            segments: Vec::new(),
            points: 0,
            times: Vec::new(),
            positions: Vec::new(),
            section: Vec::new(),
            strain: Vec::new(),
            root: Vec::new(),
            tip: Vec::new(),
            body: None,
        }
    }

    /// Draws `body` carried by the root frame.
    pub fn with_body(mut self, body: BodyBox) -> Self {
        self.body = Some(body);
        self
    }

    /// Number of frames recorded.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether no frame was recorded.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Records the frame at `time` [s]: `shape` and the tip values (one per name). A time not
    /// after the last frame's (a rollback or reset) first drops the frames at or after it.
    /// Beyond [`MAX_FRAMES`] every other frame is dropped (the first and the latest kept), so a
    /// long run's page stays a few tens of MB at most.
    pub fn push(&mut self, time: f64, shape: &Shape, tip: &[f64]) {
        let radii = if self.times.is_empty() {
            self.look.point_radii(shape)
        } else {
            Vec::new()
        };
        let centres = self.look.mass_centres(shape);
        self.push_dressed(time, shape, &radii, &centres, tip);
        // colour by the von Mises stress where the look knows the sections
        if let Some(stress) = self.look.point_stresses(shape) {
            let n = stress.len();
            let at = self.strain.len() - n;
            for (s, x) in self.strain[at..].iter_mut().zip(stress) {
                *s = x as f32;
            }
        }
    }

    /// [`Recorder::push`] with the tube's radius at each point [m] (used at the first frame
    /// only) and the masses' centres [m] (one per mass of the look) given: a series read back.
    pub fn push_dressed(
        &mut self,
        time: f64,
        shape: &Shape,
        radii: &[f64],
        centres: &[[f64; 3]],
        tip: &[f64],
    ) {
        if self.times.len() >= MAX_FRAMES {
            self.thin();
        }
        while self.times.last().is_some_and(|t| *t >= time) {
            self.pop();
        }
        if self.times.is_empty() {
            self.points = shape.points.len();
            self.segments = shape.segments.iter().map(|r| [r.start, r.end]).collect();
            self.radius = (0..shape.points.len())
                .map(|i| radii.get(i).copied().unwrap_or(0.0) as f32)
                .collect();
        }
        self.times.push(time);
        for (i, p) in shape.points.iter().enumerate() {
            self.positions.extend(p.position.map(|x| x as f32));
            self.section.extend(p.frame[1].map(|x| x as f32));
            let c = self.radius.get(i).copied().unwrap_or(0.0) as f64;
            self.strain
                .push((p.axial_strain.abs() + p.bending() * c) as f32);
        }
        for k in 0..self.look.masses.len() {
            let c = centres.get(k).copied().unwrap_or_default();
            self.masses.extend(c.map(|x| x as f32));
        }
        let r = &shape.root;
        self.root.extend(r.origin.map(|x| x as f32));
        for a in &r.axes {
            self.root.extend(a.map(|x| x as f32));
        }
        self.tip
            .extend((0..self.tip_names.len()).map(|k| tip.get(k).copied().unwrap_or(f64::NAN)));
    }

    /// Keeps the even frames and the last one.
    fn thin(&mut self) {
        let n = self.times.len();
        let keep = |i: usize| i.is_multiple_of(2) || i + 1 == n;
        fn retain<T: Copy>(v: &mut Vec<T>, per: usize, keep: impl Fn(usize) -> bool) {
            let mut w = 0;
            for i in 0..v.len() / per.max(1) {
                if keep(i) {
                    v.copy_within(i * per..(i + 1) * per, w * per);
                    w += 1;
                }
            }
            v.truncate(w * per);
        }
        let p = self.points;
        retain(&mut self.times, 1, keep);
        retain(&mut self.positions, 3 * p, keep);
        retain(&mut self.section, 3 * p, keep);
        retain(&mut self.strain, p, keep);
        retain(&mut self.root, 12, keep);
        retain(&mut self.tip, self.tip_names.len(), keep);
        retain(&mut self.masses, 3 * self.look.masses.len(), keep);
    }

    fn pop(&mut self) {
        self.times.pop();
        let n = self.points;
        self.positions.truncate(self.positions.len() - 3 * n);
        self.section.truncate(self.section.len() - 3 * n);
        self.strain.truncate(self.strain.len() - n);
        self.root.truncate(self.root.len() - 12);
        self.tip.truncate(self.tip.len() - self.tip_names.len());
        self.masses
            .truncate(self.masses.len() - 3 * self.look.masses.len());
    }

    /// The page's HTML text.
    pub fn page(&self) -> String {
        let f32s = |v: &[f32]| {
            let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
            base64::engine::general_purpose::STANDARD.encode(bytes)
        };
        let f64s = |v: &[f64]| {
            let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
            base64::engine::general_purpose::STANDARD.encode(bytes)
        };
        let data = PageData {
            title: &self.title,
            up: self.up,
            points: self.points,
            segments: &self.segments,
            radius: f32s(&self.radius),
            times: f64s(&self.times),
            positions: f32s(&self.positions),
            section: f32s(&self.section),
            strain: f32s(&self.strain),
            strain_label: if self.look.segments.is_empty() {
                "largest fibre strain |ε| + |κ|·c [-]"
            } else {
                "von Mises stress [Pa]"
            },
            root: f32s(&self.root),
            tip: TipData {
                names: &self.tip_names,
                values: f64s(&self.tip),
            },
            body: self.body,
            mass_radius: self.look.mass_radii(),
            masses: f32s(&self.masses),
        };
        let json = serde_json::to_string(&data).expect("plain data serializes");
        // inside <script>: no "</" may end the element early
        let json = json.replace("</", "<\\/");
        PAGE.replacen("__TITLE__", &html_escape(&self.title), 1)
            .replacen("__DATA__", &json, 1)
            .replacen("__VIEWER__", &VIEWER.replace("</script", "<\\/script"), 1)
    }

    /// Writes the page to `path`, whole or not at all ([`crate::vtk::write_atomic`]).
    pub fn write(&self, path: &Path) -> Result<(), ViewError> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|source| ViewError::Io {
                path: dir.to_path_buf(),
                source,
            })?;
        }
        crate::vtk::write_atomic(path, self.page().as_bytes())
    }
}

/// `s` with the HTML special characters escaped.
fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
