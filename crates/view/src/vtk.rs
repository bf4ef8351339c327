//! The beam's shape over time as a ParaView series: one `.vtu` (VTK XML unstructured grid,
//! encoded by `vtkio`) per output time and a `.pvd` collection naming them with their times
//! (encoded by `quick-xml`), each file written whole or not at all ([`write_atomic`]).
//!
//! Each `.vtu` holds the centreline samples of [`hybeam::model::Shape`] as points, one
//! `VTK_POLY_LINE` cell per segment, a `VTK_VERTEX` at each joint, one at the root (mount)
//! frame's origin and one at each attached mass's centre ([`crate::look`]). Point data: `velocity` [m/s], `tangent`, `section_y`, `section_z` (the
//! section frame, unit vectors; at the root vertex the root frame's x, y, z axes),
//! `axial_strain` [-], `curvature` [1/m] (magnitude), `curvature_y`, `curvature_z` [1/m]
//! (about the section axes), `twist` [rad/m], `arc` [m] (reference arc length from the root).
//! Cell data: `segment` (scene index; −1 at the root vertex), `kind` (0 segment, 1 joint,
//! 2 root frame, 3 attached mass). A Tube filter with radius `radius` (point data, the section's
//! outer radius [m], varying along a taper) draws the real section; `stress` [Pa] is the largest
//! von Mises stress over the section from the point's strains (`hybeam::model::strain_stress`); at a mass's vertex `radius`
//! is its sphere's (a Glyph filter scaled by it draws the masses).

use crate::look::Look;
use hybeam::model::Shape;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};
use std::path::{Path, PathBuf};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataArray, DataSet, ElementType,
    UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

/// Why a view could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// A file or directory operation failed.
    #[error("{path}: {source}")]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
    /// vtkio refused to write or read a piece.
    #[error("{path}: {message}")]
    Vtk {
        /// The file.
        path: PathBuf,
        /// vtkio's message.
        message: String,
    },
    /// A series or piece is not what this module writes.
    #[error("{path}: {message}")]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
}

impl ViewError {
    fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Self + '_ {
        move |source| Self::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

/// The VTK data set of one shape (see the module doc) dressed by `look` (the tube's radius,
/// the attached masses).
pub fn piece(shape: &Shape, look: &Look) -> Vtk {
    let n = shape.points.len();
    let masses = look.mass_centres(shape);
    let extra = shape.joints.len() + 1 + masses.len();
    let total = n + 1 + masses.len();
    let radii = look.point_radii(shape);
    let stresses = look.point_stresses(shape).unwrap_or_else(|| vec![0.0; n]);
    let mut points = Vec::with_capacity(3 * total);
    let mut vectors: [Vec<f64>; 4] = std::array::from_fn(|_| Vec::with_capacity(3 * total));
    let mut scalars: [Vec<f64>; 8] = std::array::from_fn(|_| Vec::with_capacity(total));
    for ((p, radius), stress) in shape.points.iter().zip(radii).zip(stresses) {
        points.extend_from_slice(&p.position);
        vectors[0].extend_from_slice(&p.velocity);
        for k in 0..3 {
            vectors[k + 1].extend_from_slice(&p.frame[k]);
        }
        for (s, v) in scalars.iter_mut().zip([
            p.axial_strain,
            p.bending(),
            p.curvature[0],
            p.curvature[1],
            p.twist,
            p.arc,
            radius,
            stress,
        ]) {
            s.push(v);
        }
    }
    // the root frame's origin as one more point, its axes in the frame arrays
    points.extend_from_slice(&shape.root.origin);
    vectors[0].extend_from_slice(&[0.0; 3]);
    for k in 0..3 {
        vectors[k + 1].extend_from_slice(&shape.root.axes[k]);
    }
    for s in &mut scalars {
        s.push(0.0);
    }
    // the attached masses' centres as points, their spheres' radii in `radius`
    for (c, r) in masses.iter().zip(look.mass_radii()) {
        points.extend_from_slice(c);
        for v in &mut vectors {
            v.extend_from_slice(&[0.0; 3]);
        }
        for (k, s) in scalars.iter_mut().enumerate() {
            s.push(if k == 6 { r } else { 0.0 });
        }
    }
    // cells: polylines, joint vertices, the root vertex
    let (mut connectivity, mut offsets, mut types) = (Vec::new(), Vec::new(), Vec::new());
    let (mut segment, mut kind) = (Vec::new(), Vec::new());
    for (si, r) in shape.segments.iter().enumerate() {
        connectivity.extend(r.clone().map(|i| i as u64));
        offsets.push(connectivity.len() as u64);
        types.push(CellType::PolyLine);
        segment.push(si as i32);
        kind.push(0i32);
    }
    for (j, r) in shape.segments.iter().skip(1).enumerate() {
        connectivity.push(r.start as u64);
        offsets.push(connectivity.len() as u64);
        types.push(CellType::Vertex);
        segment.push(j as i32 + 1);
        kind.push(1);
    }
    connectivity.push(n as u64);
    offsets.push(connectivity.len() as u64);
    types.push(CellType::Vertex);
    segment.push(-1);
    kind.push(2);
    for (j, m) in look.masses.iter().enumerate() {
        connectivity.push((n + 1 + j) as u64);
        offsets.push(connectivity.len() as u64);
        types.push(CellType::Vertex);
        segment.push(m.segment as i32);
        kind.push(3);
    }
    debug_assert_eq!(types.len(), shape.segments.len() + extra);
    let vector = |name: &str, data: Vec<f64>| {
        Attribute::DataArray(DataArray {
            name: name.into(),
            elem: ElementType::Vectors,
            data: data.into(),
        })
    };
    let scalar = |name: &str, data: Vec<f64>| {
        Attribute::DataArray(DataArray::scalars(name, 1).with_data(data))
    };
    let [velocity, tangent, section_y, section_z] = vectors;
    let [axial, curvature, curvature_y, curvature_z, twist, arc, radius, stress] = scalars;
    let point = vec![
        vector("velocity", velocity),
        vector("tangent", tangent),
        vector("section_y", section_y),
        vector("section_z", section_z),
        scalar("axial_strain", axial),
        scalar("curvature", curvature),
        scalar("curvature_y", curvature_y),
        scalar("curvature_z", curvature_z),
        scalar("twist", twist),
        scalar("arc", arc),
        scalar("radius", radius),
        scalar("stress", stress),
    ];
    let cell = vec![
        Attribute::DataArray(DataArray::scalars("segment", 1).with_data(segment)),
        Attribute::DataArray(DataArray::scalars("kind", 1).with_data(kind)),
    ];
    Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: points.into(),
            cells: Cells {
                cell_verts: VertexNumbers::XML {
                    connectivity,
                    offsets,
                },
                types,
            },
            data: Attributes { point, cell },
        }),
    }
}

