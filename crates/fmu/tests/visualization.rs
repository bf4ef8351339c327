//! The String parameter `visualization.directory` through the C ABI of the built cdylib (see
//! `host/mod.rs`): the ParaView series and the animation page written at the communication
//! points, outputs bit-identical to a run without, a directory that cannot be written is a
//! warning, rollback and reset, and the String calls' argument checks.

mod host;

use std::path::{Path, PathBuf};
use std::ptr;

use fmi2::types::*;
use fmi2::{Causality, CoSimModel};
use host::*;

const H: f64 = 0.01;

/// Value reference of `visualization.directory`.
fn dir_vr() -> u32 {
    let model = hybeam_fmu::FmuModel::from_resource(SCENE).unwrap();
    model
        .string_variables()
        .iter()
        .find(|v| v.name == "visualization.directory")
        .expect("the String parameter")
        .vr
}

/// An instance named `name` with `visualization.directory` = `dir` (unset if `None`), set up at
/// t = 0 and in initialization mode.
fn instance(name: &str, dir: Option<&Path>) -> Inst {
    // the resources' folder is named after at most the name's first 32 characters
    let tag: String = name.chars().take(32).collect();
    let args = InstantiateArgs {
        name: name.into(),
        ..InstantiateArgs::valid(&tag)
    };
    let (c, log) = instantiate_raw(&args);
    assert!(!c.is_null(), "{:?}", log.entries());
    let i = Inst { c, log, api: api() };
    if let Some(d) = dir {
        assert_eq!(i.set_string(&[dir_vr()], &[d.to_str().unwrap()]), OK);
    }
    assert_eq!(i.setup(0.0, None), OK);
    assert_eq!(i.enter_init(), OK);
    i
}

/// Steps `from..to` (t = k·h) under a varying tip force; every step must return `expect`.
/// Returns the outputs after each step.
fn steps(i: &Inst, from: usize, to: usize) -> Vec<Vec<u64>> {
    let outs = vrs_where(|v| v.causality == Causality::Output);
    let force = [vr("tip.force.x"), vr("tip.force.y")];
    (from..to)
        .map(|k| {
            let fy = 0.01 * (k as f64 * 0.2).sin();
            assert_eq!(i.set_real(&force, &[0.02, fy]), OK);
            assert_eq!(i.do_step(k as f64 * H, H), OK, "{:?}", i.log.entries());
            let row = i.get_real(&outs).unwrap();
            row.iter().map(|x| x.to_bits()).collect()
        })
        .collect()
}

/// The (time, piece) entries of `DIR/STEM.pvd`.
fn collection(dir: &Path, stem: &str) -> Vec<(f64, PathBuf)> {
    hybeam_view::vtk::read_collection(&dir.join(format!("{stem}.pvd"))).unwrap()
}

/// The times of the pieces of `DIR/STEM.pvd`.
fn written(dir: &Path, stem: &str) -> Vec<f64> {
    collection(dir, stem).iter().map(|e| e.0).collect()
}

/// [`instance`], initialized (fmi2OK: the initial piece was written, or no directory).
fn started(name: &str, dir: Option<&Path>) -> Inst {
    let i = instance(name, dir);
    assert_eq!(i.exit_init(), OK, "{:?}", i.log.entries());
    i
}

/// The times a run of steps `0..n` writes: the start, then each step's end `t + h`.
fn times(n: usize) -> Vec<f64> {
    std::iter::once(0.0)
        .chain((0..n).map(|k| k as f64 * H + H))
        .collect()
}

