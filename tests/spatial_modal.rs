//! The spatial floating-frame modal body (kernel `ModalBody3`, components in
//! `model::spatial`), each against an independent reference:
//! * the Newton block against central differences of the residual;
//! * the port fields (position, directors, normals: first and second derivatives), the frame
//!   rotation and the moment stiffness against central differences;
//! * ½q̇ᵀMq̇ against the kinetic energy by quadrature of ½∫ρA|ṙ|² + ½∫ρI_p(ω̄_x + θ̇)² over
//!   sample points of the deformed body (ṙ from Ȧ of the normalized p, not from Ē);
//! * the velocity terms against Lagrange's equations by finite differences of that energy;
//! * the support reaction against the static balance of a clamped body under gravity;
//! * the linear frequencies of a clamped segment against the closed forms of B4;
//! * B5 torque-free precession of a free body (assembled by hand, generalized-α).

use hybeam::integrator::{GeneralizedAlpha, Integrable, IntegrationParameters, State};
use hybeam::model::component::{ConstraintOut, Support};
use hybeam::model::modal::basis::quadrature;
use hybeam::model::modal::body3d::{euler_rotation, torsion_shapes};
use hybeam::model::modal::{ModalBasis, ModalBody3, ModalProps3};
use hybeam::model::space::Space;
use hybeam::model::spatial::{
    EndKin3, EulerNormalization, FrameSupport3, ModalElement3, ModalRootPort3, ModalTipPort3,
    NodePort3,
};
use hybeam::model::{Constraint, Dof, LocalDofs, Model, Numbering, Parts, Port, Spatial};
use nalgebra::{DMatrix, Matrix3, Vector3};
use std::f64::consts::PI;
use std::sync::Arc;

/// Properties with unequal bending stiffnesses (to tell the planes apart), torsion, and the
/// damping ratio ζ and retardation time τ [s].
fn test_props(damping_ratio: f64, damping_time: f64) -> ModalProps3 {
    ModalProps3 {
        length: 0.4,
        rho_a: 2.4,
        rho_ip: 3.1e-4,
        ei_z: 1650.0,
        ei_y: 900.0,
        gj: 1270.0,
        damping_ratio,
        damping_time,
    }
}

/// A body of [`test_props`] with damping.
fn test_body(modes: usize, interface: bool) -> ModalBody3 {
    ModalBody3::new(ModalBasis::new(modes, interface), test_props(0.02, 1e-4))
}

/// `b` without damping, the nonlinear body or (`nonlinear = false`) the linear one.
fn undamped(mut b: ModalBody3, nonlinear: bool) -> ModalBody3 {
    if !nonlinear {
        b = b.linear();
    }
    b.d_y.iter_mut().for_each(|x| *x = 0.0);
    b.d_z.iter_mut().for_each(|x| *x = 0.0);
    b.d_t = [[0.0; 2]; 2];
    b.props.damping_time = 0.0;
    b
}

/// Deterministic pseudo-random numbers in [−1, 1].
fn noise(seed: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| ((i as f64 + 1.0) * 12.9898 + seed * 78.233).sin())
        .collect()
}

/// A state with unit p, ṗ ⟂ p, ω ≠ 0 and the modes excited (amplitudes ~ 1 cm, twist ~ 0.05 rad).
fn random_state(b: &ModalBody3, seed: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let d = b.dim();
    let mut q = noise(seed, d);
    let mut v = noise(seed + 1.0, d);
    let a = noise(seed + 2.0, d).iter().map(|x| 20.0 * x).collect();
    let n = (3..7).map(|k| q[k] * q[k]).sum::<f64>().sqrt();
    for k in 3..7 {
        q[k] /= n;
    }
    // ṗ ⟂ p (the motion stays on the unit sphere)
    let pv: f64 = (3..7).map(|k| q[k] * v[k]).sum();
    for k in 3..7 {
        v[k] = 3.0 * (v[k] - pv * q[k]);
    }
    for k in 7..d {
        q[k] *= if k >= b.it(0) { 0.05 } else { 0.01 };
        v[k] *= 0.5;
    }
    (q, v, a)
}

/// [`random_state`] with the bending amplitudes and rates of shape n scaled by
/// amp·(K_1/K_n)^e (a smooth deflection, as a physical one: the slopes of the stiff interface
/// shapes stay small; tip slopes ~0.1·amp).
fn smooth_state(b: &ModalBody3, seed: f64, amp: f64, e: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let (mut q, mut v, a) = random_state(b, seed);
    let nb = b.modes();
    for n in 0..nb {
        let f = amp * (b.k_y[0] / b.k_y[n]).powf(e);
        for k in [b.iy(n), b.iz(n)] {
            q[k] *= f;
            v[k] *= f;
        }
    }
    (q, v, a)
}

fn residual(b: &ModalBody3, q: &[f64], v: &[f64], a: &[f64], g: [f64; 3]) -> Vec<f64> {
    let mut r = vec![0.0; b.dim()];
    b.residual(q, v, a, g, &mut r);
    r
}

#[test]
fn newton_block_matches_central_differences() {
    let g = [0.3, -9.81, 1.2];
    for (modes, interface) in [(2, false), (3, true)] {
        let b = test_body(modes, interface);
        let d = b.dim();
        let (q, v, a) = random_state(&b, 0.7 + modes as f64);
        let r0 = residual(&b, &q, &v, &a, g);
        let rmax = r0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut worst: f64 = 0.0;
        for (which, c) in [
            (0, (1.0, 0.0, 0.0)),
            (1, (0.0, 1.0, 0.0)),
            (2, (0.0, 0.0, 1.0)),
        ] {
            let mut block = vec![0.0; d * d];
            b.newton_block((&q, &v, &a), g, c, &mut block);
            for j in 0..d {
                let h = 1e-6;
                let shift = |s: f64| {
                    let (mut qq, mut vv, mut aa) = (q.clone(), v.clone(), a.clone());
                    match which {
                        0 => aa[j] += s,
                        1 => vv[j] += s,
                        _ => qq[j] += s,
                    }
                    residual(&b, &qq, &vv, &aa, g)
                };
                let (rp, rm) = (shift(h), shift(-h));
                for i in 0..d {
                    let fd = (rp[i] - rm[i]) / (2.0 * h);
                    let x = block[i * d + j];
                    let err = (fd - x).abs() / (1.0 + x.abs() + 1e-3 * rmax);
                    worst = worst.max(err);
                    assert!(
                        err < 1e-6,
                        "modes {modes} block {which} [{i},{j}]: {x} vs FD {fd}"
                    );
                }
            }
        }
        eprintln!("Newton block vs central differences (modes {modes}, interface {interface}): worst relative error {worst:.2e}");
    }
}

