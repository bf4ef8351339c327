//! The spatial car against independent references: the closed-form static wheel loads (lever
//! rule, roll moment split by the axles' roll stiffnesses), its own energy ledger at RK4's
//! order, the pitch-plane car (`hybeam-vehicle`) in the symmetric case, finite differences of
//! its mount kinematics and accelerations, and its saved state; driven through the FMI layer.

use fmi2::log::Logger;
use fmi2::types::Status;
use fmi2::{CoSimModel, Instance};
use hybeam_vehicle::{vr as pvr, Vehicle};
use hybeam_vehicle3d::{vr, Car, Vehicle3d, N};

const SCENE: &str = include_str!("../vehicle3d.toml");
const PLANAR: &str = include_str!("../../vehicle/vehicle.toml");

/// `text` with the replacements `edit` (each must occur).
fn edited(text: &str, edit: &[(&str, &str)]) -> String {
    let mut s = text.to_string();
    for (from, to) in edit {
        assert!(s.contains(from), "{from}");
        s = s.replace(from, to);
    }
    s
}

fn instance<M: CoSimModel>(text: &str) -> Instance<M> {
    let model = M::from_resource(text).unwrap();
    let mut i = Instance::new("car", Logger::memory(), true, "{g}".into(), model).unwrap();
    assert_eq!(i.setup_experiment(None, 0.0, None), Status::Ok);
    assert_eq!(i.enter_initialization_mode(), Status::Ok);
    i
}

/// Instantiated, the inputs `set` given in initialization mode, initialized.
fn started<M: CoSimModel>(text: &str, set: &[(u32, f64)]) -> Instance<M> {
    let mut i = instance::<M>(text);
    for &(r, x) in set {
        assert_eq!(i.set_real(&[r], &[x]), Status::Ok);
    }
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    i
}

fn get<M: CoSimModel>(i: &Instance<M>, r: u32) -> f64 {
    let mut v = [f64::NAN];
    assert_eq!(i.get_real(&[r], &mut v), Status::Ok);
    v[0]
}