/// A ParaView time series being written: `DIR/STEM_000000.vtu`, … and `DIR/STEM.pvd`.
///
/// Every file is written whole or not at all ([`write_atomic`]: a temporary file renamed into
/// place, never through a symlink). The first piece is written in line, so that a directory or
/// name that cannot be written fails at once; the later pieces are encoded and written by a
/// writer thread of the series (joined by [`Series::finish`] and on drop), so the simulation goes
/// on while they are written, and a write that failed is reported by the next call
/// ([`Series::write`] or [`Series::poll`]). With a byte limit ([`Series::with_limit`]) no piece is
/// started that could take the series' files past it.
#[derive(Debug)]
pub struct Series {
    dir: PathBuf,
    stem: String,
    look: Look,
    /// The time [s] of each piece listed; piece `k` is `STEM_{k:06}.vtu`.
    times: Vec<f64>,
    writer: Option<Writer>,
    /// Size of each piece file on disk [bytes] by number (0: being written), as far as written
    /// (a rollback's pieces beyond the list stay on disk until written again).
    sizes: Vec<u64>,
    /// Their sum [bytes].
    bytes: u64,
    /// The largest piece written [bytes]: the estimate of the next.
    largest: u64,
    /// At most this many bytes of pieces on disk.
    limit: u64,
    /// A piece was refused for the limit: none is written any more.
    full: bool,
}

/// The writer thread: (number, path, shape) in, (number, bytes written or the failure) out.
#[derive(Debug)]
struct Writer {
    send: std::sync::mpsc::SyncSender<(usize, PathBuf, Shape)>,
    done: std::sync::mpsc::Receiver<(usize, Result<u64, ViewError>)>,
    thread: std::thread::JoinHandle<()>,
}

/// Pieces queued for the writer thread at most (the memory of a series being written is
/// bounded by this many shapes).
const QUEUED_PIECES: usize = 64;

impl Series {
    /// A series in `dir` (created if missing) of files named `stem`, dressed by `look`.
    pub fn create(dir: &Path, stem: &str, look: Look) -> Result<Self, ViewError> {
        std::fs::create_dir_all(dir).map_err(ViewError::io(dir))?;
        Ok(Self {
            dir: dir.to_path_buf(),
            stem: stem.to_string(),
            look,
            times: Vec::new(),
            writer: None,
            sizes: Vec::new(),
            bytes: 0,
            largest: 0,
            limit: u64::MAX,
            full: false,
        })
    }

