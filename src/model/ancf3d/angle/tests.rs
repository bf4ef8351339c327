//! The angle element against independent references: central differences of its energies, the
//! spin of the smallest rotation by differences of the frame, closed forms of uniform twist,
//! and the director element on the same section frames.

use super::*;
use crate::model::ancf3d::tests::{check_jacobians, noise, props};
use std::f64::consts::PI;

/// The element along the reference axis t⁰ = (0.6, 0, 0.8) with d⁰ = ŷ.
fn element(tau: f64) -> Angle3 {
    Angle3::new(props(false, tau, 1.0), [0.6, 0.0, 0.8], [0.0, 1.0, 0.0]).unwrap()
}

/// Index of the stretch noise of the node at offset `o`.
fn c_noise(o: usize) -> usize {
    (o + 5) % 14
}

/// A bent, stretched and twisted element and a rate, deterministic: slopes turned by up to
/// ~0.6 rad from t⁰, angles up to ±1 rad.
fn deformed(p: &Angle3, seed: u64) -> ([f64; 14], [f64; 14]) {
    let l = p.cable.length;
    let r = noise(seed, 28);
    let mut e = [0.0; 14];
    for node in 0..2 {
        let o = 7 * node;
        // slopes turned from t⁰, stretched by ≤ 1e-3 (the axial force then does not drown
        // the twist's in the energy differences)
        let a = [0, 1, 2].map(|c| p.t0[c] + 0.3 * r[o + 3 + c]);
        let a = scale(&unit(&a), 1.0 + 1e-3 * r[o + c_noise(o)]);
        for c in 0..3 {
            e[o + c] = 0.1 + node as f64 * l * p.t0[c] + 1e-4 * r[o + c];
            e[o + 3 + c] = a[c];
        }
        e[o + 6] = r[o + 6];
    }
    let ed: [f64; 14] = std::array::from_fn(|k| 3.0 * r[14 + k]);
    (e, ed)
}

#[test]
fn spin_is_the_turn_rate_of_the_reference_frame() {
    // ω·t of u(a) = P(t⁰ → t) d⁰ by central differences along ȧ: (t × u)·u̇ = σ(a)·ȧ
    let p = element(0.0);
    let r = noise(3, 60);
    for k in 0..10 {
        let a = [0, 1, 2].map(|c| p.t0[c] + 0.8 * r[6 * k + c]);
        let ad = [0, 1, 2].map(|c| r[6 * k + 3 + c]);
        let u = |a: [f64; 3]| reference(&p.t0, &p.d0, &unit(&a));
        let h = 1e-6;
        let (up, um) = (
            u([0, 1, 2].map(|c| a[c] + h * ad[c])),
            u([0, 1, 2].map(|c| a[c] - h * ad[c])),
        );
        let udot = [0, 1, 2].map(|c| (up[c] - um[c]) / (2.0 * h));
        let fd = dot(&cross(&unit(&a), &u(a)), &udot);
        let got = dot(&spin(&p.t0, &a), &ad);
        assert!((fd - got).abs() < 1e-8, "{k}: {got} vs {fd}");
        assert!(got.abs() > 1e-3, "{k}: trivial spin {got}");
    }
}

#[test]
fn uniform_twist_is_the_difference_of_the_nodal_angles() {
    // straight element turned about its axis by Δ between the nodes: φ = Δ and the energy
    // ½GJΔ²/l, also beyond ±π per element (the director element wraps there)
    let p = element(0.0);
    let tab = p.tables();
    let l = p.cable.length;
    for delta in [-4.0, -1.0, 0.3, 2.5, 5.0] {
        let mut e = [0.0; 14];
        for node in 0..2 {
            for c in 0..3 {
                e[7 * node + c] = node as f64 * l * p.t0[c];
                e[7 * node + 3 + c] = p.t0[c];
            }
        }
        e[6] = 0.7;
        e[13] = 0.7 + delta;
        let phi = p.twist(&tab, &e);
        assert!((phi - delta).abs() < 1e-14, "{delta}: {phi}");
        let u = p.strain_energy(&tab, &e) / (0.5 * p.cable.gj * delta * delta / l);
        assert!((u - 1.0).abs() < 1e-12, "{delta}: {u}");
    }
}