#[test]
fn writes_the_series_and_the_page_and_changes_no_output() {
    let dir = temp_dir("vis").join("views (new)");
    let on = started("beam #1", Some(&dir));
    let off = started("beam-off", None);
    assert_eq!(on.get_string(&[dir_vr()]).unwrap(), [dir.to_str().unwrap()]);
    assert_eq!(off.get_string(&[dir_vr()]).unwrap(), [""]);
    assert_eq!(
        steps(&on, 0, 50),
        steps(&off, 0, 50),
        "outputs bit-identical"
    );
    assert_eq!(on.terminate(), OK);
    assert_eq!(off.terminate(), OK);
    // the stem is the instance name with characters outside [A-Za-z0-9_-] replaced by _
    let entries = collection(&dir, "beam__1");
    let written: Vec<f64> = entries.iter().map(|e| e.0).collect();
    assert_eq!(written, times(50));
    for (_, piece) in &entries {
        assert!(piece.is_file(), "{}", piece.display());
    }
    let page = std::fs::read_to_string(dir.join("beam__1.html")).unwrap();
    assert!(page.contains("FMU instance beam__1"));
    assert!(page.contains("tip.position.x") && page.contains("\"times\""));
    assert!(page.len() > 100_000, "the viewer and the frames");
    on.assert_no_problems();
    off.assert_no_problems();
}

#[test]
fn an_unwritable_directory_is_a_warning_and_changes_no_output() {
    let base = temp_dir("vis-bad");
    let file = base.join("a-file");
    std::fs::write(&file, "not a directory").unwrap();
    let bad = instance("bad", Some(&file.join("views")));
    assert_eq!(bad.exit_init(), WARNING);
    bad.log.assert_last(
        WARNING,
        "logStatusWarning",
        &[
            "fmi2ExitInitializationMode",
            "visualization.directory",
            "visualization is off for the rest of this run",
        ],
    );
    let off = started("off", None);
    // once only: the steps return fmi2OK
    assert_eq!(steps(&bad, 0, 20), steps(&off, 0, 20));
    assert_eq!(bad.terminate(), OK);
    let warnings = bad
        .log
        .entries()
        .iter()
        .filter(|e| e.status == WARNING)
        .count();
    assert_eq!(warnings, 1);
}

#[test]
fn rollback_drops_the_later_pieces_and_reset_starts_a_new_series() {
    let dir = temp_dir("vis-rollback");
    let i = started("roll", Some(&dir));
    steps(&i, 0, 10);
    let mut saved = i.get_state();
    steps(&i, 10, 20);
    assert_eq!(i.set_state(saved), OK);
    steps(&i, 10, 15);
    assert_eq!(i.free_state(&mut saved), OK);
    assert_eq!(i.terminate(), OK);
    assert_eq!(written(&dir, "roll"), times(15));
    // fmi2Reset: the parameter is back to its start (off) until set again; a new series
    assert_eq!(i.reset(), OK);
    assert_eq!(i.setup(0.0, None), OK);
    assert_eq!(i.enter_init(), OK);
    assert_eq!(i.get_string(&[dir_vr()]).unwrap(), [""]);
    assert_eq!(i.set_string(&[dir_vr()], &[dir.to_str().unwrap()]), OK);
    assert_eq!(i.exit_init(), OK);
    steps(&i, 0, 5);
    assert_eq!(i.terminate(), OK);
    assert_eq!(written(&dir, "roll"), times(5));
    i.assert_no_problems();
}

#[test]
fn free_instance_without_terminate_writes_the_collection() {
    let dir = temp_dir("vis-free");
    let i = started("freed", Some(&dir));
    steps(&i, 0, 3);
    drop(i);
    assert_eq!(written(&dir, "freed"), times(3));
    assert!(dir.join("freed.html").is_file());
}