/// The damping force of a body with retardation time τ (and no damping ratio) is the
/// Kelvin–Voigt force of its inextensible curvatures κ_z = v″(1 + ½v′²) + v′w′w″ and
/// κ_y = w″(1 + ½w′²) (Crespo da Silva & Glynn): F = τ∫(EI_z κ̇_z ∂κ_z/∂a + EI_y κ̇_y ∂κ_y/∂a)dx,
/// κ computed here from the basis, κ̇ and ∂κ/∂a by central differences, both on a 50-panel
/// rule; the damping's share of the residual is the damped body's less the τ = 0 twin's.
#[test]
fn damping_is_kelvin_voigt_on_the_nonlinear_curvatures() {
    let tau = 1e-3;
    let basis = ModalBasis::new(3, true);
    let body = |tau| ModalBody3::new(basis.clone(), test_props(0.0, tau)).with_panels(50);
    let (damped, plain) = (body(tau), body(0.0));
    let (q, v, a) = smooth_state(&damped, 0.3, 1.0, 0.5);
    let g = [0.3, -9.81, 1.2];
    let (r1, r0) = (
        residual(&damped, &q, &v, &a, g),
        residual(&plain, &q, &v, &a, g),
    );
    let nb = damped.modes();
    let pr = test_props(0.0, tau);
    let l = pr.length;
    // (κ_z, κ_y) at ξ of the amplitudes (a_y, a_z)
    let kappa = |ay: &[f64], az: &[f64], xi: f64| {
        let mut phi = Vec::new();
        basis.eval_all(xi, &mut phi);
        let [mut s, mut vv, mut t, mut ww] = [0.0; 4];
        for ((p, y), z) in phi.iter().zip(ay).zip(az) {
            s += y * p[1] / l;
            vv += y * p[2] / (l * l);
            t += z * p[1] / l;
            ww += z * p[2] / (l * l);
        }
        [
            vv * (1.0 + 0.5 * s * s) + s * t * ww,
            ww * (1.0 + 0.5 * t * t),
        ]
    };
    let (iy, iz) = (damped.iy(0), damped.iz(0));
    let h = 1e-7;
    // directional derivative of κ along (δa_y, δa_z)
    let along = |dy: &[f64], dz: &[f64], xi: f64| {
        let shift = |sgn: f64| {
            let ay: Vec<f64> = (0..nb).map(|k| q[iy + k] + sgn * h * dy[k]).collect();
            let az: Vec<f64> = (0..nb).map(|k| q[iz + k] + sgn * h * dz[k]).collect();
            kappa(&ay, &az, xi)
        };
        let (p, m) = (shift(1.0), shift(-1.0));
        [(p[0] - m[0]) / (2.0 * h), (p[1] - m[1]) / (2.0 * h)]
    };
    let mut want = vec![0.0; 2 * nb];
    let panels = 50;
    for panel in 0..panels {
        for &(t, wt) in &quadrature(1) {
            let xi = (panel as f64 + t) / panels as f64;
            let kd = along(&v[iy..iy + nb], &v[iz..iz + nb], xi);
            for (j, f) in want.iter_mut().enumerate() {
                let mut e = vec![0.0; 2 * nb];
                e[j] = 1.0;
                let dk = along(&e[..nb], &e[nb..], xi);
                *f += tau * (pr.ei_z * kd[0] * dk[0] + pr.ei_y * kd[1] * dk[1]) * wt
                    / panels as f64
                    * l;
            }
        }
    }
    let got: Vec<f64> = (0..nb)
        .map(|k| r1[iy + k] - r0[iy + k])
        .chain((0..nb).map(|k| r1[iz + k] - r0[iz + k]))
        .collect();
    let linear: Vec<f64> = (0..nb)
        .map(|k| tau * damped.k_y[k] * v[iy + k])
        .chain((0..nb).map(|k| tau * damped.k_z[k] * v[iz + k]))
        .collect();
    let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let nl = (0..2 * nb)
        .map(|j| (want[j] - linear[j]).abs())
        .fold(0.0, f64::max);
    eprintln!("damping: nonlinear part {:.2e} of {scale:.2e}", nl);
    assert!(
        nl > 1e-2 * scale,
        "the state should exercise the nonlinear part"
    );
    for j in 0..2 * nb {
        assert!(
            (got[j] - want[j]).abs() < 1e-7 * scale,
            "amplitude {j}: {} vs {}",
            got[j],
            want[j]
        );
    }
}

/// Dense ∂²v/∂q∂q of a field from its sparse list.
fn dense_hessian(dd: &[(usize, usize, Vector3<f64>)], d: usize) -> Vec<Vec<Vector3<f64>>> {
    let mut h = vec![vec![Vector3::zeros(); d]; d];
    for &(i, j, v) in dd {
        assert!(i <= j, "pairs are stored with i ≤ j");
        assert_eq!(h[i][j], Vector3::zeros(), "pair ({i}, {j}) stored twice");
        h[i][j] = v;
        h[j][i] = v;
    }
    h
}

/// The fields of an end in a fixed order: position, tangent, section, n1, n2, n3.
fn fields(k: &EndKin3) -> Vec<hybeam::model::spatial::Field3> {
    let mut f = vec![
        k.p.clone(),
        k.tangent.clone(),
        k.section
            .clone()
            .expect("modal ends carry a section director"),
    ];
    f.extend(k.normals.clone().expect("modal ends carry normals"));
    f
}

fn check_port(port: &dyn Port<Spatial>, b: &ModalBody3, seed: f64, name: &str) {
    let d = b.dim();
    let (q, _, _) = random_state(b, seed);
    let kin = port.kinematics(&q);
    // the first-order kinematics are the same but for the second derivatives
    let first = port.kinematics_first(&q);
    assert_eq!((first.frame, &first.rotation), (kin.frame, &kin.rotation));
    for (a, b) in fields(&first).iter().zip(&fields(&kin)) {
        assert_eq!((a.v, &a.d), (b.v, &b.d));
    }
    // the values alone (a joint's Φ) are the kinematics' values, to the bit
    assert_eq!(
        port.values(&q),
        Spatial::port_values(&first),
        "{name}: values"
    );
    // fourth-order central differences (the directors are trigonometric in the amplitudes):
    // (8(f(h) − f(−h)) − (f(2h) − f(−2h)))/12h
    let h = 1e-5;
    let fd4 = |p: &[EndKin3; 4], g: &dyn Fn(&EndKin3) -> Vector3<f64>| {
        (8.0 * (g(&p[0]) - g(&p[1])) - (g(&p[2]) - g(&p[3]))) / (12.0 * h)
    };
    let at = |k: usize, s: f64| {
        let mut x = q.clone();
        x[k] += s;
        port.kinematics(&x)
    };
    let mut worst = [0.0f64; 4];
    let f0 = fields(&kin);
    for k in 0..d {
        let ks = [at(k, h), at(k, -h), at(k, 2.0 * h), at(k, -2.0 * h)];
        for (n, f) in f0.iter().enumerate() {
            // first derivatives
            let fd = fd4(&ks, &|e| fields(e)[n].v);
            let e = (fd - f.d[k]).norm() / (1.0 + f.d[k].norm());
            worst[0] = worst[0].max(e);
            assert!(e < 1e-8, "{name} field {n} d[{k}]: {:?} vs {fd:?}", f.d[k]);
            // second derivatives: FD of the first along q_k
            let hd = dense_hessian(&f.dd, d);
            for i in 0..d {
                let fd = fd4(&ks, &|e| fields(e)[n].d[i]);
                let e = (fd - hd[i][k]).norm() / (1.0 + hd[i][k].norm());
                worst[1] = worst[1].max(e);
                assert!(
                    e < 1e-7,
                    "{name} field {n} dd[{i},{k}]: {:?} vs {fd:?}",
                    hd[i][k]
                );
            }
        }
        // rotation: ½Σ f_c × ∂f_c/∂q_k of the frame columns
        let mut w = Vector3::zeros();
        for c in 0..3 {
            let df = fd4(&ks, &|e| e.frame.column(c).into());
            w += 0.5 * kin.frame.column(c).cross(&df);
        }
        let e = (w - kin.rotation[k]).norm() / (1.0 + w.norm());
        worst[2] = worst[2].max(e);
        assert!(
            e < 1e-7,
            "{name} rotation[{k}]: {:?} vs {w:?}",
            kin.rotation[k]
        );
    }
    // the frame is orthonormal; n1, n2 ⟂ tangent exactly
    let fr = kin.frame;
    assert!((fr.transpose() * fr - Matrix3::identity()).norm() < 1e-14);
    assert!(fr.determinant() > 0.0);
    let n = kin.normals.as_ref().unwrap();
    for i in 0..2 {
        let nt = n[i].v.dot(&kin.tangent.v) / (n[i].v.norm() * kin.tangent.v.norm());
        assert!(nt.abs() < 1e-15, "n{} · t: {nt:e}", i + 1);
    }
    // moment stiffness −m·∂²θ/∂q∂q against FD of −m·∂θ/∂q
    let m = [0.7, -1.3, 0.4];
    let mut k = vec![0.0; d * d];
    port.add_moment_stiffness(&q, &m, &mut |i, j, v| k[i * d + j] += v);
    let mv = Vector3::from(m);
    for j in 0..d {
        let ks = [at(j, h), at(j, -h), at(j, 2.0 * h), at(j, -2.0 * h)];
        for i in 0..d {
            let fd = -mv.dot(&fd4(&ks, &|e| e.rotation[i]));
            let e = (fd - k[i * d + j]).abs() / (1.0 + fd.abs());
            worst[3] = worst[3].max(e);
            assert!(
                e < 1e-7,
                "{name} moment stiffness [{i},{j}]: {} vs {fd}",
                k[i * d + j]
            );
        }
    }
    check_along(port, &q, name);
    eprintln!(
        "{name}: worst relative FD error d {:.1e}, dd {:.1e}, rotation {:.1e}, moment stiffness {:.1e}",
        worst[0], worst[1], worst[2], worst[3]
    );
}

