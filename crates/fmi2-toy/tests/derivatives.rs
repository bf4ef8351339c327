//! The FMI layer's optional calls through the toy (a 2D mass on a spring-damper, force input
//! F, internal step 1 ms): input derivatives, output derivatives, directional derivatives and
//! the ModelStructure they are declared in, each against an independent reference.

use fmi2::log::Logger;
use fmi2::types::Status;
use fmi2::{CoSimModel, Instance};
use fmi2_toy::Toy;

const SCENE: &str = include_str!("../toy.toml");
const FORCE_X: u32 = 10;
const POS_X: u32 = 20;
const VEL_X: u32 = 22;
const ACC_X: u32 = 25;
const ACC_Y: u32 = 26;
const MASS: u32 = 0;

fn started() -> Instance<Toy> {
    let model = Toy::from_resource(SCENE).unwrap();
    let mut i = Instance::new("toy", Logger::memory(), true, "{g}".into(), model).unwrap();
    assert_eq!(i.setup_experiment(None, 0.0, None), Status::Ok);
    assert_eq!(i.enter_initialization_mode(), Status::Ok);
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    i
}

fn get(i: &Instance<Toy>, vr: u32) -> f64 {
    let mut v = [f64::NAN];
    assert_eq!(i.get_real(&[vr], &mut v), Status::Ok);
    v[0]
}

/// A step of 0.1 s with F(τ) = F0 + F1 τ + ½F2 τ² given as input derivatives equals 100 host
/// steps of 1 ms (the toy's internal step) with F set to that polynomial at each step start.
#[test]
fn input_derivatives_equal_the_sub_stepped_polynomial() {
    let (f0, f1, f2) = (3.0, -20.0, 150.0);
    let mut a = started();
    assert_eq!(a.set_real(&[FORCE_X], &[f0]), Status::Ok);
    assert_eq!(
        a.set_real_input_derivatives(&[FORCE_X, FORCE_X], &[1, 2], &[f1, f2]),
        Status::Ok
    );
    assert_eq!(a.do_step(0.0, 0.1), Status::Ok);
    let mut b = started();
    let dt = 0.1 / 100.0;
    for k in 0..100 {
        let tau = k as f64 * dt;
        let f = f0 + f1 * tau + 0.5 * f2 * tau * tau;
        assert_eq!(b.set_real(&[FORCE_X], &[f]), Status::Ok);
        assert_eq!(b.do_step(tau, dt), Status::Ok);
    }
    for vr in [POS_X, VEL_X] {
        let (x, y) = (get(&a, vr), get(&b, vr));
        assert!(
            (x - y).abs() <= 1e-14 * y.abs().max(1.0),
            "vr {vr}: {x} vs {y}"
        );
    }
    // without the derivatives the step differs by far more (the reference is not trivial)
    let mut c = started();
    assert_eq!(c.set_real(&[FORCE_X], &[f0]), Status::Ok);
    assert_eq!(c.do_step(0.0, 0.1), Status::Ok);
    assert!((get(&c, POS_X) - get(&b, POS_X)).abs() > 1e-4);
    // the derivatives held for that step only: the next step uses a constant force
    let mut d = a;
    let mut e = b;
    assert_eq!(d.do_step(0.1, 0.05), Status::Ok);
    assert_eq!(e.set_real(&[FORCE_X], &[f0]), Status::Ok);
    assert_eq!(e.do_step(0.1, 0.05), Status::Ok);
    assert!((get(&d, POS_X) - get(&e, POS_X)).abs() <= 1e-14);
}

