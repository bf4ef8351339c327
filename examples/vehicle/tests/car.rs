//! The pitch-plane car against independent references: the textbook static equilibrium, the
//! textbook mass and stiffness matrices, its own energy ledger, and finite differences of its
//! mount kinematics, driven through the FMI layer.

use fmi2::log::Logger;
use fmi2::types::Status;
use fmi2::{CoSimModel, Instance};
use hybeam_vehicle::{vr, Vehicle};
use nalgebra::{Matrix4, SymmetricEigen};

const SCENE: &str = include_str!("../vehicle.toml");

/// The shipped car released from free-length springs (not its static start), with `edit`.
fn scene(edit: &[(&str, &str)]) -> String {
    let mut s = SCENE.replace("static_start = true", "static_start = false");
    for (from, to) in edit {
        assert!(s.contains(from), "{from}");
        s = s.replace(from, to);
    }
    s
}

fn started(text: &str) -> Instance<Vehicle> {
    let model = Vehicle::from_resource(text).unwrap();
    let mut i = Instance::new("car", Logger::memory(), true, "{g}".into(), model).unwrap();
    assert_eq!(i.setup_experiment(None, 0.0, None), Status::Ok);
    assert_eq!(i.enter_initialization_mode(), Status::Ok);
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    i
}

fn get(i: &Instance<Vehicle>, r: u32) -> f64 {
    let mut v = [f64::NAN];
    assert_eq!(i.get_real(&[r], &mut v), Status::Ok);
    v[0]
}

/// Released from free-length springs on a flat road, the damped car settles at the static
/// equilibrium: axle loads m g b/(a+b) and m g a/(a+b), springs and tires compressed by
/// load/stiffness.
#[test]
fn settles_at_the_static_equilibrium() {
    let text = scene(&[("bump_height = 0.05", "bump_height = 0.0")]);
    let mut i = started(&text);
    for k in 0..200 {
        assert_eq!(i.do_step(0.1 * k as f64, 0.1), Status::Ok);
    }
    let c = Vehicle::from_resource(&text).unwrap().car;
    let (m, g, a, b) = (c.body.mass, c.solver.gravity, c.body.front, c.body.rear);
    let (pf, pr) = (m * g * b / (a + b), m * g * a / (a + b));
    let wg = c.wheels.mass * g;
    let yf = -(pf + wg) / c.wheels.tire_stiffness;
    let yr = -(pr + wg) / c.wheels.tire_stiffness;
    let (ybf, ybr) = (
        yf - pf / c.suspension.front_stiffness,
        yr - pr / c.suspension.rear_stiffness,
    );
    let heave = (b * ybf + a * ybr) / (a + b);
    let pitch = (ybf - ybr) / (a + b);
    let (h, p) = (get(&i, vr::HEAVE), get(&i, vr::PITCH));
    assert!((h - heave).abs() < 1e-9, "heave {h} vs {heave}");
    assert!((p - pitch).abs() < 1e-9, "pitch {p} vs {pitch}");
    // static_start: the same equilibrium at once, and it stays (1e-9 m over 1 s)
    let text = text.replace("static_start = false", "static_start = true");
    let mut s = started(&text);
    let (h0, p0) = (get(&s, vr::HEAVE), get(&s, vr::PITCH));
    assert!(
        (h0 - heave).abs() < 1e-9 && (p0 - pitch).abs() < 1e-9,
        "{h0} {p0}"
    );
    for k in 0..10 {
        assert_eq!(s.do_step(0.1 * k as f64, 0.1), Status::Ok);
    }
    assert!((get(&s, vr::HEAVE) - heave).abs() < 1e-9);
}