#[test]
fn force_is_the_gradient_of_the_strain_energy() {
    let p = element(0.0);
    let tab = p.tables();
    for seed in [1, 2] {
        let (e, _) = deformed(&p, seed);
        let f = p.internal_force(&tab, &e, &[0.0; 14]);
        let fmax = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let h = 1e-7;
        for i in 0..14 {
            let (mut ep, mut em) = (e, e);
            ep[i] += h;
            em[i] -= h;
            let fd = (p.strain_energy(&tab, &ep) - p.strain_energy(&tab, &em)) / (2.0 * h);
            assert!(
                (fd - f[i]).abs() < 1e-6 * fmax,
                "{seed} {i}: {} vs {fd}",
                f[i]
            );
        }
        // the twist's share: its moment on the angles [N m], to 1e-6 of itself (a wrong spin
        // term σ would move the slope entries by about this moment per unit slope, far above
        // the tolerance above)
        for s in THETA {
            let (mut ep, mut em) = (e, e);
            ep[s] += h;
            em[s] -= h;
            let fd = (p.strain_energy(&tab, &ep) - p.strain_energy(&tab, &em)) / (2.0 * h);
            assert!(
                (fd - f[s]).abs() < 1e-6 * f[s].abs(),
                "{seed} θ {s}: {} vs {fd}",
                f[s]
            );
            assert!(f[s].abs() > 1.0, "{seed}: {}", f[s]);
        }
    }
}

#[test]
fn tangent_and_damping_match_central_differences() {
    for tau in [0.0, 7e-4] {
        let p = element(tau);
        let tab = p.tables();
        let (e, ed) = deformed(&p, 7);
        let (f, k, c) = p.tangent(&tab, &e, &ed);
        let f0 = p.internal_force(&tab, &e, &ed);
        assert_eq!(f, f0);
        let mats: &[(usize, &[[f64; 14]; 14])] = if tau > 0.0 {
            &[(0, &k), (1, &c)]
        } else {
            &[(0, &k)]
        };
        check_jacobians([e, ed, [0.0; 14]], mats, 1e-7, 1e-6, |x| {
            p.internal_force(&tab, &x[0], &x[1])
        });
    }
}

/// The frames (t_i, d2_i) of `e` rotated by `rot` (columns), as the angle element's
/// coordinates: r and r_x rotated, θ_i the angle about t'_i from P(t⁰ → t'_i) d⁰ to R d2_i.
fn rotated(p: &Angle3, e: &[f64; 14], rot: [[f64; 3]; 3]) -> [f64; 14] {
    let apply = |v: [f64; 3]| [0, 1, 2].map(|i| (0..3).map(|k| rot[k][i] * v[k]).sum::<f64>());
    let mut out = *e;
    for node in 0..2 {
        let o = 7 * node;
        let a = v3(e, o + 3);
        let d2 = apply(p.director(a, e[o + 6]));
        let (r, a2) = (apply(v3(e, o)), apply(a));
        out[o..o + 3].copy_from_slice(&r);
        out[o + 3..o + 6].copy_from_slice(&a2);
        let t = unit(&a2);
        let u = reference(&p.t0, &p.d0, &t);
        // keep the angle on the branch nearest the original (the energy sees differences)
        let mut th = crate::math::atan2(dot(&cross(&u, &d2), &t), dot(&u, &d2));
        while th - e[o + 6] > PI {
            th -= 2.0 * PI;
        }
        while th - e[o + 6] < -PI {
            th += 2.0 * PI;
        }
        out[o + 6] = th;
    }
    out
}

#[test]
fn strain_energy_is_objective() {
    // a rigid rotation of a deformed element (its section frames turned with it) leaves the
    // strain energy and the twist unchanged, though the angles themselves change (the
    // reference frames P(t⁰ → t) d⁰ do not rotate with the element)
    let p = element(0.0);
    let tab = p.tables();
    let (e, _) = deformed(&p, 11);
    let u0 = p.strain_energy(&tab, &e);
    let phi0 = p.twist(&tab, &e);
    let n3 = 1.0 / 3f64.sqrt();
    for (axis, angle) in [
        ([n3, -n3, n3], 0.9),
        ([0.0, 1.0, 0.0], 1.4),
        ([1.0, 0.0, 0.0], -0.5),
    ] {
        let (s, c) = f64::sin_cos(angle);
        let rot = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].map(|v: [f64; 3]| {
            let kv = cross(&axis, &v);
            let kd = dot(&axis, &v);
            [0, 1, 2].map(|i| c * v[i] + s * kv[i] + (1.0 - c) * kd * axis[i])
        });
        let er = rotated(&p, &e, rot);
        let moved = (er[6] - e[6]).abs() + (er[13] - e[13]).abs();
        assert!(moved > 1e-3, "the angles did not change: {moved}");
        let u = p.strain_energy(&tab, &er);
        assert!((u - u0).abs() < 1e-10 * u0, "{angle}: {u} vs {u0}");
        assert!((p.twist(&tab, &er) - phi0).abs() < 1e-12, "{angle}");
    }
}