/// The rotation's second derivative along a direction (the angular acceleration's velocity
/// term) = the moment stiffness contracted with it, component by component.
fn check_along(port: &dyn Port<Spatial>, q: &[f64], name: &str) {
    let d = q.len();
    let dir: Vec<f64> = (0..d)
        .map(|i| 0.3 + 0.17 * i as f64 - 0.05 * (i * i) as f64)
        .collect();
    let along = port.rotation_second_derivative_along(q, &dir);
    for (c, got) in along.iter().enumerate() {
        let mut unit = [0.0; 3];
        unit[c] = 1.0;
        let mut want = 0.0;
        port.add_moment_stiffness(q, &unit, &mut |i, j, v| want -= v * dir[i] * dir[j]);
        assert!(
            (got - want).abs() <= 1e-12 * (1.0 + want.abs()) && want.abs() > 1e-3,
            "{name} along [{c}]: {got} vs {want}"
        );
    }
}

/// The ANCF node's port (with and without the section director r_y) overrides the default
/// with one directional evaluation: the same contraction of its moment stiffness.
#[test]
fn ancf_node_rotation_second_derivative_is_the_contracted_moment_stiffness() {
    let reference = Matrix3::from_columns(&[
        Vector3::new(0.6, 0.8, 0.0),
        Vector3::new(-0.8, 0.6, 0.0),
        Vector3::z(),
    ]);
    for torsion in [true, false] {
        let mut q = vec![0.1, -0.2, 0.05, 0.7, 0.6, 0.3];
        if torsion {
            q.extend([-0.5, 0.6, 0.2]);
        }
        check_along(
            &NodePort3::new(torsion, reference),
            &q,
            &format!("node, torsion {torsion}"),
        );
    }
}

#[test]
fn port_fields_rotations_and_moment_stiffness_match_central_differences() {
    let b = Arc::new(test_body(3, true));
    check_port(&ModalTipPort3(b.clone()), &b, 0.3, "tip");
    check_port(&ModalRootPort3(b.clone()), &b, 0.9, "root");
}

#[test]
fn tip_port_is_the_straight_frame_at_zero_amplitudes() {
    // with a = 0 the tip sits at R + L A x̄ with frame A and rotation 2E (unit p)
    let b = Arc::new(test_body(2, false));
    let mut q = vec![0.0; b.dim()];
    q[..7].copy_from_slice(&[0.1, -0.2, 0.3, 0.5, 0.5, -0.5, 0.5]);
    let kin = ModalTipPort3(b.clone()).kinematics(&q);
    let a = euler_rotation([0.5, 0.5, -0.5, 0.5]);
    let am = Matrix3::from_fn(|i, j| a[i][j]);
    assert!((kin.frame - am).norm() < 1e-15);
    let want = Vector3::new(0.1, -0.2, 0.3) + 0.4 * am.column(0);
    assert!((kin.p.v - want).norm() < 1e-15);
    // a tip twist a_t turns the section about the tangent: rotation ∂θ/∂a_t = χ(1) A x̄
    let r = kin.rotation[b.it(0)];
    assert!((r - am.column(0)).norm() < 1e-14, "{r:?}");
    assert!(kin.rotation[b.it(1)].norm() < 1e-14);
}

fn mat(p: [f64; 4]) -> Matrix3<f64> {
    let a = euler_rotation(p);
    Matrix3::from_fn(|i, j| a[i][j])
}

/// The rotation A(p̂) of the normalized p̂ = p/|p| and its rate Ȧ = ∂A/∂p(p̂)·(I − p̂p̂ᵀ)ṗ/|p|
/// (exact by A(p̂ ± δp̂), A being quadratic): a reference frame whose motion, like the model's
/// ω̄ = 2Ēṗ, ignores the component of ṗ along p.
fn rotation_and_rate(q: &[f64], v: &[f64]) -> (Matrix3<f64>, Matrix3<f64>) {
    let n = (3..7).map(|k| q[k] * q[k]).sum::<f64>().sqrt();
    let p = [0, 1, 2, 3].map(|k| q[3 + k] / n);
    let pv: f64 = (0..4).map(|k| p[k] * v[3 + k]).sum();
    let dp = [0, 1, 2, 3].map(|k| (v[3 + k] - pv * p[k]) / n);
    let a = mat(p);
    let ad =
        0.5 * (mat([0, 1, 2, 3].map(|k| p[k] + dp[k])) - mat([0, 1, 2, 3].map(|k| p[k] - dp[k])));
    (a, ad)
}

/// One sample of the deformed body: weight × L [m], position r [m], velocity ṙ [m/s], disk
/// spin ω̄_x + θ̇ [rad/s] and the world axis A x̄.
struct Sample {
    wl: f64,
    r: Vector3<f64>,
    rd: Vector3<f64>,
    spin: f64,
    axis: Vector3<f64>,
}