/// All 19 mount outputs (position, Euler parameters, velocity, angular velocity,
/// acceleration, angular acceleration).
fn mount(i: &Instance<Vehicle3d>) -> [f64; 19] {
    std::array::from_fn(|k| get(i, vr::MOUNT_X + k as u32))
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// R_y(θ) R_x(φ) applied to `v`, written as the two rotations one after the other.
fn rotate(theta: f64, phi: f64, v: [f64; 3]) -> [f64; 3] {
    let (sp, cp) = phi.sin_cos();
    let w = [v[0], cp * v[1] - sp * v[2], sp * v[1] + cp * v[2]];
    let (st, ct) = theta.sin_cos();
    [ct * w[0] + st * w[2], w[1], -st * w[0] + ct * w[2]]
}

/// The static start (with a beam reaction at a lateral mount offset, and without) carries the
/// closed-form wheel loads: axle loads by the lever rule, the roll moment split between the
/// axles in proportion to their roll stiffnesses (series spring and tire; the warp of the
/// four corners is zero for a rigid body), the wheels' weights on top; heave, pitch and roll
/// are the plane through the corners' closed-form deflections; the car stays there.
/// A rigid payload at the mount (interface-mass inputs): 40 kg, its centre of mass off every
/// axis, a full inertia tensor about the mount point.
const PAYLOAD: [(u32, f64); 10] = [
    (vr::BEAM_MASS, 40.0),
    (vr::BEAM_COM_X, 1.0),
    (vr::BEAM_COM_X + 1, 0.1),
    (vr::BEAM_COM_X + 2, 0.2),
    (vr::BEAM_INERTIA_XX, 5.0),
    (vr::BEAM_INERTIA_XX + 1, 50.0),
    (vr::BEAM_INERTIA_XX + 2, 50.0),
    (vr::BEAM_INERTIA_XX + 3, -4.0),
    (vr::BEAM_INERTIA_XX + 4, -8.0),
    (vr::BEAM_INERTIA_XX + 5, -0.8),
];

#[test]
fn static_start_has_the_closed_form_wheel_loads() {
    let flat = edited(SCENE, &[("bump_height = 0.05", "bump_height = 0.0")]);
    let offset = edited(
        &flat,
        &[("position = [0.3, 0.0, 0.9]", "position = [0.3, 0.4, 0.9]")],
    );
    // support on the beam: holding it up (F_z > 0), pushing it back and left, twisting it
    let (f, m) = ([35.0, -20.0, 420.0], [15.0, -180.0, 6.0]);
    for (text, f, m) in [
        (&flat, [0.0; 3], [0.0; 3]),
        (&offset, [0.0; 3], [0.0; 3]),
        (&offset, f, m),
        (&flat, f, m),
    ] {
        let set: Vec<(u32, f64)> = (0..3)
            .flat_map(|k| {
                [
                    (vr::BEAM_FORCE_X + k as u32, f[k]),
                    (vr::BEAM_MOMENT_X + k as u32, m[k]),
                ]
            })
            .collect();
        let mut i = started::<Vehicle3d>(text, &set);
        let c: Car = i.model.car;
        let (t, s) = i.model.state();
        let got = c.tire_loads(t, &s);
        // closed form at the settled attitude (the mount arm r = R s̄ turns with the body)
        let (theta, phi) = (get(&i, vr::PITCH), get(&i, vr::ROLL));
        let r = rotate(theta, phi, c.mount.position);
        let u = rotate(theta, 0.0, [1.0, 0.0, 0.0]);
        let moment = {
            let rf = cross(r, f);
            [rf[0] + m[0], rf[1] + m[1], rf[2] + m[2]]
        };
        let (b, g, mw) = (&c.body, c.solver.gravity, c.wheels.mass);
        let (a, rear, w) = (b.front, b.rear, b.track);
        let load = b.mass * g + f[2];
        // generalized pitch (about +y) and roll (about u) moments of −F, −M on the body
        let (q_pitch, q_roll) = (-moment[1], -dot(u, moment));
        let front = (load * rear + q_pitch) / (a + rear);
        let back = (load * a - q_pitch) / (a + rear);
        let kt = c.wheels.tire_stiffness;
        let series = |k: f64| k * kt / (k + kt);
        let (kf, kr) = (
            series(c.suspension.front_stiffness),
            series(c.suspension.rear_stiffness),
        );
        // Σ y_i P_i = −Q_roll, split front:rear = kf:kr
        let roll = -2.0 * q_roll / w;
        let (df, dr) = (roll * kf / (kf + kr), roll * kr / (kf + kr));
        let p = [
            0.5 * (front + df),
            0.5 * (front - df),
            0.5 * (back + dr),
            0.5 * (back - dr),
        ];
        let want = p.map(|x| x + mw * g);
        for k in 0..4 {
            assert!(
                (got[k] - want[k]).abs() < 1e-9 * b.mass * g,
                "wheel {k}: {} vs closed form {}",
                got[k],
                want[k]
            );
        }
        // the body plane through the corners' deflections (spring and tire in series)
        let stiff = [
            c.suspension.front_stiffness,
            c.suspension.front_stiffness,
            c.suspension.rear_stiffness,
            c.suspension.rear_stiffness,
        ];
        let zc: [f64; 4] = std::array::from_fn(|k| -want[k] / kt - p[k] / stiff[k]);
        let (zf, zr) = (0.5 * (zc[0] + zc[1]), 0.5 * (zc[2] + zc[3]));
        let pitch = (zr - zf) / (a + rear);
        let heave = zf + a * pitch;
        let roll_angle = (zc[0] - zc[1]) / w;
        for (name, r, x) in [
            ("heave", vr::HEAVE, heave),
            ("pitch", vr::PITCH, pitch),
            ("roll", vr::ROLL, roll_angle),
        ] {
            let y = get(&i, r);
            assert!((y - x).abs() < 1e-11, "{name} {y} vs closed form {x}");
        }
        println!(
            "F = {f:?}, M = {m:?}, mount {:?}: tire loads {got:.3?} N (closed form {want:.3?}); heave {heave:.6e} m, pitch {pitch:.6e}, roll {roll_angle:.6e} rad",
            c.mount.position
        );
        // it stays (1e-9 m over 1 s, the reaction held)
        let z0 = get(&i, vr::HEAVE);
        for k in 0..10 {
            assert_eq!(i.do_step(0.1 * k as f64, 0.1), Status::Ok);
        }
        assert!((get(&i, vr::HEAVE) - z0).abs() < 1e-9);
        assert!((get(&i, vr::ROLL) - roll_angle).abs() < 1e-9);
    }
}

/// Over the bump under the left wheels, with no beam and with a constant beam reaction at a
/// lateral offset, the energy ledger closes: E − E₀ = W_road + W_beam − D, to RK4's accuracy
/// (shrinking ~16× per halved step); the drive work is Σ F_x V h of the held x reaction.
#[test]
fn energy_ledger_closes_at_fourth_order() {
    let offset = edited(
        SCENE,
        &[("position = [0.3, 0.0, 0.9]", "position = [0.3, -0.3, 0.9]")],
    );
    let reaction = [
        (vr::BEAM_FORCE_X, 30.0),
        (vr::BEAM_FORCE_Y, 25.0),
        (vr::BEAM_FORCE_Z, 1500.0),
        (vr::BEAM_MOMENT_X, -40.0),
        (vr::BEAM_MOMENT_Y, 120.0),
        (vr::BEAM_MOMENT_Z, 10.0),
    ];
    for set in [&[][..], &reaction[..]] {
        let residual = |step: &str| {
            let text = edited(&offset, &[("internal_step = 5e-4", step)]);
            let mut i = started::<Vehicle3d>(&text, set);
            let e0 = get(&i, vr::ENERGY);
            let mut scale: f64 = 0.0;
            let mut beam: f64 = 0.0;
            let mut drive = 0.0;
            let fx = get(&i, vr::BEAM_FORCE_X);
            for k in 0..100 {
                assert_eq!(i.do_step(0.01 * k as f64, 0.01), Status::Ok);
                for r in [vr::W_ROAD, vr::W_BEAM, vr::DISSIPATED] {
                    scale = scale.max(get(&i, r).abs());
                }
                beam = beam.max(get(&i, vr::W_BEAM).abs());
                // the drive holds 10 m/s against the held x reaction: F_x V h per step
                drive += fx * 10.0 * 0.01;
            }
            let w = get(&i, vr::W_DRIVE);
            assert!(
                (w - drive).abs() <= 1e-12 * drive.abs(),
                "drive work {w} J vs {drive} J"
            );
            let de = get(&i, vr::ENERGY) - e0;
            let ledger = get(&i, vr::W_ROAD) + get(&i, vr::W_BEAM) - get(&i, vr::DISSIPATED);
            assert!(get(&i, vr::W_ROAD).abs() > 1.0, "the bump is crossed");
            if !set.is_empty() {
                assert!(beam > 0.5, "the beam works: {beam} J");
            }
            ((de - ledger) / scale).abs()
        };
        let (r1, r2) = (
            residual("internal_step = 2e-3"),
            residual("internal_step = 1e-3"),
        );
        println!(
            "energy residual / scale ({} reaction): h = 2 ms {r1:.2e}, 1 ms {r2:.2e}, ratio {:.1}",
            if set.is_empty() { "no" } else { "constant" },
            r1 / r2
        );
        assert!(r2 < 1e-5, "{r2}");
        assert!(r1 / r2 > 12.0 || r2 < 1e-9, "fourth order: {r1:e} → {r2:e}");
    }
}

/// The scenes of the symmetric comparison: the spatial car with the bump across the road and
/// the pitch-plane car whose wheel stands for the axle's two (twice the mass and tire).
fn symmetric_pair() -> (String, String) {
    let spatial = edited(SCENE, &[("sides = \"left\"", "sides = \"both\"")]);
    let planar = edited(
        PLANAR,
        &[
            ("mass = 40.0 ", "mass = 80.0 "),
            ("tire_stiffness = 200000.0", "tire_stiffness = 400000.0"),
        ],
    );
    (spatial, planar)
}

/// Symmetric car, bump across the road, no lateral offset: heave, pitch (the planar car's is
/// −pitch), mount position, velocity, accelerations and energies equal the pitch-plane car's
/// to 1e-10 relative over a bump run with the same time-varying reaction inputs (planar force
/// (x, y) = spatial (x, z), planar moment z = −spatial moment y), with and without an
/// interface-mass payload in the pitch plane; roll, the lateral and out-of-plane components
/// stay exactly 0.
#[test]
fn symmetric_car_equals_the_pitch_plane_car() {
    let (spatial, planar) = symmetric_pair();
    // payload: 60 kg, centre of mass (1.1, 0, 0.25) from the mount, central inertia
    // diag(10, 25, 20) kg m2
    let (mp, cx, cz) = (60.0, 1.1, 0.25);
    let iyy = 25.0 + mp * (cx * cx + cz * cz);
    let payload3 = [
        (vr::BEAM_MASS, mp),
        (vr::BEAM_COM_X, cx),
        (vr::BEAM_COM_X + 2, cz),
        (vr::BEAM_INERTIA_XX, 10.0 + mp * cz * cz),
        (vr::BEAM_INERTIA_XX + 1, iyy),
        (vr::BEAM_INERTIA_XX + 2, 20.0 + mp * cx * cx),
        (vr::BEAM_INERTIA_XX + 4, -mp * cx * cz),
    ];
    let payload2 = [
        (pvr::BEAM_MASS, mp),
        (pvr::BEAM_COM_X, cx),
        (pvr::BEAM_COM_Y, cz),
        (pvr::BEAM_INERTIA, iyy),
    ];
    for with_payload in [false, true] {
        let (p3, p2) = if with_payload {
            (&payload3[..], &payload2[..])
        } else {
            (&[][..], &[][..])
        };
        let mut a = started::<Vehicle3d>(&spatial, p3);
        let mut b = started::<Vehicle>(&planar, p2);
        // pairs (spatial output, sign, planar output) and the spatial outputs that must be 0
        let pairs = [
            (vr::HEAVE, 1.0, pvr::HEAVE),
            (vr::PITCH, -1.0, pvr::PITCH),
            (vr::MOUNT_X, 1.0, pvr::MOUNT_X),
            (vr::MOUNT_X + 2, 1.0, pvr::MOUNT_Y),
            (vr::MOUNT_VX, 1.0, pvr::MOUNT_VX),
            (vr::MOUNT_VX + 2, 1.0, pvr::MOUNT_VY),
            (vr::MOUNT_WX + 1, -1.0, pvr::MOUNT_OMEGA),
            (vr::MOUNT_AX, 1.0, pvr::MOUNT_AX),
            (vr::MOUNT_AX + 2, 1.0, pvr::MOUNT_AY),
            (vr::MOUNT_ALPHA_X + 1, -1.0, pvr::MOUNT_ALPHA),
            (vr::ENERGY, 1.0, pvr::ENERGY),
            (vr::W_ROAD, 1.0, pvr::W_ROAD),
            (vr::W_BEAM, 1.0, pvr::W_BEAM),
            (vr::DISSIPATED, 1.0, pvr::DISSIPATED),
            (vr::W_DRIVE, 1.0, pvr::W_DRIVE),
        ];
        let zeros = [
            vr::ROLL,
            vr::MOUNT_X + 1,
            vr::MOUNT_E0 + 1,
            vr::MOUNT_E0 + 3,
            vr::MOUNT_VX + 1,
            vr::MOUNT_WX,
            vr::MOUNT_WX + 2,
            vr::MOUNT_AX + 1,
            vr::MOUNT_ALPHA_X,
            vr::MOUNT_ALPHA_Z,
        ];
        let mut worst = vec![0.0f64; pairs.len()];
        let mut scale = vec![0.0f64; pairs.len()];
        for k in 0..100 {
            let t = 0.01 * k as f64;
            let (fx, fz, my) = (
                3.0 * t,
                40.0 + 20.0 * (9.0 * t).sin(),
                -5.0 * (4.0 * t).cos(),
            );
            let f3 = [
                (vr::BEAM_FORCE_X, fx),
                (vr::BEAM_FORCE_Z, fz),
                (vr::BEAM_MOMENT_Y, my),
            ];
            let f2 = [
                (pvr::BEAM_FORCE_X, fx),
                (pvr::BEAM_FORCE_Y, fz),
                (pvr::BEAM_MOMENT_Z, -my),
            ];
            for (r, x) in f3 {
                assert_eq!(a.set_real(&[r], &[x]), Status::Ok);
            }
            for (r, x) in f2 {
                assert_eq!(b.set_real(&[r], &[x]), Status::Ok);
            }
            for (j, &(r3, sign, r2)) in pairs.iter().enumerate() {
                let (x3, x2) = (get(&a, r3), get(&b, r2));
                worst[j] = worst[j].max((x3 - sign * x2).abs());
                scale[j] = scale[j].max(x2.abs());
            }
            for r in zeros {
                assert_eq!(get(&a, r), 0.0, "vr {r} at t = {t}");
            }
            assert_eq!(a.do_step(t, 0.01), Status::Ok);
            assert_eq!(b.do_step(t, 0.01), Status::Ok);
        }
        let rel: Vec<f64> = worst.iter().zip(&scale).map(|(w, s)| w / s).collect();
        println!(
            "spatial vs planar ({} payload), max |difference| / max |planar| per output: {:?}",
            if with_payload { "with" } else { "no" },
            rel.iter().map(|r| format!("{r:.1e}")).collect::<Vec<_>>()
        );
        assert!(scale[1] > 1e-3, "the car pitches over the bump");
        for (j, r) in rel.iter().enumerate() {
            assert!(*r < 1e-10, "output {:?}: {r:e}", pairs[j]);
        }
    }
}

/// Bump under the left wheels: the car rolls (left side up first, positive), the mount turns
/// about x (ω_x nonzero), and its attitude output is R_y(pitch) R_x(roll).
#[test]
fn left_bump_rolls_the_car() {
    let mut i = started::<Vehicle3d>(SCENE, &[]);
    let (mut max_roll, mut max_wx, mut first) = (0.0f64, 0.0f64, 0.0);
    for k in 0..100 {
        assert_eq!(i.do_step(0.01 * k as f64, 0.01), Status::Ok);
        let (roll, wx) = (get(&i, vr::ROLL), get(&i, vr::MOUNT_WX));
        if first == 0.0 && roll.abs() > 1e-4 {
            first = roll;
        }
        max_roll = max_roll.max(roll.abs());
        max_wx = max_wx.max(wx.abs());
        // the Euler parameters turn the body axes as R_y(θ) R_x(φ)
        let m = mount(&i);
        let (theta, phi) = (get(&i, vr::PITCH), roll);
        let e = [m[3], m[4], m[5], m[6]];
        let ev = [e[1], e[2], e[3]];
        for v in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
            // v' = v + 2 e0 (e × v) + 2 e × (e × v)
            let ex = cross(ev, v);
            let eex = cross(ev, ex);
            let rq: [f64; 3] = std::array::from_fn(|j| v[j] + 2.0 * e[0] * ex[j] + 2.0 * eex[j]);
            let rr = rotate(theta, phi, v);
            for j in 0..3 {
                assert!((rq[j] - rr[j]).abs() < 1e-14, "{rq:?} vs {rr:?}");
            }
        }
        assert!((dot(ev, ev) + e[0] * e[0] - 1.0).abs() < 1e-15);
    }
    println!("left bump: max |roll| {max_roll:.3e} rad, max |ω_x| {max_wx:.3e} rad/s, first roll {first:.2e}");
    assert!(first > 0.0, "the left wheels rise first: left side up");
    assert!(max_roll > 1e-3 && max_wx > 1e-2);
}

