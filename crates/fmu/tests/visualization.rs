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
    let args = InstantiateArgs {
        name: name.into(),
        ..InstantiateArgs::valid(name)
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