    /// This series with at most `limit` bytes of pieces on disk.
    pub fn with_limit(mut self, limit: u64) -> Self {
        self.limit = limit;
        self
    }

    /// Sets the byte limit of the pieces on disk (it applies from the next piece on).
    pub fn set_limit(&mut self, limit: u64) {
        self.limit = limit;
    }

    /// The `.pvd` file's path.
    pub fn collection(&self) -> PathBuf {
        self.dir.join(format!("{}.pvd", self.stem))
    }

    /// Number of pieces listed.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether no piece is listed.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Bytes of the pieces on disk, as far as they are written.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// Whether a piece was refused for the byte limit (none is written any more).
    pub fn is_full(&self) -> bool {
        self.full
    }

    /// Writes the shape at `time` [s] as the next piece; `Ok(false)` if it was not written
    /// because it could take the series past its byte limit (from then on none is). A time not
    /// after the last one (a host's rollback or reset) first drops the pieces at or after it
    /// from the collection. An error is this piece's (written in line) or an earlier piece's
    /// that failed to write.
    pub fn write(&mut self, time: f64, shape: &Shape) -> Result<bool, ViewError> {
        self.poll()?;
        if self.full {
            return Ok(false);
        }
        while self.times.last().is_some_and(|t| *t >= time) {
            self.times.pop();
        }
        let k = self.times.len();
        // every piece at most the largest so far: the files after this one
        let slots = self.sizes.len().max(k + 1) as u64;
        if slots.saturating_mul(self.largest) > self.limit {
            self.full = true;
            return Ok(false);
        }
        let path = self.dir.join(format!("{}_{:06}.vtu", self.stem, k));
        if self.sizes.is_empty() {
            // the first piece in line: a directory or name that cannot be written fails now
            // (and it measures the pieces for the limit)
            let n = write_piece(&path, shape, &self.look)?;
            if n > self.limit {
                let _ = std::fs::remove_file(&path);
                self.full = true;
                return Ok(false);
            }
            self.sized(k, n);
        } else {
            if self.writer.is_none() {
                self.writer = Some(self.spawn()?);
            }
            if k >= self.sizes.len() {
                self.sizes.resize(k + 1, 0);
            }
            let w = self.writer.as_ref().expect("started above");
            if w.send.send((k, path.clone(), shape.clone())).is_err() {
                // the thread is gone: write in line
                let n = write_piece(&path, shape, &self.look)?;
                self.sized(k, n);
            }
        }
        self.times.push(time);
        Ok(true)
    }

    /// Piece `k` is on disk with `n` bytes.
    fn sized(&mut self, k: usize, n: u64) {
        if k >= self.sizes.len() {
            self.sizes.resize(k + 1, 0);
        }
        self.bytes = self.bytes - self.sizes[k] + n;
        self.sizes[k] = n;
        self.largest = self.largest.max(n);
    }

    fn spawn(&self) -> Result<Writer, ViewError> {
        let (send, recv) = std::sync::mpsc::sync_channel::<(usize, PathBuf, Shape)>(QUEUED_PIECES);
        let (report, done) = std::sync::mpsc::channel();
        let look = self.look.clone();
        let thread = std::thread::Builder::new()
            .name("hybeam-vtk".into())
            .spawn(move || {
                for (k, path, shape) in recv {
                    let _ = report.send((k, write_piece(&path, &shape, &look)));
                }
            })
            .map_err(ViewError::io(&self.dir))?;
        Ok(Writer { send, done, thread })
    }

    /// Takes the writer thread's reports: the first failure since the last call, if any.
    pub fn poll(&mut self) -> Result<(), ViewError> {
        let mut failure = None;
        while let Some(Ok((k, r))) = self.writer.as_ref().map(|w| w.done.try_recv()) {
            match r {
                Ok(n) => self.sized(k, n),
                Err(e) => {
                    failure.get_or_insert(e);
                }
            }
        }
        failure.map_or(Ok(()), Err)
    }

    /// Waits until every piece is written.
    fn flush(&mut self) -> Result<(), ViewError> {
        let Some(w) = self.writer.take() else {
            return Ok(());
        };
        drop(w.send);
        let _ = w.thread.join();
        let mut failure = None;
        for (k, r) in w.done.try_iter() {
            match r {
                Ok(n) => self.sized(k, n),
                Err(e) => {
                    failure.get_or_insert(e);
                }
            }
        }
        failure.map_or(Ok(()), Err)
    }

