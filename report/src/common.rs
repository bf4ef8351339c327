//! Shared pieces of the report binary: scene loading, timed runs, the reference cache, tables,
//! the machine description and a one-line progress indicator on stderr.

use hybeam::error::SimError;
use hybeam::integrator::Counters;
use hybeam::scene::{Scene, SpaceKind};
use hybeam::simulator::AnySimulator;
use std::fmt::Write as _;
use std::hash::Hasher as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Repository root (where `scenes/` and `docs/` live): the parent of this crate's folder.
pub fn root() -> PathBuf {
    let krate = Path::new(env!("CARGO_MANIFEST_DIR"));
    krate.parent().unwrap_or(krate).to_path_buf()
}

/// Output folder of CSVs, plots and fragments.
pub fn out_dir() -> PathBuf {
    let d = root().join("docs/report");
    let _ = std::fs::create_dir_all(&d);
    d
}

/// `nproc` and CPU model of this machine, for the pages.
pub fn machine() -> String {
    let nproc = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(0);
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    format!("{nproc} cores (`nproc`), CPU `{cpu}` (/proc/cpuinfo), shared with other jobs")
}

/// Overrides as `(key, value)` pairs from `"key=value"` strings.
pub fn sets(items: &[String]) -> Vec<(String, String)> {
    items
        .iter()
        .filter_map(|s| s.split_once('='))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

/// Loads `scenes/<name>.toml` with `key=value` overrides.
pub fn scene(name: &str, overrides: &[String]) -> Result<Scene, String> {
    let path = root().join("scenes").join(format!("{name}.toml"));
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    Scene::from_toml_with_overrides(&text, &sets(overrides)).map_err(|e| format!("{name}: {e}"))
}

/// A run sampled every output chunk.
#[derive(Debug, Clone)]
pub struct Run {
    /// Sample times [s].
    pub t: Vec<f64>,
    /// Tip positions [m], global axes (z = 0 for a planar scene).
    pub tip: Vec<[f64; 3]>,
    /// Wall time [s] (median over repetitions), building the simulator included.
    pub wall: f64,
    /// Work counters at the end.
    pub counters: Counters,
    /// Smallest internal step [s].
    pub min_step: f64,
    /// The refusal, if `advance` returned Err.
    pub err: Option<SimError>,
}

/// The tip position of a state as three components (z = 0 in the plane).
fn tip3(sim: &AnySimulator) -> [f64; 3] {
    let o = sim.outputs();
    let p = o.tip_position();
    [p[0], p[1], p.get(2).copied().unwrap_or(0.0)]
}

/// Simulates to `t_end` in the scene's space, advancing (and sampling) in chunks of `chunk`.
pub fn simulate(scene: &Scene, t_end: f64, chunk: f64) -> Run {
    let start = Instant::now();
    let mut run = Run {
        t: Vec::new(),
        tip: Vec::new(),
        wall: 0.0,
        counters: Counters::default(),
        min_step: f64::INFINITY,
        err: None,
    };
    let mut sim = match AnySimulator::new(scene.clone()) {
        Ok(s) => s,
        Err(e) => {
            run.err = Some(e);
            return run;
        }
    };
    run.t.push(0.0);
    run.tip.push(tip3(&sim));
    let n = (t_end / chunk).round().max(1.0) as usize;
    for k in 1..=n {
        let t = k as f64 * chunk;
        if let Err(e) = sim.advance(t) {
            run.err = Some(e);
            break;
        }
        run.t.push(t);
        run.tip.push(tip3(&sim));
    }
    run.wall = start.elapsed().as_secs_f64();
    run.counters = sim.counters();
    run.min_step = sim.min_step_used();
    run
}

/// [`simulate`] repeated `reps` times; wall time is the median.
pub fn timed(scene: &Scene, t_end: f64, chunk: f64, reps: usize) -> Run {
    let mut walls = Vec::new();
    let mut last = None;
    for _ in 0..reps.max(1) {
        let r = simulate(scene, t_end, chunk);
        walls.push(r.wall);
        let failed = r.err.is_some();
        last = Some(r);
        if failed {
            break;
        }
    }
    let mut r = last.expect("at least one run");
    r.wall = median(&mut walls);
    r
}

/// Median (sorts in place).
pub fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// 64-bit FNV-1a of the bytes of `s` (the cache file names; stable across runs and builds).
fn fnv1a(s: &str) -> u64 {
    let mut h = fnv::FnvHasher::default();
    h.write(s.as_bytes());
    h.finish()
}

/// Bump when the engine changes in a way that invalidates cached references.
const CACHE_VERSION: &str = "v1";

/// A reference tip history, computed once and cached under `target/report-cache/`, keyed by
/// the full scene (after overrides), end time and sampling step. `fresh` recomputes it. The
/// file holds `time,tip.x,tip.y` (planar: the layout of earlier caches, so they stay valid) or
/// `time,tip.x,tip.y,tip.z` (spatial).
pub fn cached(
    label: &str,
    scene: &Scene,
    t_end: f64,
    chunk: f64,
    fresh: bool,
) -> Result<Vec<[f64; 3]>, String> {
    let spatial = scene.space == SpaceKind::Spatial;
    let key = format!(
        "{CACHE_VERSION}\n{}\nt_end={t_end:e}\nchunk={chunk:e}",
        scene.to_toml()
    );
    let dir = root().join("target/report-cache");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let path = dir.join(format!("{label}-{:016x}.csv", fnv1a(&key)));
    if !fresh {
        if let Ok(text) = std::fs::read_to_string(&path) {
            let tip: Vec<[f64; 3]> = text
                .lines()
                .skip(1)
                .filter_map(|l| {
                    let v: Vec<f64> = l.split(',').filter_map(|x| x.parse().ok()).collect();
                    match v.len() {
                        3 if !spatial => Some([v[1], v[2], 0.0]),
                        4 if spatial => Some([v[1], v[2], v[3]]),
                        _ => None,
                    }
                })
                .collect();
            if tip.len() == (t_end / chunk).round() as usize + 1 {
                return Ok(tip);
            }
        }
    }
    eprintln!(
        "  computing reference {label} (cached afterwards in {})",
        path.display()
    );
    let r = simulate(scene, t_end, chunk);
    if let Some(e) = r.err {
        return Err(format!("reference {label} failed: {e}"));
    }
    let mut s = String::from(if spatial {
        "time,tip.x,tip.y,tip.z\n"
    } else {
        "time,tip.x,tip.y\n"
    });
    for (t, p) in r.t.iter().zip(&r.tip) {
        let _ = write!(s, "{t:.9e},{:.17e},{:.17e}", p[0], p[1]);
        if spatial {
            let _ = write!(s, ",{:.17e}", p[2]);
        }
        s.push('\n');
    }
    std::fs::write(&path, s).map_err(|e| e.to_string())?;
    eprintln!("  reference {label}: wall {:.1} s", r.wall);
    Ok(r.tip)
}

/// Writes a CSV file under `docs/report/`.
pub fn write_csv(name: &str, head: &[&str], rows: &[Vec<String>]) -> Result<(), String> {
    let mut s = head.join(",");
    s.push('\n');
    for r in rows {
        s.push_str(&r.join(","));
        s.push('\n');
    }
    let p = out_dir().join(name);
    std::fs::write(&p, s).map_err(|e| format!("cannot write {}: {e}", p.display()))
}

/// Writes a text file under `docs/` (path relative to `docs/`).
pub fn write_doc(rel: &str, text: &str) -> Result<(), String> {
    let p = root().join("docs").join(rel);
    if let Some(d) = p.parent() {
        let _ = std::fs::create_dir_all(d);
    }
    std::fs::write(&p, text).map_err(|e| format!("cannot write {}: {e}", p.display()))
}

/// A markdown table.
pub fn md_table(head: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = format!("| {} |\n|", head.join(" | "));
    for _ in head {
        s.push_str("---|");
    }
    s.push('\n');
    for r in rows {
        let _ = writeln!(s, "| {} |", r.join(" | "));
    }
    s
}

/// `x` in short scientific notation (`–` for NaN).
pub fn e3(x: f64) -> String {
    if x.is_nan() {
        "–".into()
    } else {
        format!("{x:.2e}")
    }
}

/// A one-line progress indicator on stderr.
pub struct Progress {
    label: String,
    total: usize,
    done: usize,
    start: Instant,
}

impl Progress {
    /// Starts a progress line for `total` items.
    pub fn new(label: &str, total: usize) -> Self {
        Self {
            label: label.into(),
            total,
            done: 0,
            start: Instant::now(),
        }
    }

    /// Announces the item about to run.
    pub fn item(&mut self, what: &str) {
        let el = self.start.elapsed().as_secs_f64();
        let eta = if self.done > 0 {
            format!(
                ", ~{:.0} s left",
                el / self.done as f64 * (self.total - self.done) as f64
            )
        } else {
            String::new()
        };
        eprint!(
            "\r\x1b[K[{}] {}/{} ({el:.0} s{eta}) {what}",
            self.label,
            self.done + 1,
            self.total
        );
        self.done += 1;
    }

    /// Ends the line.
    pub fn finish(&self) {
        eprintln!(
            "\r\x1b[K[{}] {} items in {:.1} s",
            self.label,
            self.total,
            self.start.elapsed().as_secs_f64()
        );
    }
}

/// Largest Euclidean distance between two tip histories, and the distance at the end;
/// `stride` picks every stride-th reference sample. Also the largest difference of the
/// vertical component `up` (1 = y in the plane, 2 = z in the spatial scenes).
pub fn tip_errors(
    run: &[[f64; 3]],
    reference: &[[f64; 3]],
    stride: usize,
    up: usize,
) -> (f64, f64, f64) {
    let mut max = 0.0f64;
    let mut max_y = 0.0f64;
    let mut end = f64::NAN;
    for (k, p) in run.iter().enumerate() {
        let Some(r) = reference.get(k * stride) else {
            return (f64::NAN, f64::NAN, f64::NAN);
        };
        let d = ((p[0] - r[0]).powi(2) + (p[1] - r[1]).powi(2) + (p[2] - r[2]).powi(2)).sqrt();
        if !d.is_finite() {
            return (f64::NAN, f64::NAN, f64::NAN);
        }
        max = max.max(d);
        max_y = max_y.max((p[up] - r[up]).abs());
        end = d;
    }
    (max, end, max_y)
}

#[cfg(test)]
mod tests {
    /// The cache keys name files under `target/report-cache/`: the hash must stay FNV-1a 64
    /// (published test vectors of the FNV reference page) so existing caches keep their names.
    #[test]
    fn cache_hash_is_fnv1a_64() {
        assert_eq!(super::fnv1a(""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(super::fnv1a("a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(super::fnv1a("foobar"), 0x8594_4171_f739_67e8);
    }
}