/// The mount's velocity, angular velocity and accelerations are the time derivatives of its
/// pose (central differences over ±0.25 ms across the bump, their error O(h²), constant inputs, a payload and an
/// offset mount so every term is exercised); ω also from the Euler parameters' rate,
/// ω = 2 ė ⊗ e*.
#[test]
fn mount_kinematics_are_the_derivatives_of_the_pose() {
    let text = edited(
        SCENE,
        &[("position = [0.3, 0.0, 0.9]", "position = [0.3, 0.35, 0.9]")],
    );
    let reaction = [
        (vr::BEAM_FORCE_X, 20.0),
        (vr::BEAM_FORCE_Y, -15.0),
        (vr::BEAM_FORCE_Z, 100.0),
        (vr::BEAM_MOMENT_X, 30.0),
        (vr::BEAM_MOMENT_Y, -50.0),
    ];
    let set: Vec<(u32, f64)> = reaction.into_iter().chain(PAYLOAD).collect();
    let mut i = started::<Vehicle3d>(&text, &set);
    for k in 0..54 {
        assert_eq!(i.do_step(0.01 * k as f64, 0.01), Status::Ok);
    }
    let h = 2.5e-4;
    let t = 0.54;
    let m0 = mount(&i);
    assert_eq!(i.do_step(t, h), Status::Ok);
    let m1 = mount(&i);
    assert_eq!(i.do_step(t + h, h), Status::Ok);
    let m2 = mount(&i);
    let d = |k: usize| (m2[k] - m0[k]) / (2.0 * h);
    // e ⊗ conj: ω = 2 ė ⊗ e*, vector part
    let e = [m1[3], m1[4], m1[5], m1[6]];
    let de = [d(3), d(4), d(5), d(6)];
    let w_quat = {
        let (a0, av) = (de[0], [de[1], de[2], de[3]]);
        let bv = [-e[1], -e[2], -e[3]];
        let c = cross(av, bv);
        [
            2.0 * (a0 * bv[0] + e[0] * av[0] + c[0]),
            2.0 * (a0 * bv[1] + e[0] * av[1] + c[1]),
            2.0 * (a0 * bv[2] + e[0] * av[2] + c[2]),
        ]
    };
    let checks: Vec<(&str, f64, f64)> = (0..3)
        .flat_map(|j| {
            [
                ("velocity", m1[7 + j], d(j)),
                ("angular velocity (quaternion rate)", m1[10 + j], w_quat[j]),
                ("acceleration", m1[13 + j], d(7 + j)),
                ("angular acceleration", m1[16 + j], d(10 + j)),
            ]
        })
        .collect();
    for (j, (name, got, fd)) in checks.iter().enumerate() {
        // relative to the size of the vector (the FD error is the bump's high-frequency part)
        let size = (0..3)
            .map(|a| checks[(j % 4) + 4 * a].1.powi(2))
            .sum::<f64>()
            .sqrt();
        let tol = 1e-4 * size.max(1e-2);
        assert!((got - fd).abs() < tol, "{name}: {got} vs FD {fd}");
    }
    println!("mount kinematics at t = {:.3}: {checks:.4?}", t + h);
    assert!(
        m1[10].abs() > 1e-3 && m1[16].abs() > 1e-2 && m1[17].abs() > 1e-2,
        "pitching and rolling"
    );
}