/// The model's stiffness-over-mass block (central differences of its accelerations) equals
/// M⁻¹K of the textbook 4-dof pitch-plane car, and its undamped natural frequencies are the
/// textbook ones (bounce ≈ 1.2 Hz, pitch ≈ 1.3 Hz, wheel hop ≈ 12 Hz).
#[test]
fn stiffness_matrix_and_frequencies_are_the_textbook_ones() {
    let text = scene(&[("bump_height = 0.05", "bump_height = 0.0")]);
    let c = Vehicle::from_resource(&text).unwrap().car;
    let (m, j, a, b) = (c.body.mass, c.body.pitch_inertia, c.body.front, c.body.rear);
    let (kf, kr, kt, mw) = (
        c.suspension.front_stiffness,
        c.suspension.rear_stiffness,
        c.wheels.tire_stiffness,
        c.wheels.mass,
    );
    // textbook: q = (y, θ, y_f, y_r)
    let k = Matrix4::new(
        kf + kr,
        a * kf - b * kr,
        -kf,
        -kr,
        a * kf - b * kr,
        a * a * kf + b * b * kr,
        -a * kf,
        b * kr,
        -kf,
        -a * kf,
        kf + kt,
        0.0,
        -kr,
        b * kr,
        0.0,
        kr + kt,
    );
    let mass = Matrix4::from_diagonal(&nalgebra::Vector4::new(m, j, mw, mw));
    let want = mass.try_inverse().unwrap() * k;
    // the model: −∂q̈/∂q by central differences at rest, no beam force
    let mut got = Matrix4::zeros();
    let h = 1e-6;
    for col in 0..4 {
        let mut sp = [0.0; 12];
        let mut sm = [0.0; 12];
        sp[col] = h;
        sm[col] = -h;
        let (dp, dm) = (
            c.rate(0.0, &sp, [0.0; 2], 0.0, &[0.0; 4]),
            c.rate(0.0, &sm, [0.0; 2], 0.0, &[0.0; 4]),
        );
        for row in 0..4 {
            got[(row, col)] = -(dp[4 + row] - dm[4 + row]) / (2.0 * h);
        }
    }
    let err = (got - want).abs().max();
    assert!(err < 1e-6 * want.abs().max(), "M⁻¹K differs by {err}");
    // frequencies of the symmetric M^-1/2 K M^-1/2
    let s = mass.map(|x| if x > 0.0 { x.sqrt().recip() } else { 0.0 });
    let mut f: Vec<f64> = SymmetricEigen::new(s * k * s)
        .eigenvalues
        .iter()
        .map(|l| l.sqrt() / (2.0 * std::f64::consts::PI))
        .collect();
    f.sort_by(f64::total_cmp);
    println!("undamped natural frequencies [Hz]: {f:.3?}");
    assert!(
        f[0] > 0.8 && f[1] < 2.0 && f[2] > 8.0,
        "a passenger car: {f:?}"
    );
}

/// Over the bump with a beam pushing on the roof, the energy ledger closes:
/// E − E₀ = W_road + W_beam − D, to RK4's accuracy (shrinking ~16× per halved step).
#[test]
fn energy_balance_closes_and_converges() {
    let residual = |step: &str| {
        let text = scene(&[("internal_step = 5e-4", step)]);
        let mut i = started(&text);
        let e0 = get(&i, vr::ENERGY);
        let beam = [vr::BEAM_FORCE_X, vr::BEAM_FORCE_Y, vr::BEAM_MOMENT_Z];
        let mut scale: f64 = 0.0;
        let mut drive = 0.0;
        for k in 0..100 {
            let t = 0.01 * k as f64;
            let f = [
                3.0 * t,
                -40.0 + 20.0 * (9.0 * t).sin(),
                5.0 * (4.0 * t).cos(),
            ];
            assert_eq!(i.set_real(&beam, &f), Status::Ok);
            assert_eq!(i.do_step(t, 0.01), Status::Ok);
            for r in [vr::W_ROAD, vr::W_BEAM, vr::DISSIPATED] {
                scale = scale.max(get(&i, r).abs());
            }
            // the drive holds 10 m/s against the held x reaction: F_x V h per step
            drive += f[0] * 10.0 * 0.01;
        }
        let w = get(&i, vr::W_DRIVE);
        assert!(
            (w - drive).abs() < 1e-12 * drive,
            "drive work {w} J vs {drive} J"
        );
        let de = get(&i, vr::ENERGY) - e0;
        let ledger = get(&i, vr::W_ROAD) + get(&i, vr::W_BEAM) - get(&i, vr::DISSIPATED);
        assert!(
            get(&i, vr::W_ROAD).abs() > 1.0,
            "the bump is crossed in the first second"
        );
        ((de - ledger) / scale).abs()
    };
    let (r1, r2) = (
        residual("internal_step = 2e-3"),
        residual("internal_step = 1e-3"),
    );
    println!("energy residual / scale: h = 2 ms {r1:.2e}, 1 ms {r2:.2e}");
    assert!(r2 < 1e-6, "{r2}");
    assert!(r1 / r2 > 8.0, "fourth order: {r1:e} → {r2:e}");
}