#[test]
fn string_calls_check_their_arguments() {
    let i = Inst::new("vis-args");
    let r = dir_vr();
    let api = i.api;
    // in initialization mode: both set and get are allowed
    assert_eq!(i.setup(0.0, None), OK);
    assert_eq!(i.enter_init(), OK);
    // a NULL value pointer
    let values: [fmi2String; 1] = [ptr::null()];
    let status = unsafe { api.set_string.unwrap()(i.c, [r].as_ptr(), 1, values.as_ptr()) };
    assert_eq!(status, ERROR);
    i.log.assert_last(
        ERROR,
        "logStatusError",
        &["fmi2SetString", "value[0] is NULL"],
    );
    // a NULL value array, a NULL output array
    let status = unsafe { api.set_string.unwrap()(i.c, [r].as_ptr(), 1, ptr::null()) };
    assert_eq!(status, ERROR);
    let status = unsafe { api.get_string.unwrap()(i.c, [r].as_ptr(), 1, ptr::null_mut()) };
    assert_eq!(status, ERROR);
    // unknown and Real value references
    assert_eq!(i.set_string(&[999_999], &["x"]), ERROR);
    i.log.assert_last(
        ERROR,
        "logStatusError",
        &["value reference 999999 is not a variable"],
    );
    let real = vr("tip.force.x");
    assert_eq!(i.set_string(&[real], &["x"]), ERROR);
    i.log.assert_last(
        ERROR,
        "logStatusError",
        &["tip.force.x, a Real variable, not a String variable"],
    );
    assert_eq!(i.get_string(&[real]), Err(ERROR));
    i.log.assert_last(
        ERROR,
        "logStatusError",
        &["fmi2GetString", "a Real variable, not a String variable"],
    );
    assert_eq!(i.get_real(&[r]), Err(ERROR));
    i.log.assert_last(
        ERROR,
        "logStatusError",
        &["visualization.directory, a String variable, not a Real variable"],
    );
    // nothing was set by the refused calls; the value is a copy of the host's
    assert_eq!(i.get_string(&[r]).unwrap(), [""]);
    assert_eq!(i.set_string(&[r], &["somewhere"]), OK);
    assert_eq!(i.get_string(&[r, r]).unwrap(), ["somewhere", "somewhere"]);
    // fixed: not after fmi2ExitInitializationMode
    assert_eq!(i.set_string(&[r], &[""]), OK);
    assert_eq!(i.exit_init(), OK);
    assert_eq!(i.set_string(&[r], &["later"]), ERROR);
    i.log
        .assert_last(ERROR, "logStatusError", &["is a fixed parameter"]);
    assert_eq!(i.get_string(&[r]).unwrap(), [""]);
}

#[test]
fn instances_in_parallel_threads_write_their_own_series() {
    use fmi2::{log::Logger, Instance, Status};
    let dir = temp_dir("vis-threads");
    let threads: Vec<_> = (0..4)
        .map(|n| {
            let dir = dir.clone();
            std::thread::spawn(move || {
                let model = hybeam_fmu::FmuModel::from_resource(SCENE).unwrap();
                let name = format!("thread {n}");
                let mut i =
                    Instance::new(&name, Logger::memory(), false, guid_of(SCENE), model).unwrap();
                let value = dir.to_str().unwrap();
                assert_eq!(i.set_string(&[dir_vr()], &[value]), Status::Ok);
                assert_eq!(i.enter_initialization_mode(), Status::Ok);
                assert_eq!(i.exit_initialization_mode(), Status::Ok);
                for k in 0..(10 + n) {
                    assert_eq!(i.do_step(k as f64 * H, H), Status::Ok);
                }
                assert_eq!(i.terminate(), Status::Ok);
            })
        })
        .collect();
    for t in threads {
        t.join().unwrap();
    }
    for n in 0..4 {
        assert_eq!(written(&dir, &format!("thread_{n}")), times(10 + n));
    }
}

const MAGIC: [u8; 8] = <hybeam_fmu::FmuModel as CoSimModel>::STATE_MAGIC;

/// `state` of instance `i` moved into another directory: its String section names `dir`; with
/// `refuse`, its model part is cut short so that the model refuses it.
fn state_in(i: &Inst, dir: &Path, refuse: bool) -> fmi2FMUstate {
    let mut s = i.get_state();
    let bytes = i.serialize(s);
    assert_eq!(i.free_state(&mut s), OK);
    let guid = guid_of(SCENE);
    let mut st = fmi2::fmu_state::FmuState::deserialize(&bytes, &MAGIC, &guid).unwrap();
    st.strings = vec![dir.to_str().unwrap().to_owned()];
    if refuse {
        st.model.truncate(st.model.len() / 2);
    }
    let (status, p) = i.deserialize(&st.serialize(&MAGIC, &guid));
    assert_eq!(status, OK, "{:?}", i.log.entries());
    p
}