#[test]
fn twist_inertia_is_lagrange_of_its_kinetic_energy() {
    // ρI_p(l/2) θ̈ + twist_inertia = d/dt ∂T_t/∂ė − ∂T_t/∂e by central differences of the
    // twist kinetic energy T_t (quadratic in ė: its ė-gradient by differences is exact)
    let p = element(0.0);
    let (e, ed) = deformed(&p, 5);
    let r = noise(9, 14);
    let ea: [f64; 14] = std::array::from_fn(|k| 40.0 * r[k]);
    let mut f = p.twist_inertia(&e, &ed, &ea);
    for s in THETA {
        f[s] += p.node_inertia() * ea[s];
    }
    // T_t = Σ ½k ω², ω = θ̇ + σ·ṙ_x (σ itself: `spin_is_the_turn_rate_of_the_reference_frame`)
    let tt = |e: &[f64; 14], ed: &[f64; 14]| {
        let k = p.node_inertia();
        (0..2)
            .map(|n| {
                let (xs, ts) = (SLOPE[n], THETA[n]);
                let w = ed[ts] + dot(&spin(&p.t0, &v3(e, xs)), &v3(ed, xs));
                0.5 * k * w * w
            })
            .sum::<f64>()
    };
    let grad_rate = |e: &[f64; 14], ed: &[f64; 14], i: usize| {
        let (mut vp, mut vm) = (*ed, *ed);
        vp[i] += 1.0;
        vm[i] -= 1.0;
        0.5 * (tt(e, &vp) - tt(e, &vm))
    };
    let h = 1e-6;
    let fmax = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(fmax > 0.0);
    for i in 0..14 {
        let ep: [f64; 14] = std::array::from_fn(|k| e[k] + h * ed[k]);
        let em: [f64; 14] = std::array::from_fn(|k| e[k] - h * ed[k]);
        let vp: [f64; 14] = std::array::from_fn(|k| ed[k] + h * ea[k]);
        let vm: [f64; 14] = std::array::from_fn(|k| ed[k] - h * ea[k]);
        let ddt = (grad_rate(&ep, &vp, i) - grad_rate(&em, &vm, i)) / (2.0 * h);
        let (mut xp, mut xm) = (e, e);
        xp[i] += h;
        xm[i] -= h;
        let dq = (tt(&xp, &ed) - tt(&xm, &ed)) / (2.0 * h);
        let want = ddt - dq;
        assert!(
            (f[i] - want).abs() < 1e-7 * fmax,
            "{i}: {} vs {want} (of {fmax:e})",
            f[i]
        );
    }
}

#[test]
fn twist_inertia_tangent_matches_central_differences() {
    let p = element(0.0);
    let (e, ed) = deformed(&p, 3);
    let r = noise(4, 14);
    let ea: [f64; 14] = std::array::from_fn(|k| 40.0 * r[k]);
    let mut k = [[0.0; 14]; 14];
    let mut c = [[0.0; 14]; 14];
    let (f, m) = p.twist_inertia_tangent((&e, &ed, &ea), &mut k, &mut c);
    let f0 = p.twist_inertia(&e, &ed, &ea);
    let fmax = f0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for i in 0..14 {
        assert!((f[i] - f0[i]).abs() <= 1e-14 * fmax, "force {i}");
    }
    check_jacobians([e, ed, ea], &[(0, &k), (1, &c), (2, &m)], 1e-6, 1e-6, |x| {
        p.twist_inertia(&x[0], &x[1], &x[2])
    });
}