/// The mount velocity and acceleration outputs are the time derivatives of the mount pose
/// (central differences over ±1 ms through fmi2GetFMUstate/fmi2SetFMUstate), crossing the bump.
#[test]
fn mount_kinematics_are_consistent() {
    let mut i = started(SCENE);
    for k in 0..50 {
        assert_eq!(i.do_step(0.01 * k as f64, 0.01), Status::Ok);
    }
    let t = 0.5;
    let state = i.get_fmu_state().unwrap();
    let pose = |i: &Instance<Vehicle>| {
        [
            vr::MOUNT_X,
            vr::MOUNT_Y,
            vr::MOUNT_ANGLE,
            vr::MOUNT_VX,
            vr::MOUNT_VY,
            vr::MOUNT_OMEGA,
        ]
        .map(|r| get(i, r))
    };
    let now = [
        vr::MOUNT_VX,
        vr::MOUNT_VY,
        vr::MOUNT_OMEGA,
        vr::MOUNT_AX,
        vr::MOUNT_AY,
        vr::MOUNT_ALPHA,
    ]
    .map(|r| get(&i, r));
    let h = 1e-3;
    assert_eq!(i.do_step(t, h), Status::Ok);
    let plus = pose(&i);
    // backwards: restore, then a run from t − h needs the state at t − h: take it by
    // re-running from a state saved one step earlier
    assert_eq!(i.set_fmu_state(&state), Status::Ok);
    let mut j = started(SCENE);
    for k in 0..49 {
        assert_eq!(j.do_step(0.01 * k as f64, 0.01), Status::Ok);
    }
    assert_eq!(j.do_step(0.49, 0.01 - h), Status::Ok);
    let minus = pose(&j);
    for k in 0..6 {
        let fd = (plus[k] - minus[k]) / (2.0 * h);
        let tol = 1e-3 * now[k].abs().max(1e-2);
        assert!(
            (fd - now[k]).abs() < tol,
            "component {k}: {} vs FD {fd}",
            now[k]
        );
    }
    assert!(
        now[4].abs() > 1e-3,
        "the body moves at t = 0.5 s (bump crossed)"
    );
}

/// A payload `[mass, c.x, c.y, inertia about the mount]` (mount frame), set as inputs.
fn set_payload(i: &mut Instance<Vehicle>, p: [f64; 4]) {
    let r = [
        vr::BEAM_MASS,
        vr::BEAM_COM_X,
        vr::BEAM_COM_Y,
        vr::BEAM_INERTIA,
    ];
    assert_eq!(i.set_real(&r, &p), Status::Ok);
}

const PAYLOAD: [f64; 4] = [60.0, 1.1, 0.25, 60.0 * (1.1 * 1.1 + 0.25 * 0.25) + 25.0];

/// At rest a rigid payload (interface mass) weighs on the mount like the force and moment of
/// its weight given as the beam reaction: the static starts agree (support on the payload:
/// force (0, m g), moment m g c_x about the mount, c the centre of mass in world axes).
#[test]
fn a_payload_at_rest_weighs_like_its_reaction() {
    let text = SCENE.replace("bump_height = 0.05", "bump_height = 0.0");
    let start = |payload: Option<[f64; 4]>, angle: f64| {
        let model = Vehicle::from_resource(&text).unwrap();
        let mut i = Instance::new("car", Logger::memory(), true, "{g}".into(), model).unwrap();
        assert_eq!(i.setup_experiment(None, 0.0, None), Status::Ok);
        assert_eq!(i.enter_initialization_mode(), Status::Ok);
        let [m, cx, cy, _] = PAYLOAD;
        match payload {
            Some(p) => set_payload(&mut i, p),
            None => {
                let g = 9.81;
                let (s, c) = angle.sin_cos();
                let x = c * cx - s * cy;
                let f = [0.0, m * g, m * g * x];
                let r = [vr::BEAM_FORCE_X, vr::BEAM_FORCE_Y, vr::BEAM_MOMENT_Z];
                assert_eq!(i.set_real(&r, &f), Status::Ok);
            }
        }
        assert_eq!(i.exit_initialization_mode(), Status::Ok);
        i
    };
    let with = start(Some(PAYLOAD), 0.0);
    // the weight's arm depends on the settled pitch: iterate the reaction on it
    let mut angle = 0.0;
    let mut as_force = start(None, angle);
    for _ in 0..4 {
        angle = get(&as_force, vr::PITCH);
        as_force = start(None, angle);
    }
    for r in [vr::HEAVE, vr::PITCH] {
        let (a, b) = (get(&with, r), get(&as_force, r));
        assert!(
            (a - b).abs() < 1e-12,
            "vr {r}: payload {a} vs its reaction {b}"
        );
    }
    assert!(
        (get(&with, vr::HEAVE) - get(&started(&scene(&[])), vr::HEAVE)).abs() > 1e-3,
        "the payload sags the car"
    );
}