/// V1: a state naming another directory that the model refuses changes nothing: the running
/// series keeps its pieces, its numbering and its first piece's bytes, and the other directory
/// gets nothing.
#[test]
fn a_refused_state_of_another_directory_changes_nothing() {
    let (a_dir, b_dir) = (temp_dir("vis-v1-a"), temp_dir("vis-v1-b"));
    let a = started("v1", Some(&a_dir));
    steps(&a, 0, 10);
    let mut p = state_in(&a, &b_dir, true);
    assert_eq!(a.set_state(p), ERROR);
    assert_eq!(a.free_state(&mut p), OK);
    assert_eq!(
        a.get_string(&[dir_vr()]).unwrap(),
        [a_dir.to_str().unwrap()]
    );
    let first = std::fs::read(a_dir.join("v1_000000.vtu")).unwrap();
    steps(&a, 10, 15);
    assert_eq!(a.terminate(), OK);
    assert_eq!(written(&a_dir, "v1"), times(15));
    assert_eq!(std::fs::read(a_dir.join("v1_000000.vtu")).unwrap(), first);
    assert_eq!(
        std::fs::read_dir(&b_dir).unwrap().count(),
        0,
        "nothing in B"
    );
}

/// V1: a restored state of another directory writes there, and the instance's own state
/// restored after it continues the first series (its numbering and its earlier pieces kept).
#[test]
fn a_series_continues_after_a_visit_to_another_directory() {
    let (a_dir, b_dir) = (temp_dir("vis-v1b-a"), temp_dir("vis-v1b-b"));
    let a = started("v1b", Some(&a_dir));
    steps(&a, 0, 5);
    let mut in_b = state_in(&a, &b_dir, false);
    steps(&a, 5, 10);
    let mut own = a.get_state();
    assert_eq!(a.set_state(in_b), OK, "{:?}", a.log.entries());
    steps(&a, 5, 8);
    assert_eq!(a.set_state(own), OK, "{:?}", a.log.entries());
    steps(&a, 10, 15);
    assert_eq!(a.terminate(), OK);
    assert_eq!(a.free_state(&mut in_b), OK);
    assert_eq!(a.free_state(&mut own), OK);
    assert_eq!(written(&a_dir, "v1b"), times(15));
    let in_b: Vec<f64> = (5..8).map(|k| k as f64 * H + H).collect();
    assert_eq!(written(&b_dir, "v1b"), in_b);
    a.assert_no_problems();
}

/// Value reference of a Real parameter of the views.
fn view_vr(name: &str) -> u32 {
    vr(&format!("visualization.{name}"))
}

/// Steps `from..to` as [`steps`], returning each step's status (fmi2OK or fmi2Warning).
fn statuses(i: &Inst, from: usize, to: usize) -> Vec<fmi2Status> {
    (from..to).map(|k| i.do_step(k as f64 * H, H)).collect()
}

/// The `.vtu` files in `dir` and their sizes.
fn pieces_in(dir: &Path) -> Vec<(PathBuf, u64)> {
    let mut out: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "vtu"))
        .map(|p| {
            let n = std::fs::metadata(&p).unwrap().len();
            (p, n)
        })
        .collect();
    out.sort();
    out
}