/// Output derivatives are those of the continuous model: x′ = v, x″ = v′ = a, checked
/// against the outputs themselves and against a central difference of a short free run.
#[test]
fn output_derivatives_are_the_model_derivatives() {
    let mut i = started();
    assert_eq!(i.set_real(&[FORCE_X], &[2.0]), Status::Ok);
    assert_eq!(i.do_step(0.0, 0.05), Status::Ok);
    let mut d = [0.0; 4];
    assert_eq!(
        i.get_real_output_derivatives(&[POS_X, POS_X, VEL_X, ACC_X], &[1, 2, 1, 1], &mut d),
        Status::Ok
    );
    assert_eq!(d[0], get(&i, VEL_X));
    assert_eq!(d[1], get(&i, ACC_X));
    assert_eq!(d[2], get(&i, ACC_X));
    // a′ = (F′ − k v − c a)/m with F′ = 0: against the acceleration output 1 ms either side
    // (the toy's internal step; semi-implicit Euler is first order, so the check is loose)
    let state = i.get_fmu_state().unwrap();
    let a0 = get(&i, ACC_X);
    assert_eq!(i.do_step(0.05, 1e-3), Status::Ok);
    let a_plus = get(&i, ACC_X);
    assert_eq!(i.set_fmu_state(&state), Status::Ok);
    let fd = (a_plus - a0) / 1e-3;
    assert!(
        (fd - d[3]).abs() < 0.05 * d[3].abs().max(1.0),
        "a′ {} vs {fd}",
        d[3]
    );
    // orders beyond maxOutputDerivativeOrder and non-outputs are errors
    let mut out = [0.0];
    assert_eq!(
        i.get_real_output_derivatives(&[POS_X], &[3], &mut out),
        Status::Error
    );
    assert_eq!(
        i.get_real_output_derivatives(&[FORCE_X], &[1], &mut out),
        Status::Error
    );
    assert_eq!(
        i.set_real_input_derivatives(&[POS_X], &[1], &[1.0]),
        Status::Error
    );
    assert_eq!(
        i.set_real_input_derivatives(&[FORCE_X], &[3], &[1.0]),
        Status::Error
    );
    assert_eq!(
        i.set_real_input_derivatives(&[FORCE_X], &[1], &[f64::NAN]),
        Status::Error
    );
}

/// The directional derivative of the acceleration outputs with respect to the force inputs
/// (declared direct dependencies) against a central difference through fmi2SetReal and
/// fmi2GetReal; undeclared pairs are zero.
#[test]
fn directional_derivative_matches_finite_differences() {
    let mut i = started();
    assert_eq!(
        i.set_real(&[MASS], &[2.5]),
        Status::Error,
        "mass is fixed after init"
    );
    assert_eq!(i.set_real(&[FORCE_X], &[1.0]), Status::Ok);
    assert_eq!(i.do_step(0.0, 0.02), Status::Ok);
    let mut dv = [f64::NAN; 3];
    assert_eq!(
        i.get_directional_derivative(&[ACC_X, ACC_Y, POS_X], &[FORCE_X], &[0.7], &mut dv),
        Status::Ok
    );
    let h = 1e-3;
    let at = |i: &mut Instance<Toy>, f: f64| {
        assert_eq!(i.set_real(&[FORCE_X], &[f]), Status::Ok);
        [get(i, ACC_X), get(i, ACC_Y), get(i, POS_X)]
    };
    let (p, m) = (at(&mut i, 1.0 + h), at(&mut i, 1.0 - h));
    for k in 0..3 {
        let fd = 0.7 * (p[k] - m[k]) / (2.0 * h);
        assert!((dv[k] - fd).abs() <= 1e-9, "unknown {k}: {} vs {fd}", dv[k]);
    }
    assert!((dv[0] - 0.7).abs() < 1e-15, "∂a/∂F = 1/m with m = 1 kg");
    // a known that is not an input, an unknown that is not an output: errors
    assert_eq!(
        i.get_directional_derivative(&[ACC_X], &[POS_X], &[1.0], &mut dv[..1]),
        Status::Error
    );
    assert_eq!(
        i.get_directional_derivative(&[FORCE_X], &[FORCE_X], &[1.0], &mut dv[..1]),
        Status::Error
    );
}

/// modelDescription.xml declares the capabilities and exactly the direct dependencies.
#[test]
fn model_structure_lists_the_direct_dependencies() {
    let model = Toy::from_resource(SCENE).unwrap();
    let xml = fmi2::xml::model_description_of(&model, "toy", "{g}").unwrap();
    for attr in [
        r#"canInterpolateInputs="true""#,
        r#"maxOutputDerivativeOrder="2""#,
        r#"providesDirectionalDerivative="true""#,
    ] {
        assert!(xml.contains(attr), "{attr} missing");
    }
    let index = |vr: u32| model.variables().iter().position(|v| v.vr == vr).unwrap() + 1;
    let acc = format!(
        r#"<Unknown index="{}" dependencies="{}" dependenciesKind="dependent"/>"#,
        index(ACC_X),
        index(FORCE_X)
    );
    assert!(xml.contains(&acc), "{acc} missing in\n{xml}");
    let pos = format!(r#"<Unknown index="{}" dependencies=""/>"#, index(POS_X));
    assert!(xml.contains(&pos), "{pos} missing");
}