/// Car and rigid payload conserve energy together over the bump: the car's energy change
/// plus the payload's (kinetic ½ m |v_c|² + ½ I_c ω² in the frame moving with the car's
/// constant speed, gravity m g y_c, from the mount outputs)
/// equals the road's work minus the dampers' dissipation, to RK4's accuracy; the car's
/// `energy.beam_work` is minus the payload's energy change.
#[test]
fn car_and_payload_conserve_energy() {
    let residual = |step: &str| {
        let text = scene(&[("internal_step = 5e-4", step)]);
        let model = Vehicle::from_resource(&text).unwrap();
        let mut i = Instance::new("car", Logger::memory(), true, "{g}".into(), model).unwrap();
        assert_eq!(i.setup_experiment(None, 0.0, None), Status::Ok);
        assert_eq!(i.enter_initialization_mode(), Status::Ok);
        set_payload(&mut i, PAYLOAD);
        assert_eq!(i.exit_initialization_mode(), Status::Ok);
        let [m, cx, cy, io] = PAYLOAD;
        let ic = io - m * (cx * cx + cy * cy);
        let speed = Vehicle::from_resource(&text).unwrap().car.road.speed;
        let payload_energy = |i: &Instance<Vehicle>| {
            let [y, th, vx, vy, w] = [
                vr::MOUNT_Y,
                vr::MOUNT_ANGLE,
                vr::MOUNT_VX,
                vr::MOUNT_VY,
                vr::MOUNT_OMEGA,
            ]
            .map(|r| get(i, r));
            let (s, c) = th.sin_cos();
            let (rx, ry) = (c * cx - s * cy, s * cx + c * cy);
            // velocities in the frame moving with the car's constant forward speed (inertial:
            // the drive, which holds x, does no work there)
            let (ux, uy) = (vx - speed - w * ry, vy + w * rx);
            0.5 * m * (ux * ux + uy * uy) + 0.5 * ic * w * w + m * 9.81 * (y + ry)
        };
        let (e0, p0) = (get(&i, vr::ENERGY), payload_energy(&i));
        for k in 0..100 {
            assert_eq!(i.do_step(0.01 * k as f64, 0.01), Status::Ok);
        }
        let de = get(&i, vr::ENERGY) - e0;
        let dp = payload_energy(&i) - p0;
        let (road, diss, beam) = (
            get(&i, vr::W_ROAD),
            get(&i, vr::DISSIPATED),
            get(&i, vr::W_BEAM),
        );
        assert!(road.abs() > 1.0, "the bump is crossed in the first second");
        let scale = road.abs().max(diss.abs());
        (
            ((de + dp - road + diss) / scale).abs(),
            ((beam + dp) / scale).abs(),
        )
    };
    let (r1, b1) = residual("internal_step = 2e-3");
    let (r2, b2) = residual("internal_step = 1e-3");
    println!("car + payload energy residual / scale: 2 ms {r1:.2e}, 1 ms {r2:.2e}; beam work + ΔE_payload: {b1:.2e}, {b2:.2e}");
    assert!(r2 < 1e-6 && b2 < 1e-6, "{r2} {b2}");
    assert!(r1 / r2 > 8.0, "fourth order: {r1:e} → {r2:e}");
}