/// V2: `visualization.interval` writes a piece only when that much time has passed since the
/// last one; `visualization.max_bytes` stops the pieces before they pass it, with one warning,
/// and the collection lists exactly the pieces on disk.
#[test]
fn the_interval_thins_the_pieces_and_the_byte_cap_stops_them_with_one_warning() {
    let dir = temp_dir("vis-v2");
    let i = instance("every3", Some(&dir));
    for (name, bad) in [
        ("interval", -1.0),
        ("max_bytes", -1.0),
        ("interval", f64::INFINITY),
    ] {
        assert_eq!(i.set_real(&[view_vr(name)], &[bad]), ERROR);
        let last = i.log.last().message;
        assert!(last.contains(&format!("visualization.{name}")), "{last}");
    }
    i.log.clear();
    assert_eq!(i.set_real(&[view_vr("interval")], &[3.0 * H]), OK);
    assert_eq!(i.get_real(&[view_vr("interval")]).unwrap(), [3.0 * H]);
    assert_eq!(i.exit_init(), OK);
    steps(&i, 0, 30);
    assert_eq!(i.terminate(), OK);
    i.assert_no_problems();
    let expect: Vec<f64> = times(30).into_iter().step_by(3).collect();
    assert_eq!(written(&dir, "every3"), expect);
    let size = std::fs::metadata(dir.join("every3_000000.vtu"))
        .unwrap()
        .len();
    // a cap of three and a half pieces
    let cap_dir = temp_dir("vis-v2-cap");
    let c = instance("capped", Some(&cap_dir));
    let cap = 3.5 * size as f64;
    assert_eq!(c.set_real(&[view_vr("max_bytes")], &[cap]), OK);
    assert_eq!(c.exit_init(), OK);
    let st = statuses(&c, 0, 20);
    assert_eq!(c.terminate(), OK);
    let warnings: Vec<_> = c
        .log
        .entries()
        .into_iter()
        .filter(|e| e.status == WARNING)
        .collect();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].message.contains("visualization.max_bytes"),
        "{warnings:?}"
    );
    assert_eq!(st.iter().filter(|s| **s == WARNING).count(), 1, "{st:?}");
    let on_disk = pieces_in(&cap_dir);
    let total: u64 = on_disk.iter().map(|p| p.1).sum();
    assert!(total as f64 <= cap, "{total} bytes written, cap {cap}");
    assert_eq!(on_disk.len(), 3, "{on_disk:?}");
    assert_eq!(written(&cap_dir, "capped"), times(2));
    // the page still holds the whole run
    let page = std::fs::read_to_string(cap_dir.join("capped.html")).unwrap();
    assert!(page.contains("\"times\""));
}

/// Every piece in `dir` is well-formed VTK XML that vtkio reads.
fn assert_whole(dir: &Path) {
    for (p, n) in pieces_in(dir) {
        assert!(n > 0, "{}: empty", p.display());
        hybeam_view::read::read_piece(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    }
}

/// V3: a 4 KiB instance name writes its views under a shortened stem (no late failure).
#[test]
fn a_long_instance_name_writes_its_views_under_a_short_stem() {
    let dir = temp_dir("vis-v3-long");
    let name = "x".repeat(4096);
    let i = started(&name, Some(&dir));
    steps(&i, 0, 3);
    assert_eq!(i.terminate(), OK);
    i.assert_no_problems();
    let pvd: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "pvd"))
        .collect();
    assert_eq!(pvd.len(), 1, "{pvd:?}");
    let stem = pvd[0].file_stem().unwrap().to_str().unwrap().to_owned();
    assert!(stem.starts_with("xxxxxxxx") && stem.len() <= 80, "{stem}");
    assert_eq!(written(&dir, &stem), times(3));
    // a name differing only after the cut gets another stem
    assert_ne!(
        hybeam_fmu::cosim::view::stem_of(&name),
        hybeam_fmu::cosim::view::stem_of(&format!("{name}y"))
    );
}

/// V3: a disk that fills mid-run is a warning naming the OS error in words, on the call after
/// the failure at the latest; no empty or partial piece is left. Needs a small tmpfs (root);
/// where it cannot be mounted the test says so and returns.
#[test]
fn a_full_disk_is_a_warning_in_words_and_leaves_no_partial_piece() {
    let dir = temp_dir("vis-v3-full");
    let mounted = std::process::Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=48k", "tmpfs"])
        .arg(&dir)
        .status()
        .is_ok_and(|s| s.success());
    if !mounted {
        eprintln!(
            "skipped: cannot mount a tmpfs at {} (needs root)",
            dir.display()
        );
        return;
    }
    /// Unmounts the tmpfs whatever the test's outcome.
    struct Mounted(PathBuf);
    impl Drop for Mounted {
        fn drop(&mut self) {
            let _ = std::process::Command::new("umount").arg(&self.0).status();
        }
    }
    let _mounted = Mounted(dir.clone());
    let i = started("full", Some(&dir));
    let mut st = Vec::new();
    for k in 0..10 {
        st.push(i.do_step(k as f64 * H, H));
        // the writer thread has written (or failed) before the next call
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let _ = i.terminate();
    let entries = i.log.entries();
    let warn: Vec<_> = entries.iter().filter(|e| e.status == WARNING).collect();
    assert!(!warn.is_empty(), "{entries:?}");
    assert!(
        warn[0].message.contains("No space left on device"),
        "{:?}",
        warn[0].message
    );
    // the failure was reported on a step, the first after it
    assert!(st.contains(&WARNING), "{st:?}");
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_str().unwrap().starts_with('.'))
        .collect();
    assert_whole(&dir);
    drop(i);
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
}

