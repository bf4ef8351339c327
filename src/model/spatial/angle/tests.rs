//! The angle node's port against central differences of its own frame and section axis.

use super::*;
use crate::model::spatial::node::tests::{assert_point_force_residual_is_the_default, fd_rotation};
use crate::model::PortKin;

fn port() -> AnglePort3 {
    let s = 1.0 / 2f64.sqrt();
    AnglePort3 {
        t0: [s, 0.0, s],
        d0: [0.0, 1.0, 0.0],
    }
}

/// A node: position, slope turned ~35° from t⁰ and stretched, twist angle 0.7 rad.
fn node() -> Vec<f64> {
    vec![0.1, -0.2, 0.3, 0.9, 0.35, 0.4, 0.7]
}

#[test]
fn frame_is_orthonormal_and_turns_with_the_angle() {
    let p = port();
    let q = node();
    let k = p.kinematics(&q);
    let f = k.frame;
    assert!((f.transpose() * f - nalgebra::Matrix3::identity()).amax() < 1e-15);
    assert!((f.determinant() - 1.0).abs() < 1e-15);
    let t = Vector3::new(q[3], q[4], q[5]).normalize();
    assert!((f.column(0) - t).amax() < 1e-15);
    // θ turns the section about t: its rotation is t
    assert!((Vector3::from(k.rotation_jacobian(6)) - t).amax() < 1e-15);
    // at θ = 0 along t⁰ the frame is the reference
    let mut q0 = vec![0.0; 7];
    q0[3..6].copy_from_slice(&p.t0);
    let f0 = p.kinematics(&q0).frame;
    assert!((f0.column(1) - Vector3::from(p.d0)).amax() < 1e-15);
}

#[test]
fn rotations_section_field_and_moment_stiffness_match_central_differences() {
    let p = port();
    let q = node();
    let kin = p.kinematics(&q);
    let h = 1e-6;
    let sec = kin.section.as_ref().unwrap();
    for k in 0..7 {
        let fd = fd_rotation(&p, &q, k);
        let got = Vector3::from(kin.rotation_jacobian(k));
        assert!((fd - got).amax() < 1e-9, "rotation {k}: {fd} vs {got}");
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[k] += h;
        qm[k] -= h;
        let (sp, sm) = (p.kinematics(&qp), p.kinematics(&qm));
        let (sp, sm) = (sp.section.unwrap(), sm.section.unwrap());
        let fd = (sp.v - sm.v) / (2.0 * h);
        assert!(
            (fd - sec.d[k]).amax() < 1e-9,
            "section {k}: {fd} vs {}",
            sec.d[k]
        );
        // second derivatives: ∂/∂q_k of the gradient, against the Hessian entries
        for j in 0..7 {
            let fd = (sp.d[j] - sm.d[j]) / (2.0 * h);
            let (a, b) = (j.min(k), j.max(k));
            let got = sec
                .dd
                .list
                .iter()
                .find(|(x, y, _)| (*x, *y) == (a, b))
                .map_or(Vector3::zeros(), |e| e.2);
            assert!((fd - got).amax() < 1e-8, "section ({j},{k}): {fd} vs {got}");
        }
    }
    let m = [0.7, -1.3, 0.4];
    let d = q.len();
    let mut hm = vec![0.0; d * d];
    p.add_moment_stiffness(&q, &m, &mut |i, j, v| hm[i * d + j] += v);
    assert!(hm.iter().any(|x| x.abs() > 0.1));
    for j in 0..d {
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[j] += h;
        qm[j] -= h;
        let (kp, km) = (p.kinematics(&qp), p.kinematics(&qm));
        for i in 0..d {
            let rp = -Vector3::from(m).dot(&Vector3::from(kp.rotation_jacobian(i)));
            let rm = -Vector3::from(m).dot(&Vector3::from(km.rotation_jacobian(i)));
            let fd = (rp - rm) / (2.0 * h);
            assert!(
                (fd - hm[i * d + j]).abs() < 1e-8,
                "({i},{j}): {fd} vs {}",
                hm[i * d + j]
            );
        }
    }
}

/// The node's point-force residual is the kinematics' one bit for bit (zeros' signs included).
#[test]
fn point_force_residual_is_the_kinematics_one_bit_for_bit() {
    assert_point_force_residual_is_the_default(&port(), &node());
}