/// Sample points of the deformed body by a composite Gauss rule: r = R + A ū, ṙ = Ṙ + Ȧū + A s
/// ([`rotation_and_rate`]), ū = (ξL, φᵀa_y, φᵀa_z), s = (0, φᵀȧ_y, φᵀȧ_z), section spin
/// ω̄_x + χᵀȧ_t with ω̄ the axial vector of AᵀȦ. For the nonlinear body ū_x and s_x carry the
/// foreshortening −½∫₀ˣ(v′² + w′²)dx and its rate −∫₀ˣ(v′v̇′ + w′ẇ′)dx, integrated here by
/// a nested Gauss rule on [0, x] (16 panels of 5 points, independent of the body's rule).
fn samples(b: &ModalBody3, q: &[f64], v: &[f64]) -> Vec<Sample> {
    let nb = b.modes();
    let l = b.props.length;
    let (a, ad) = rotation_and_rate(q, v);
    let om = a.transpose() * ad;
    let wx = 0.5 * (om[(2, 1)] - om[(1, 2)]);
    let r0 = Vector3::new(q[0], q[1], q[2]);
    let rd = Vector3::new(v[0], v[1], v[2]);
    quadrature(40)
        .into_iter()
        .map(|(xi, w)| {
            let (mut u, mut s) = (Vector3::new(xi * l, 0.0, 0.0), Vector3::zeros());
            for n in 0..nb {
                let phi = b.basis.eval_one(n, xi)[0];
                u[1] += phi * q[7 + n];
                u[2] += phi * q[7 + nb + n];
                s[1] += phi * v[7 + n];
                s[2] += phi * v[7 + nb + n];
            }
            if b.nonlinear {
                let (mut c, mut cd) = (0.0, 0.0);
                for (t, wt) in quadrature(16) {
                    let (mut sl, mut sld) = ([0.0; 2], [0.0; 2]);
                    for n in 0..nb {
                        let d1 = b.basis.eval_one(n, t * xi)[1] / l;
                        sl[0] += d1 * q[7 + n];
                        sl[1] += d1 * q[7 + nb + n];
                        sld[0] += d1 * v[7 + n];
                        sld[1] += d1 * v[7 + nb + n];
                    }
                    let dx = wt * xi * l;
                    c -= 0.5 * dx * (sl[0] * sl[0] + sl[1] * sl[1]);
                    cd -= dx * (sl[0] * sld[0] + sl[1] * sld[1]);
                }
                u[0] += c;
                s[0] += cd;
            }
            let (chi, _) = torsion_shapes(xi);
            Sample {
                wl: w * l,
                r: r0 + a * u,
                rd: rd + ad * u + a * s,
                spin: wx + chi[0] * v[b.it(0)] + chi[1] * v[b.it(1)],
                axis: a.column(0).into_owned(),
            }
        })
        .collect()
}

/// Kinetic energy by quadrature over sample points of the deformed body ([`samples`]):
/// ½∫ρA|ṙ|² + ½∫ρI_p(ω̄_x + θ̇)².
fn quadrature_kinetic_energy(b: &ModalBody3, q: &[f64], v: &[f64]) -> f64 {
    samples(b, q, v)
        .iter()
        .map(|x| {
            x.wl * 0.5 * (b.props.rho_a * x.rd.norm_squared() + b.props.rho_ip * x.spin * x.spin)
        })
        .sum()
}

#[test]
fn mass_matrix_and_kinetic_energy_match_quadrature() {
    for (modes, interface, seed) in [(2, false, 0.1), (3, true, 0.4)] {
        // the nonlinear terms on a fine rule (the default's 2 panels integrate the cumulative
        // foreshortening of the third mode to ~1e-7 of T here)
        let b = test_body(modes, interface).with_panels(24);
        let d = b.dim();
        let (q, v, _) = smooth_state(&b, seed, 3.0, 0.5);
        let mut m = vec![0.0; d * d];
        b.newton_block((&q, &v, &v), [0.0; 3], (1.0, 0.0, 0.0), &mut m);
        let vmv: f64 = (0..d)
            .map(|i| (0..d).map(|j| v[i] * m[i * d + j] * v[j]).sum::<f64>())
            .sum();
        let t = quadrature_kinetic_energy(&b, &q, &v);
        let (e1, e2) = (
            (0.5 * vmv / t - 1.0).abs(),
            (b.kinetic_energy(&q, &v) / t - 1.0).abs(),
        );
        eprintln!("T = {t:.12e} J: ½q̇ᵀMq̇ rel. error {e1:.1e}, closed form {e2:.1e}");
        // M_aa = ρAL·I assumes ∫φ_iφ_j dξ = δ_ij, which the interface-enriched basis meets to
        // ~1e-9 (its orthonormalization), the pure clamped–free basis to round-off (the
        // nonlinear body's foreshortening on its 24-panel rule, the reference's nested 40 × 16)
        let tol = if interface { 1e-8 } else { 1e-13 };
        assert!(e1 < tol && e2 < tol, "{e1:e} {e2:e}");
        // M is symmetric
        for i in 0..d {
            for j in 0..i {
                assert!((m[i * d + j] - m[j * d + i]).abs() < 1e-14 * (1.0 + m[i * d + j].abs()));
            }
        }
    }
}

#[test]
fn velocity_terms_match_lagranges_equations() {
    // undamped, no gravity: r(q, q̇, 0) − r(q, 0, 0) = d/dt(∂T/∂q̇)|_{q̈=0} − ∂T/∂q with T by
    // quadrature, differentiated by central differences (error O(h²))
    for nonlinear in [true, false] {
        let b = undamped(test_body(3, true).with_panels(24), nonlinear);
        let d = b.dim();
        let (q, v, _) = smooth_state(&b, 0.25, 3.0, 0.5);
        let z = vec![0.0; d];
        let r1 = residual(&b, &q, &v, &z, [0.0; 3]);
        let r0 = residual(&b, &q, &z, &z, [0.0; 3]);
        let rv: Vec<f64> = r1.iter().zip(&r0).map(|(a, b)| a - b).collect();
        let t = |q: &[f64], v: &[f64]| quadrature_kinetic_energy(&b, q, v);
        let dt_dv = |q: &[f64], k: usize| {
            let hv = 1e-3;
            let (mut vp, mut vm) = (v.clone(), v.clone());
            vp[k] += hv;
            vm[k] -= hv;
            (t(q, &vp) - t(q, &vm)) / (2.0 * hv)
        };
        let mut errs = Vec::new();
        for h in [1e-3, 5e-4] {
            let mut lag = vec![0.0; d];
            for k in 0..d {
                let qp: Vec<f64> = q.iter().zip(&v).map(|(q, v)| q + h * v).collect();
                let qm: Vec<f64> = q.iter().zip(&v).map(|(q, v)| q - h * v).collect();
                let ddt = (dt_dv(&qp, k) - dt_dv(&qm, k)) / (2.0 * h);
                let (mut qkp, mut qkm) = (q.clone(), q.clone());
                qkp[k] += h;
                qkm[k] -= h;
                let dtq = (t(&qkp, &v) - t(&qkm, &v)) / (2.0 * h);
                lag[k] = ddt - dtq;
            }
            // the p rows are defined up to a multiple of p (absorbed by the normalization
            // multiplier): compare their parts ⟂ p
            let mut diff: Vec<f64> = rv.iter().zip(&lag).map(|(a, b)| a - b).collect();
            let along: f64 = (3..7).map(|k| diff[k] * q[k]).sum();
            for k in 3..7 {
                diff[k] -= along * q[k];
            }
            eprintln!("  p-rows difference along p: {along:.3e}");
            let scale = lag.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let err = diff.iter().fold(0.0f64, |m, x| m.max(x.abs())) / scale;
            eprintln!(
            "nonlinear {nonlinear}: Q_v vs Lagrange (FD of quadrature T), h = {h:e}: max error / max term = {err:.2e}"
        );
            errs.push(err);
        }
        // O(h²): halving h quarters the error (until round-off)
        assert!(errs[1] < 1e-5, "{errs:?}");
        assert!(errs[1] < 0.4 * errs[0] || errs[1] < 1e-8, "{errs:?}");
    }
}