    /// Writes every pending piece and (or rewrites) the `.pvd` collection of the pieces listed
    /// so far; the series can go on after it.
    pub fn finish(&mut self) -> Result<PathBuf, ViewError> {
        self.flush()?;
        let path = self.collection();
        let names = (0..self.times.len()).map(|k| format!("{}_{:06}.vtu", self.stem, k));
        let entries: Vec<(f64, String)> = self.times.iter().copied().zip(names).collect();
        let xml = collection_xml(&entries).map_err(ViewError::io(&path))?;
        write_atomic(&path, &xml)?;
        Ok(path)
    }
}

impl Drop for Series {
    fn drop(&mut self) {
        let _ = self.flush();
    }
}

/// Writes one piece to `path` ([`write_atomic`]); returns its size [bytes].
fn write_piece(path: &Path, shape: &Shape, look: &Look) -> Result<u64, ViewError> {
    let mut bytes = Vec::new();
    piece(shape, look)
        .write_xml(&mut bytes)
        .map_err(|e| ViewError::Vtk {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    write_atomic(path, &bytes)?;
    Ok(bytes.len() as u64)
}

/// Writes `bytes` to `path` whole or not at all: into a new temporary file beside it (created
/// exclusively, so never through a symlink; readable as a file created by `std::fs::write`),
/// then renamed over `path` (a symlink there is replaced, not followed). On failure the
/// temporary file is removed and the error is the operating system's, in words ("No space
/// left on device").
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), ViewError> {
    use std::io::Write as _;
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut builder = tempfile::Builder::new();
    builder.prefix(".hybeam-").suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        // as std::fs::write creates files (the umask applies)
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut file = builder.tempfile_in(dir).map_err(ViewError::io(path))?;
    file.write_all(bytes)
        .and_then(|()| file.flush())
        .map_err(ViewError::io(path))?;
    file.persist(path).map_err(|e| ViewError::Io {
        path: path.to_path_buf(),
        source: e.error,
    })?;
    Ok(())
}

/// The `.pvd` text of `entries` (time, file name).
fn collection_xml(entries: &[(f64, String)]) -> std::io::Result<Vec<u8>> {
    let mut w = quick_xml::Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", None, None)))?;
    w.write_event(Event::Start(BytesStart::new("VTKFile").with_attributes([
        ("type", "Collection"),
        ("version", "0.1"),
        ("byte_order", "LittleEndian"),
    ])))?;
    w.write_event(Event::Start(BytesStart::new("Collection")))?;
    for (t, file) in entries {
        let t = format!("{t:.17e}");
        w.write_event(Event::Empty(BytesStart::new("DataSet").with_attributes([
            ("timestep", t.as_str()),
            ("group", ""),
            ("part", "0"),
            ("file", file.as_str()),
        ])))?;
    }
    w.write_event(Event::End(BytesEnd::new("Collection")))?;
    w.write_event(Event::End(BytesEnd::new("VTKFile")))?;
    let mut out = w.into_inner();
    out.push(b'\n');
    Ok(out)
}

/// The (time [s], piece path) entries of a `.pvd` collection, in file order.
pub fn read_collection(pvd: &Path) -> Result<Vec<(f64, PathBuf)>, ViewError> {
    let text = std::fs::read_to_string(pvd).map_err(ViewError::io(pvd))?;
    let bad = |message: String| ViewError::Format {
        path: pvd.to_path_buf(),
        message,
    };
    let dir = pvd.parent().unwrap_or(Path::new("."));
    let mut reader = quick_xml::Reader::from_str(&text);
    let mut out = Vec::new();
    loop {
        match reader.read_event() {
            Ok(Event::Empty(e) | Event::Start(e)) if e.name().as_ref() == "DataSet" => {
                let (mut t, mut file) = (None, None);
                for a in e.attributes() {
                    let a = a.map_err(|e| bad(e.to_string()))?;
                    let v = a
                        .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                        .map_err(|e| bad(e.to_string()))?
                        .to_string();
                    match a.key.as_ref() {
                        "timestep" => t = v.parse::<f64>().ok(),
                        "file" => file = Some(v),
                        _ => {}
                    }
                }
                match (t, file) {
                    (Some(t), Some(f)) => out.push((t, dir.join(f))),
                    _ => return Err(bad("a DataSet without timestep or file".into())),
                }
            }
            Ok(Event::Eof) => break,
            Err(e) => return Err(bad(e.to_string())),
            _ => {}
        }
    }
    Ok(out)
}
