//! The real-time mode through the C ABI (issue 41 §3): a step its fixed Newton iterations
//! cannot converge returns fmi2Discard with the increment in the message and keeps the last
//! good state; the host decides.

mod host;

use host::*;

#[test]
fn an_unconverged_realtime_step_is_discarded_and_the_state_kept() {
    // one Newton iteration per 1 ms step: the first step's increment is far above the bound
    let scene = SCENE.replace(
        "max_step = 1e-4",
        "max_step = 1e-3\nmode = \"realtime\"\nrealtime_iterations = 1",
    );
    assert!(scene.contains("realtime_iterations = 1"));
    let inst = initialized_with(&scene, "realtime-discard");
    let y = vr_in(&scene, "tip.position.y");
    let before = inst.get1(y);
    assert_eq!(inst.do_step(0.0, 1e-3), DISCARD);
    inst.log.assert_last(
        DISCARD,
        "logStatusDiscard",
        &["real-time", "solver.realtime_bound", "x tolerance"],
    );
    assert_eq!(inst.get1(y), before, "the state moved on a discarded step");
    assert_eq!(inst.last_successful_time(), (OK, 0.0));
    // with enough iterations the same step goes through
    let ok = SCENE.replace("max_step = 1e-4", "max_step = 1e-3\nmode = \"realtime\"");
    let inst = initialized_with(&ok, "realtime-ok");
    assert_eq!(inst.do_step(0.0, 1e-3), OK);
}

/// The mode as an FMU parameter (`solver.realtime_iterations`, set before initialization):
/// 0 the normal mode, k the real-time mode with k iterations; a non-integer is refused naming
/// the field.
#[test]
fn the_realtime_mode_is_a_parameter() {
    let it = vr_in(SCENE, "solver.realtime_iterations");
    let h = vr_in(SCENE, "solver.max_step");
    let inst = in_initialization(SCENE, "realtime-parameter");
    assert_eq!(
        inst.get1(it),
        0.0,
        "the shipped scene is in the normal mode"
    );
    assert_eq!(inst.set_real(&[it], &[2.5]), ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &["solver.realtime_iterations = 2.5"],
    );
    // one iteration per 1 ms step: refused at the first step, as in the scene file
    assert_eq!(inst.set_real(&[it, h], &[1.0, 1e-3]), OK);
    assert_eq!(inst.get1(it), 1.0);
    assert_eq!(inst.exit_init(), OK);
    assert_eq!(inst.do_step(0.0, 1e-3), DISCARD);
    inst.log
        .assert_last(DISCARD, "logStatusDiscard", &["solver.realtime_bound"]);
}