#[test]
fn clamped_support_reaction_balances_gravity() {
    // a straight clamped body at rest under gravity: the support carries F = −m g and
    // M = −(L/2 A x̄) × m g about the root
    let b = test_body(2, false);
    let d = b.dim();
    let p = {
        let x = [0.8, 0.3, -0.4, 0.2];
        let n = x.iter().map(|v: &f64| v * v).sum::<f64>().sqrt();
        x.map(|v| v / n)
    };
    let mut q = vec![0.0; d];
    q[3..7].copy_from_slice(&p);
    let g = [0.5, -9.81, 2.0];
    let z = vec![0.0; d];
    let r = residual(&b, &q, &z, &z, g);
    let sup = FrameSupport3 {
        position: [0, 1, 2],
        attitude: Some([3, 4, 5, 6]),
    };
    let (f, m) = sup.reaction(&r, &q);
    let mg = Vector3::from(g) * b.mass();
    let arm = 0.5 * b.props.length * mat(p).column(0);
    let want_m = -arm.cross(&mg);
    assert!((Vector3::from(f) + mg).norm() < 1e-13 * mg.norm(), "{f:?}");
    assert!(
        (Vector3::from(m) - want_m).norm() < 1e-13 * want_m.norm(),
        "{m:?} vs {want_m:?}"
    );
    let ball = FrameSupport3 {
        position: [0, 1, 2],
        attitude: None,
    };
    assert_eq!(ball.reaction(&r, &q).1, [0.0; 3]);
}

#[test]
fn euler_normalization_row_matches_central_differences() {
    let c = EulerNormalization;
    let p = [0.9, -0.2, 0.35, 0.1];
    let mut out = ConstraintOut::default();
    out.reset(1, 4);
    c.eval(&p, Some(&[1.7]), &mut out);
    let phi = |x: &[f64]| {
        let mut o = ConstraintOut::default();
        o.reset(1, 4);
        c.eval(x, None, &mut o);
        o
    };
    assert!((out.phi[0] - 0.5 * (p.iter().map(|x| x * x).sum::<f64>() - 1.0)).abs() < 1e-16);
    let h = 1e-6;
    let mut hess = [[0.0; 4]; 4];
    for &(i, j, v) in &out.hess {
        hess[i][j] += v;
    }
    for k in 0..4 {
        let (mut xp, mut xm) = (p, p);
        xp[k] += h;
        xm[k] -= h;
        let (op, om) = (phi(&xp), phi(&xm));
        assert!(((op.phi[0] - om.phi[0]) / (2.0 * h) - out.jac[k]).abs() < 1e-9);
        for i in 0..4 {
            let fd = 1.7 * (op.jac[i] - om.jac[i]) / (2.0 * h);
            assert!((fd - hess[i][k]).abs() < 1e-8);
        }
    }
}

/// The brief's steel rod (E = 210 GPa × `stiffer`, ν = 0.3, ρ = 7850, L = 0.4 m), round of
/// diameter `dia`, undamped.
fn steel_rod(basis: ModalBasis, dia: f64, stiffer: f64) -> ModalBody3 {
    let (e, nu, rho) = (210e9 * stiffer, 0.3, 7850.0);
    let area = PI * dia * dia / 4.0;
    let i = area * dia * dia / 16.0;
    ModalBody3::new(
        basis,
        ModalProps3 {
            length: 0.4,
            rho_a: rho * area,
            rho_ip: rho * 2.0 * i,
            ei_z: e * i,
            ei_y: e * i,
            gj: e / (2.0 * (1.0 + nu)) * 2.0 * i,
            damping_ratio: 0.0,
            damping_time: 0.0,
        },
    )
}

/// The amplitude blocks (M, ∂r/∂q̇, ∂r/∂q) of the Newton matrix at rest, straight, p = 1.
fn amplitude_blocks(b: &ModalBody3) -> [DMatrix<f64>; 3] {
    let d = b.dim();
    let mut q = vec![0.0; d];
    q[3] = 1.0;
    let z = vec![0.0; d];
    [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)].map(|c| {
        let mut m = vec![0.0; d * d];
        b.newton_block((&q, &z, &z), [0.0; 3], c, &mut m);
        DMatrix::from_fn(d - 7, d - 7, |i, j| m[(i + 7) * d + j + 7])
    })
}

#[test]
fn clamped_segment_frequencies_match_b4() {
    // B4: steel rod E = 210 GPa, ν = 0.3, ρ = 7850, d = 2 mm, L = 0.4 m, clamped–free; modes 4
    // + interface; the eigenproblem of the a-block of the Newton matrices (c_x: K, c_a: M)
    let (e, nu, rho, l): (f64, f64, f64, f64) = (210e9, 0.3, 7850.0, 0.4);
    let g = e / (2.0 * (1.0 + nu));
    let b = steel_rod(ModalBasis::new(4, true), 0.002, 1.0);
    let [mm, _, kk] = amplitude_blocks(&b);
    let lo = mm.clone().cholesky().unwrap().l();
    let li = lo.try_inverse().unwrap();
    let c = &li * kk * li.transpose();
    let eig = (0.5 * (&c + c.transpose())).symmetric_eigen();
    // classify each mode by where its eigenvector lives (y, z or torsion block)
    let nb = b.modes();
    let mut fam: [Vec<f64>; 3] = Default::default();
    for k in 0..eig.eigenvalues.len() {
        let x = li.transpose() * eig.eigenvectors.column(k);
        let w =
            [0..nb, nb..2 * nb, 2 * nb..2 * nb + 2].map(|r| r.map(|i| x[i] * x[i]).sum::<f64>());
        let f = eig.eigenvalues[k].sqrt() / (2.0 * PI);
        let which = (0..3).max_by(|a, b| w[*a].total_cmp(&w[*b])).unwrap();
        fam[which].push(f);
    }
    for f in &mut fam {
        f.sort_by(f64::total_cmp);
    }
    let bending = [9.045, 56.682, 158.712, 311.013];
    let c_t = (g / rho).sqrt();
    let torsion = c_t / (4.0 * l);
    eprintln!("B4, modes 4 + interface (Hz): family | model | reference | rel. error");
    for (name, f) in [("x–y", &fam[0]), ("x–z", &fam[1])] {
        for (k, want) in bending.iter().enumerate() {
            let e = f[k] / want - 1.0;
            eprintln!(
                "bending {name} f{} | {:.3} | {want} | {e:+.1e}",
                k + 1,
                f[k]
            );
            assert!(e.abs() < 1e-4, "{name} f{}: {} vs {want}", k + 1, f[k]);
        }
    }
    let e1 = fam[2][0] / torsion - 1.0;
    eprintln!(
        "torsion f1 | {:.2} | {torsion:.2} (2004.79) | {e1:+.2e}",
        fam[2][0]
    );
    eprintln!(
        "torsion f2 | {:.2} | {:.2} (6014.36) | {:+.2e}",
        fam[2][1],
        3.0 * torsion,
        fam[2][1] / (3.0 * torsion) - 1.0
    );
    assert!(
        (torsion / 2004.79 - 1.0).abs() < 1e-5,
        "closed form {torsion}"
    );
    // two-term Ritz (ξ, √2 sin πξ): above the exact value, within 1 %
    assert!(e1 > 0.0 && e1 < 0.01, "{e1}");
    let wt = b.torsion_omegas();
    assert!((wt[0] / (2.0 * PI) / fam[2][0] - 1.0).abs() < 1e-10);
}