/// V4: two instances of one name in one directory: every file is whole, the bytes of one of
/// the two runs (each file written under a temporary name and renamed into place).
#[test]
fn two_instances_of_one_name_leave_only_whole_files() {
    let shared = temp_dir("vis-v4");
    let own = [temp_dir("vis-v4-a"), temp_dir("vis-v4-b")];
    let n = 150;
    let run = |dir: PathBuf, force: f64| {
        std::thread::spawn(move || {
            let i = started("twin", Some(&dir));
            let f = [vr("tip.force.x"), vr("tip.force.y")];
            for k in 0..n {
                assert_eq!(i.set_real(&f, &[force, 0.0]), OK);
                assert_eq!(i.do_step(k as f64 * H, H), OK);
            }
            assert_eq!(i.terminate(), OK);
        })
    };
    for (d, f) in own.iter().zip([0.01, 0.02]) {
        run(d.clone(), f).join().unwrap();
    }
    let both = [run(shared.clone(), 0.01), run(shared.clone(), 0.02)];
    // a reader beside them: every piece it finds is whole (a file is never seen half written)
    let partial = {
        let dir = shared.clone();
        let writing = || both.iter().any(|t| !t.is_finished());
        let mut partial = Vec::new();
        while writing() {
            for (p, _) in pieces_in(&dir) {
                if let Ok(bytes) = std::fs::read(&p) {
                    if !bytes.trim_ascii_end().ends_with(b"</VTKFile>") {
                        partial.push((p, bytes.len()));
                    }
                }
            }
        }
        partial
    };
    for t in both {
        t.join().unwrap();
    }
    assert!(partial.is_empty(), "seen half written: {partial:?}");
    assert_whole(&shared);
    for (p, _) in pieces_in(&shared) {
        let name = p.file_name().unwrap();
        let bytes = std::fs::read(&p).unwrap();
        assert!(
            own.iter()
                .any(|d| std::fs::read(d.join(name)).unwrap() == bytes),
            "{}: the bytes of neither run",
            p.display()
        );
    }
}

/// V5: the views never follow a symlink planted in the directory: the file it points to is
/// untouched, a dangling target is not created, and the views are written in its place.
#[cfg(unix)]
#[test]
fn planted_symlinks_are_not_followed() {
    let dir = temp_dir("vis-v5");
    let outside = temp_dir("vis-v5-outside");
    let precious = outside.join("precious.txt");
    std::fs::write(&precious, "keep me").unwrap();
    let dangling = outside.join("created-by-the-fmu");
    for (link, target) in [
        ("sym_000001.vtu", &precious),
        ("sym_000002.vtu", &dangling),
        ("sym.pvd", &precious),
        ("sym.html", &dangling),
    ] {
        std::os::unix::fs::symlink(target, dir.join(link)).unwrap();
    }
    let i = started("sym", Some(&dir));
    steps(&i, 0, 3);
    assert_eq!(i.terminate(), OK);
    i.assert_no_problems();
    assert_eq!(std::fs::read_to_string(&precious).unwrap(), "keep me");
    assert!(
        !dangling.exists(),
        "a dangling symlink's target was created"
    );
    assert_eq!(written(&dir, "sym"), times(3));
    for f in ["sym_000001.vtu", "sym_000002.vtu", "sym.pvd", "sym.html"] {
        let m = std::fs::symlink_metadata(dir.join(f)).unwrap();
        assert!(m.file_type().is_file(), "{f} is a regular file now");
    }
}