/// fmi2GetDirectionalDerivative of the mount accelerations by every input equals finite
/// differences of the acceleration outputs (the reaction: exact mobility vs a difference of
/// the linear outputs; the payload: vs central differences), on a pitched and rolled car
/// carrying a payload.
#[test]
fn directional_derivatives_are_finite_differences() {
    let text = edited(
        SCENE,
        &[("position = [0.3, 0.0, 0.9]", "position = [0.3, 0.35, 0.9]")],
    );
    let mut i = started::<Vehicle3d>(&text, &PAYLOAD);
    let reaction = [
        (vr::BEAM_FORCE_X, 20.0),
        (vr::BEAM_FORCE_Y, -15.0),
        (vr::BEAM_FORCE_Z, 100.0),
        (vr::BEAM_MOMENT_X, 30.0),
        (vr::BEAM_MOMENT_Y, -50.0),
        (vr::BEAM_MOMENT_Z, 7.0),
    ];
    for (r, x) in reaction {
        assert_eq!(i.set_real(&[r], &[x]), Status::Ok);
    }
    for k in 0..56 {
        assert_eq!(i.do_step(0.01 * k as f64, 0.01), Status::Ok);
    }
    assert!(get(&i, vr::ROLL).abs() > 1e-4 && get(&i, vr::PITCH).abs() > 1e-4);
    let acc: Vec<u32> = (0..6).map(|k| vr::MOUNT_AX + k).collect();
    let read = |i: &Instance<Vehicle3d>| acc.iter().map(|&r| get(i, r)).collect::<Vec<_>>();
    let mut worst = [0.0f64; 2];
    for input in 1..=16u32 {
        let mut dd = [0.0; 6];
        assert_eq!(
            i.get_directional_derivative(&acc, &[input], &[1.0], &mut dd),
            Status::Ok
        );
        let kept = get(&i, input);
        let set = |i: &mut Instance<Vehicle3d>, x: f64| {
            assert_eq!(i.set_real(&[input], &[x]), Status::Ok);
            read(i)
        };
        let (fd, tol) = if input <= 6 {
            // linear: a difference of 100 N (N m) gives the partial to rounding
            let (p, o) = (set(&mut i, kept + 100.0), set(&mut i, kept));
            let fd: Vec<f64> = (0..6).map(|k| (p[k] - o[k]) / 100.0).collect();
            (fd, 1e-9)
        } else {
            let d = 1e-4 * kept.abs().max(1.0);
            let (p, m) = (set(&mut i, kept + d), set(&mut i, kept - d));
            set(&mut i, kept);
            let fd: Vec<f64> = (0..6).map(|k| (p[k] - m[k]) / (2.0 * d)).collect();
            (fd, 1e-6)
        };
        // floor: 1e-3 (m/s2 or rad/s2 per unit input) for the payload, where some partials
        // vanish with the slow rotation
        let floor: f64 = if input <= 6 { 1e-12 } else { 1e-3 };
        let size = fd.iter().chain(&dd).fold(floor, |a, x| a.max(x.abs()));
        let err = (0..6).map(|k| (dd[k] - fd[k]).abs()).fold(0.0, f64::max) / size;
        worst[usize::from(input > 6)] = worst[usize::from(input > 6)].max(err);
        assert!(err < tol, "input {input}: {dd:?} vs FD {fd:?} ({err:e})");
    }
    println!(
        "directional derivatives vs FD, max relative difference: reaction {:.1e}, payload {:.1e}",
        worst[0], worst[1]
    );
}