#[test]
fn damping_is_modal_with_the_given_ratio_plus_kelvin_voigt() {
    // at rest, ∂r/∂q̇ is the damping alone: in the mass-normalized eigenvectors Φ of (M, K) of
    // the amplitudes, ΦᵀDΦ = diag(2ζω_i + τω_i²) for every bending and torsion mode
    let b = test_body(3, true);
    let d = b.dim();
    let [mm, cc, kk] = amplitude_blocks(&b);
    let lo = mm.clone().cholesky().unwrap().l();
    let li = lo.try_inverse().unwrap();
    let eig = (&li * &kk * li.transpose()).symmetric_eigen();
    let phi = li.transpose() * &eig.eigenvectors;
    let modal = phi.transpose() * cc * &phi;
    let (zeta, tau) = (b.props.damping_ratio, b.props.damping_time);
    for i in 0..d - 7 {
        let w = eig.eigenvalues[i].sqrt();
        let want = 2.0 * zeta * w + tau * w * w;
        assert!(
            (modal[(i, i)] / want - 1.0).abs() < 1e-9,
            "mode {i}: {} vs {want}",
            modal[(i, i)]
        );
        for j in 0..i {
            assert!(
                modal[(i, j)].abs() < 1e-9 * want,
                "coupling {i} {j}: {}",
                modal[(i, j)]
            );
        }
    }
}

/// No support: a free body has no held coordinates.
#[derive(Debug)]
struct Free;

impl Support<Spatial> for Free {
    fn reaction(&self, _: &[f64], _: &[f64]) -> ([f64; 3], [f64; 3]) {
        ([0.0; 3], [0.0; 3])
    }
}

/// Angular momentum about the centre of mass [N m s] (world) by quadrature over the body:
/// ∫ρA (r − r_c) × ṙ + ∫ρI_p(ω̄_x + θ̇) A x̄, and the world axis A x̄.
fn angular_momentum(b: &ModalBody3, q: &[f64], v: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
    let pts = samples(b, q, v);
    let ra = b.props.rho_a;
    let m: f64 = pts.iter().map(|x| x.wl * ra).sum();
    let rc = pts.iter().map(|x| x.r * x.wl * ra).sum::<Vector3<f64>>() / m;
    let h = pts
        .iter()
        .map(|x| x.wl * (ra * (x.r - rc).cross(&x.rd) + b.props.rho_ip * x.spin * x.axis))
        .sum();
    (h, pts[0].axis)
}

struct Precession {
    h_drift: f64,
    t_drift: f64,
    nutation_drift: f64,
    h0_error: f64,
    t0_error: f64,
    nutation0_error: f64,
    precession_rate: f64,
    normalization: f64,
}

/// B5: the rod L = 0.4, d = 0.02 (modes made stiff by E × 10⁴), gravity off, body-frame
/// ω = (ω₃ = 50 about the axis x̄, ω₁ = 2 about ȳ), centre of mass at rest; generalized-α
/// (ρ∞ = 0.9) for `t_end` at fixed step `h`.
fn precession(h: f64, t_end: f64) -> Precession {
    let l = 0.4;
    let body = Arc::new(steel_rod(ModalBasis::new(2, false), 0.02, 1e4));
    let d = body.dim();
    let p0 = {
        let x = [0.9, 0.2, -0.3, 0.1];
        let n = x.iter().map(|v: &f64| v * v).sum::<f64>().sqrt();
        x.map(|v| v / n)
    };
    let (w1, w3) = (2.0, 50.0);
    let wbar = Vector3::new(w3, w1, 0.0);
    let a0 = mat(p0);
    // ṗ = ½Ēᵀω̄; Ṙ = −ω × A c̄ (centre of mass at rest)
    let eb = hybeam::model::modal::body3d::e_bar(p0);
    let pd0: [f64; 4] = [0, 1, 2, 3].map(|k| 0.5 * (0..3).map(|c| eb[c][k] * wbar[c]).sum::<f64>());
    let rd0 = -(a0 * wbar).cross(&(a0 * Vector3::new(0.5 * l, 0.0, 0.0)));
    let mut num = Numbering::default();
    let mut dofs: Vec<Dof> = (0..3).map(|_| num.free(0.0, l)).collect();
    dofs.extend(p0.iter().map(|&x| num.free(x, 1.0)));
    dofs.extend((7..d).map(|_| num.free(0.0, l)));
    let pdofs = LocalDofs::new(dofs[3..7].to_vec());
    let dofs = LocalDofs::new(dofs);
    let mut model = Model::<Spatial>::assemble(Parts {
        numbering: num,
        elements: vec![(dofs.clone(), Box::new(ModalElement3::new(body.clone())), 0)],
        constraints: vec![(pdofs, Box::new(EulerNormalization) as Box<dyn Constraint>)],
        tip: (dofs, Box::new(ModalTipPort3(body.clone()))),
        support: Box::new(Free),
        gravity: [0.0; 3],
        tip_force: [0.0; 3],
        tip_moment: [0.0; 3],
        line_loads: Vec::new(),
        mounted: false,
    });
    let (n, m) = (model.coordinates(), model.constraints());
    assert_eq!((n, m), (d, 1));
    let mut s = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
    s.v[..3].copy_from_slice(rd0.as_slice());
    s.v[3..7].copy_from_slice(&pd0);
    let mut integ = GeneralizedAlpha::new(
        &IntegrationParameters {
            // the smallest allowed: with a looser one, the acceptance of a first iteration on the
            // rate of earlier steps lets |pᵀp − 1| ~ 1e-8 and Newton errors into the drifts
            tolerance: Some(1e-15),
            max_iterations: 30,
            ..Default::default()
        },
        n,
        m,
    );
    integ.initialize(&mut model, &mut s).unwrap();
    // reference invariants of the rigid body: I₁ = mL²/12 (no section rotary inertia in
    // bending, as Euler–Bernoulli), I₃ = ρI_p L
    let mass = body.mass();
    let (i1, i3) = (mass * l * l / 12.0, body.props.rho_ip * l);
    let h_ref = ((i1 * w1).powi(2) + (i3 * w3).powi(2)).sqrt();
    let t_ref = 0.5 * (i1 * w1 * w1 + i3 * w3 * w3);
    let nut_ref = (i3 * w3 / h_ref).acos();
    let measure = |s: &State| {
        let (hv, axis) = angular_momentum(&body, &s.q, &s.v);
        let t = body.kinetic_energy(&s.q, &s.v) + body.strain_energy(&s.q);
        (hv, t, (axis.dot(&hv) / hv.norm()).acos(), axis)
    };
    let (h0, t0, nut0, axis0) = measure(&s);
    let (mut hd, mut td, mut nd, mut norm) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let steps = (t_end / h).round() as usize;
    let mut axis = axis0;
    for _ in 0..steps {
        integ.step(&mut model, &mut s, h).unwrap();
        let (hv, t, nut, ax) = measure(&s);
        hd = hd.max((hv - h0).norm() / h0.norm());
        td = td.max((t - t0).abs() / t0);
        nd = nd.max((nut - nut0).abs());
        norm = norm.max((s.q[3..7].iter().map(|x| x * x).sum::<f64>() - 1.0).abs());
        axis = ax;
    }
    // mean precession rate of the axis about H over the run (projected angle)
    let hh = h0.normalize();
    let perp = |a: Vector3<f64>| (a - hh * a.dot(&hh)).normalize();
    let (u0, u1) = (perp(axis0), perp(axis));
    let ang = u0.cross(&u1).dot(&hh).atan2(u0.dot(&u1));
    Precession {
        h_drift: hd,
        t_drift: td,
        nutation_drift: nd,
        h0_error: h0.norm() / h_ref - 1.0,
        t0_error: t0 / t_ref - 1.0,
        nutation0_error: nut0 - nut_ref,
        precession_rate: ang / t_end,
        normalization: norm,
    }
}