#[test]
fn energies_equal_the_director_elements_on_the_same_frames() {
    // the director element (r_y = the section axis d2, unit and ⟂ t: its penalty is zero) of a
    // round undamped rod has the same strain energy, and its director kinetic energy with
    // ṙ_y = ḋ2 is the same twist kinetic energy (an independent formulation of both)
    let p = element(0.0);
    let tab = p.tables();
    let dp = props(true, 0.0, 1.0);
    let dtab = dp.tables();
    for seed in [21, 22, 23] {
        let (mut e, ed) = deformed(&p, seed);
        // twist within (−π, π) per element (the director element's range)
        e[13] = e[6] + 0.4 * (e[13] - e[6]);
        let d2 = |e: &[f64; 14], node: usize| p.director(v3(e, 7 * node + 3), e[7 * node + 6]);
        let to18 = |e: &[f64; 14]| {
            let mut x = [0.0; 18];
            for node in 0..2 {
                x[9 * node..9 * node + 6].copy_from_slice(&e[7 * node..7 * node + 6]);
                x[9 * node + 6..9 * node + 9].copy_from_slice(&d2(e, node));
            }
            x
        };
        let x = to18(&e);
        let ua = p.strain_energy(&tab, &e);
        let ud = dp.strain_energy(&dtab, &x);
        assert!((ua - ud).abs() < 1e-11 * ud, "{seed}: {ua} vs {ud}");
        assert!(p.twist(&tab, &e).abs() > 1e-2, "{seed}: untwisted");
        // rates: ṙ_y = d/dt d2(r_x, θ) by central differences
        let h = 1e-7;
        let ep: [f64; 14] = std::array::from_fn(|k| e[k] + h * ed[k]);
        let em: [f64; 14] = std::array::from_fn(|k| e[k] - h * ed[k]);
        let (xp, xm) = (to18(&ep), to18(&em));
        let xd: [f64; 18] = std::array::from_fn(|k| (xp[k] - xm[k]) / (2.0 * h));
        let ta = p.kinetic_energy(&p.cable.mass_patterns(), &e, &ed);
        let td = dp.kinetic_energy(&dp.mass_matrix(), &dtab, &x, &xd);
        assert!((ta - td).abs() < 1e-8 * td, "{seed}: {ta} vs {td}");
    }
}

#[test]
fn chart_margin_and_refusals() {
    let p = element(0.0);
    let (e, _) = deformed(&p, 1);
    let m = p.chart_margin(&e);
    assert!(m > 1.0 && m <= 2.0, "{m}");
    let mut back = e;
    for c in 0..3 {
        back[10 + c] = -p.t0[c];
    }
    assert!(p.chart_margin(&back).abs() < 1e-15);
    let oval = props(false, 0.0, 2.0);
    let err = Angle3::new(oval, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]).unwrap_err();
    assert!(
        err.contains("E·I_y") && err.contains("torsion_element"),
        "{err}"
    );
    let err = Angle3::new(props(false, 0.0, 1.0), [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
    assert!(err.unwrap_err().contains("parallel"));
}

#[test]
fn reference_twist_by_solid_angles_is_the_transported_frames_twist() {
    // φ_ref = twist_angle of the reference frames P(t⁰ → t_i) d⁰ (the director element's
    // transport, with its written-out gradient plus the frames' spin ∓σ), value and gradient
    use crate::model::ancf3d::kernel::twist_gradient;
    let p = element(0.0);
    let r = noise(17, 90);
    for k in 0..10 {
        let a: [[f64; 3]; 3] = std::array::from_fn(|v| {
            std::array::from_fn(|c| {
                (1.0 + 0.1 * r[9 * k + 3 * v]) * p.t0[c] + 0.5 * r[9 * k + 3 * v + c]
            })
        });
        let (phi, g) = p.reference_twist(&a);
        let u = |a: &[f64; 3]| reference(&p.t0, &p.d0, &unit(a));
        let (want, gw) = twist_gradient(&[a[0], u(&a[0]), a[1], u(&a[1]), a[2]]);
        let (s0, s1) = (spin(&p.t0, &a[0]), spin(&p.t0, &a[1]));
        let gwant = [
            lin2(1.0, &gw[0], -1.0, &s0),
            lin2(1.0, &gw[2], 1.0, &s1),
            gw[4],
        ];
        assert!((phi - want).abs() < 1e-13, "{k}: {phi} vs {want}");
        assert!(want.abs() > 1e-3, "{k}: {want}");
        for v in 0..3 {
            for c in 0..3 {
                assert!(
                    (g[v][c] - gwant[v][c]).abs() < 1e-12,
                    "{k} {v} {c}: {:?} vs {:?}",
                    g[v],
                    gwant[v]
                );
            }
        }
    }
}