/// fmi2GetFMUstate/fmi2SetFMUstate and the serialized form restore the car bit-identically:
/// the run continued from a restored state (in the same and in a fresh instance, with input
/// derivatives pending) repeats every output bit for bit.
#[test]
fn saved_state_round_trips_bit_identically() {
    let mut i = started::<Vehicle3d>(SCENE, &[(vr::BEAM_FORCE_Z, 200.0)]);
    for k in 0..40 {
        assert_eq!(i.do_step(0.01 * k as f64, 0.01), Status::Ok);
    }
    assert_eq!(
        i.set_real_input_derivatives(
            &[vr::BEAM_FORCE_Z, vr::BEAM_MOMENT_X],
            &[1, 2],
            &[50.0, -30.0]
        ),
        Status::Ok
    );
    let state = i.get_fmu_state().unwrap();
    let size = i.serialized_fmu_state_size(&state).unwrap();
    let mut bytes = vec![0; size];
    assert_eq!(i.serialize_fmu_state(&state, &mut bytes), Status::Ok);
    let bytes: Vec<u8> = bytes.iter().map(|&b| b as u8).collect();
    let run = |i: &mut Instance<Vehicle3d>| {
        let mut out = Vec::new();
        for k in 0..30 {
            assert_eq!(i.do_step(0.4 + 0.01 * k as f64, 0.01), Status::Ok);
            for r in (vr::MOUNT_X..=vr::MOUNT_ALPHA_Z).chain(vr::HEAVE..=vr::W_DRIVE) {
                out.push(get(i, r).to_bits());
            }
        }
        out
    };
    let first = run(&mut i);
    assert_eq!(i.set_fmu_state(&state), Status::Ok);
    assert_eq!(run(&mut i), first, "restored in the same instance");
    let mut fresh = started::<Vehicle3d>(SCENE, &[]);
    let restored = fresh.deserialize_fmu_state(&bytes).unwrap();
    assert_eq!(fresh.set_fmu_state(&restored), Status::Ok);
    assert_eq!(run(&mut fresh), first, "deserialized into a fresh instance");
    // another resource's state is refused
    let other = edited(SCENE, &[("speed = 10.0", "speed = 12.0")]);
    let mut j = started::<Vehicle3d>(&other, &[]);
    let s = j.model.save_state();
    assert!(i.model.load_state(&s).is_err());
    let _ = j.do_step(0.0, 0.01);
    let (_, s0) = i.model.state();
    assert_eq!(s0.len(), N);
}

/// Bad resource fields are refused naming the field, the value and what is allowed.
#[test]
fn bad_resource_fields_are_named() {
    let e =
        Vehicle3d::from_resource(&edited(SCENE, &[("track = 1.5", "track = 0.0")])).unwrap_err();
    assert!(e.contains("body.track = 0") && e.contains("> 0"), "{e}");
    let e = Vehicle3d::from_resource(&edited(SCENE, &[("sides = \"left\"", "sides = \"right\"")]))
        .unwrap_err();
    assert!(
        e.contains("sides") && e.contains("right") && e.contains("left") && e.contains("both"),
        "{e}"
    );
    let e =
        Vehicle3d::from_resource(&edited(SCENE, &[("[0.3, 0.0, 0.9]", "[0.3, 0.9]")])).unwrap_err();
    assert!(e.contains("position"), "{e}");
    // a payload that is not a rigid body is discarded at the step
    let mut i = started::<Vehicle3d>(
        SCENE,
        &[
            (vr::BEAM_MASS, 10.0),
            (vr::BEAM_COM_X, 2.0),
            (vr::BEAM_INERTIA_XX + 1, 1.0),
        ],
    );
    assert_eq!(i.do_step(0.0, 0.01), Status::Discard);
}