#[test]
fn b5_torque_free_precession_keeps_its_invariants() {
    let t_end = 0.5;
    let mut rows = Vec::new();
    for h in [2e-3, 1e-3, 5e-4] {
        let r = precession(h, t_end);
        eprintln!(
            "B5 h = {h:e}: max drift |ΔH|/|H| {:.2e}, |ΔT|/T {:.2e}, nutation {:.2e} rad; |pᵀp − 1| {:.1e}; precession {:.5} rad/s",
            r.h_drift, r.t_drift, r.nutation_drift, r.normalization, r.precession_rate
        );
        rows.push(r);
    }
    let r = &rows[0];
    eprintln!(
        "B5 initial vs rigid-body closed form: |H| {:+.1e}, T {:+.1e}, nutation {:+.1e} rad",
        r.h0_error, r.t0_error, r.nutation0_error
    );
    // the initial state is the closed form's (same inertia): quadrature-exact
    assert!(
        r.h0_error.abs() < 1e-12 && r.t0_error.abs() < 1e-12 && r.nutation0_error.abs() < 1e-10
    );
    for r in &rows {
        assert!(r.normalization < 1e-12);
        assert!(r.h_drift < 3e-3 && r.t_drift < 3e-3 && r.nutation_drift < 1e-3);
    }
    // second order: halving h divides the drifts by about 4
    for w in rows.windows(2) {
        for (a, b) in [
            (w[0].h_drift, w[1].h_drift),
            (w[0].t_drift, w[1].t_drift),
            (w[0].nutation_drift, w[1].nutation_drift),
        ] {
            assert!(b < 0.35 * a || b < 1e-9, "drift {a:e} → {b:e}");
        }
    }
    // precession of the axis about H at |H|/I₁ (2.0087 rad/s for the brief's instance)
    let (l, dia, rho) = (0.4f64, 0.02f64, 7850.0);
    let mass = rho * PI * dia * dia / 4.0 * l;
    let i1 = mass * l * l / 12.0;
    let i3 = rho * PI * dia.powi(4) / 32.0 * l;
    let rate = ((i1 * 2.0f64).powi(2) + (i3 * 50.0f64).powi(2)).sqrt() / i1;
    let got = rows[2].precession_rate;
    eprintln!("B5 precession rate {got:.5} rad/s vs |H|/I₁ = {rate:.5}");
    assert!((got / rate - 1.0).abs() < 1e-3, "{got} vs {rate}");
}

#[test]
fn clamped_segment_statics_match_beam_theory_in_both_planes_and_torsion() {
    // a clamped body (R, p held, tilted root) assembled with its tip port and support; small
    // dead tip force and moment (linear range): tip deflections v = f_y L³/(3EI_z) +
    // m_z L²/(2EI_z), w = f_z L³/(3EI_y) − m_y L²/(2EI_y), twist θ = m_x L/GJ (each exact in the
    // span of the modes + interface shapes and the static twist shape), body axes; the support
    // carries −F and −(r_T × F) − M about the root
    let body = Arc::new(test_body(3, true));
    let d = body.dim();
    let (l, pr) = (body.props.length, body.props);
    let p0 = {
        let x = [0.8, 0.3, -0.4, 0.2];
        let n = x.iter().map(|v: &f64| v * v).sum::<f64>().sqrt();
        x.map(|v| v / n)
    };
    let r0 = [0.2, -0.1, 0.3];
    let a0 = mat(p0);
    let mut num = Numbering::default();
    let mut dofs: Vec<Dof> = r0.iter().map(|&x| num.held(x)).collect();
    dofs.extend(p0.iter().map(|&x| num.held(x)));
    dofs.extend((7..d).map(|_| num.free(0.0, l)));
    let dofs = LocalDofs::new(dofs);
    let (fb, mb) = (
        Vector3::new(0.0, 0.02, -0.03),
        Vector3::new(0.004, 0.003, -0.002),
    );
    let (f, m) = (a0 * fb, a0 * mb);
    let mut model = Model::<Spatial>::assemble(Parts {
        numbering: num,
        elements: vec![(dofs.clone(), Box::new(ModalElement3::new(body.clone())), 0)],
        constraints: Vec::new(),
        tip: (dofs, Box::new(ModalTipPort3(body.clone()))),
        support: Box::new(FrameSupport3 {
            position: [0, 1, 2],
            attitude: Some([3, 4, 5, 6]),
        }),
        gravity: [0.0; 3],
        tip_force: f.into(),
        tip_moment: m.into(),
        line_loads: Vec::new(),
        mounted: false,
    });
    assert!(std::ptr::eq(model.modal_body(0), &*body));
    let mut s = State::at_rest(0.0, model.initial_coordinates().to_vec(), 0);
    hybeam::integrator::solve_static(&mut model, &mut s, 1e-13).unwrap();
    let o = model.outputs(&s.q, &s.v, &s.acc, &s.lambda);
    let tip = a0.transpose() * (Vector3::from(o.tip_position) - Vector3::from(r0));
    let v = fb[1] * l.powi(3) / (3.0 * pr.ei_z) + mb[2] * l * l / (2.0 * pr.ei_z);
    let w = fb[2] * l.powi(3) / (3.0 * pr.ei_y) - mb[1] * l * l / (2.0 * pr.ei_y);
    let theta = mb[0] * l / pr.gj;
    let q: Vec<f64> = (0..d)
        .map(|k| if k < 7 { 0.0 } else { s.q[k - 7] })
        .collect();
    let (_, _, th) = body.tip_elastic(&q);
    eprintln!(
        "statics: v {:.6e} (beam {v:.6e}), w {:.6e} (beam {w:.6e}), twist {th:.6e} (GJ {theta:.6e})",
        tip[1], tip[2]
    );
    // the reference is linear; the tip frame R(ψ)R_x(θ) turns a dead moment's components
    // into each other at second order (relative O(slope, twist) ~ 4e-6 here)
    assert!((tip[1] / v - 1.0).abs() < 1e-5, "{} vs {v}", tip[1]);
    assert!((tip[2] / w - 1.0).abs() < 1e-5, "{} vs {w}", tip[2]);
    assert!((th / theta - 1.0).abs() < 1e-5, "{th} vs {theta}");
    let rt = Vector3::from(o.tip_position) - Vector3::from(r0);
    let want_m = -rt.cross(&f) - m;
    assert!((Vector3::from(o.root_force) + f).norm() < 1e-10 * f.norm());
    assert!(
        (Vector3::from(o.root_moment) - want_m).norm() < 1e-9 * want_m.norm(),
        "{:?} vs {want_m:?}",
        o.root_moment
    );
}

#[test]
#[ignore = "timing, run with --ignored --nocapture"]
fn residual_timing() {
    use hybeam::model::modal::{BodyOut, ModalBody};
    use hybeam::model::Planar;
    use std::hint::black_box;
    use std::time::Instant;
    /// Best time per call [s] of `f` over 7 batches of `n` calls (the machine is shared).
    fn best(n: usize, mut f: impl FnMut()) -> f64 {
        (0..7)
            .map(|_| {
                let t0 = Instant::now();
                for _ in 0..n {
                    f();
                }
                t0.elapsed().as_secs_f64() / n as f64
            })
            .fold(f64::INFINITY, f64::min)
    }
    let b = test_body(4, true);
    let d = b.dim();
    let (q, v, a) = random_state(&b, 0.5);
    let g = [0.0, -9.81, 0.0];
    let mut r = vec![0.0; d];
    let t3 = best(20_000, || {
        b.residual(black_box(&q), black_box(&v), black_box(&a), g, &mut r);
        black_box(&r);
    });
    let p = ModalBody::new(ModalBasis::new(4, true), 0.4, 2.4, 1650.0, 0.02, 1e-4);
    let dp = p.dim();
    let mut o = BodyOut::new(dp);
    let (qp, vp, ap) = (&q[..dp], &v[..dp], &a[..dp]);
    let t2 = best(20_000, || {
        p.eval(
            black_box(qp),
            black_box(vp),
            black_box(ap),
            [0.0, -9.81],
            false,
            &mut o,
        );
        black_box(&o.res);
    });
    let mut block = vec![0.0; d * d];
    let tb = best(300, || {
        b.newton_block((&q, &v, &a), g, (1.0, 0.5, 0.25), &mut block);
        black_box(&block);
    });
    let port = ModalTipPort3(Arc::new(b.clone()));
    let tk = best(1000, || {
        black_box(port.kinematics(black_box(&q)));
    });
    let pport = hybeam::model::planar::ModalTipPort(Arc::new(p.clone()));
    let tpk = best(1000, || {
        black_box(Port::<Planar>::kinematics(&pport, black_box(qp)));
    });
    eprintln!(
        "best of 7: residual spatial {:.0} ns ({d} coordinates), planar {:.0} ns ({dp}); Newton block {:.1} µs; tip kinematics {:.2} µs (planar {:.2} µs)",
        t3 * 1e9,
        t2 * 1e9,
        tb * 1e6,
        tk * 1e6,
        tpk * 1e6
    );
}

/// Power balance of the undamped free body under gravity: with q̈ solving r(q, q̇, q̈) = 0 and
/// the Euler-parameter normalization p·p̈ = −|ṗ|² (its multiplier's force λp does no work, ṗ ⟂
/// p), the total energy T + U + V_g is stationary: d/dt E = ∇_qE·q̇ + ∇_q̇T·q̈ = 0, by central
/// differences of the energy functions along the motion. The reference is the conservation law;
/// it checks that the residual is the Lagrangian of the energies, the nonlinear terms
/// (foreshortening in the inertia and gravity forces, curvature) included, at slopes up to ~0.5.
/// Any one of them perturbed by 5 % breaks it (checked by hand: see docs/validation.md).
#[test]
fn undamped_body_conserves_energy_along_its_motion() {
    let g = [0.3, -9.81, 1.2];
    for (nonlinear, modes, interface, seed, amp) in [
        (true, 3, true, 0.35, 1.0),
        (true, 3, true, 1.1, 4.0),
        (true, 2, false, 2.3, 4.0),
        (false, 3, true, 1.1, 4.0),
    ] {
        let b = undamped(test_body(modes, interface), nonlinear);
        let d = b.dim();
        let (q, v, _) = smooth_state(&b, seed, amp, 0.5);
        // q̈: [M p̂; p̂ᵀ 0] (q̈, λ) = (−r(q, q̇, 0), −|ṗ|²), p̂ in the p rows
        let z = vec![0.0; d];
        let r0 = residual(&b, &q, &v, &z, g);
        let mut m = vec![0.0; d * d];
        b.newton_block((&q, &v, &z), g, (1.0, 0.0, 0.0), &mut m);
        let mut aug = DMatrix::<f64>::zeros(d + 1, d + 1);
        let mut rhs = nalgebra::DVector::<f64>::zeros(d + 1);
        for i in 0..d {
            for j in 0..d {
                aug[(i, j)] = m[i * d + j];
            }
            rhs[i] = -r0[i];
        }
        for k in 3..7 {
            aug[(k, d)] = q[k];
            aug[(d, k)] = q[k];
        }
        rhs[d] = -(3..7).map(|k| v[k] * v[k]).sum::<f64>();
        let sol = aug.lu().solve(&rhs).expect("regular");
        let acc: Vec<f64> = (0..d).map(|i| sol[i]).collect();
        let energy = |q: &[f64], v: &[f64]| {
            b.kinetic_energy(q, v) + b.strain_energy(q) + b.potential_energy(q, g)
        };
        let h = 1e-8;
        let step = |s: f64| -> f64 {
            let qs: Vec<f64> = (0..d).map(|i| q[i] + s * v[i]).collect();
            let vs: Vec<f64> = (0..d).map(|i| v[i] + s * acc[i]).collect();
            energy(&qs, &vs)
        };
        let rate = (step(h) - step(-h)) / (2.0 * h);
        let ma: Vec<f64> = (0..d)
            .map(|i| (0..d).map(|j| m[i * d + j] * acc[j]).sum::<f64>())
            .collect();
        let vmax = v.iter().fold(0.0f64, |x, y| x.max(y.abs()));
        let scale = ma.iter().fold(0.0f64, |x, y| x.max(y.abs())) * vmax;
        // the nonlinear terms' share of the power (the rate of the strain energy beyond ½aᵀKa),
        // to show that the check sees them
        let lin_u = |q: &[f64]| {
            let nb = b.modes();
            let at = &q[b.it(0)..];
            (0..nb)
                .map(|n| 0.5 * (b.k_y[n] * q[7 + n].powi(2) + b.k_z[n] * q[7 + nb + n].powi(2)))
                .sum::<f64>()
                + (0..2)
                    .map(|i| {
                        (0..2)
                            .map(|j| 0.5 * at[i] * b.k_t[i][j] * at[j])
                            .sum::<f64>()
                    })
                    .sum::<f64>()
        };
        let unl = |s: f64| {
            let qs: Vec<f64> = (0..d).map(|i| q[i] + s * v[i]).collect();
            b.strain_energy(&qs) - lin_u(&qs)
        };
        let p_nl = (unl(h) - unl(-h)) / (2.0 * h);
        let (_, slope, _) = b.tip_elastic(&q);
        eprintln!(
            "nonlinear {nonlinear}, modes {modes}, tip slope {:.2}: dE/dt = {rate:.2e} W, scale {scale:.2e} W, curvature power {p_nl:.2e} W",
            slope.norm()
        );
        assert!(
            rate.abs() < 1e-8 * scale,
            "nonlinear {nonlinear}: dE/dt = {rate:e} W vs scale {scale:e} W"
        );
    }
}
