//! Tests of the 3D cable and the director element ([`super::Ancf3Props`]).

use super::*;
use crate::model::ancf::{AncfProps, Vec8};
use crate::scene::StrainModel;

/// Steel rod d = 2 mm (the paper's), element length 0.05 m; optionally E·I_y ≠ E·I_z.
pub(crate) fn props(torsion: bool, tau: f64, ei_ratio: f64) -> Ancf3Props {
    let (e, g, rho, d) = (210e9, 210e9 / 2.6, 7850.0, 2e-3);
    let a = PI * d * d / 4.0;
    let i = a * d * d / 16.0;
    Ancf3Props {
        length: 0.05,
        rho_a: rho * a,
        rho_ip: rho * 2.0 * i,
        ea: e * a,
        ei_y: e * i * ei_ratio,
        ei_z: e * i,
        gj: g * 2.0 * i,
        damping_time: tau,
        director: torsion,
        reference: None,
        taper: None,
    }
}

use std::f64::consts::PI;

/// Deterministic pseudo-random numbers in [−1, 1].
pub(crate) fn noise(seed: u64, n: usize) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        })
        .collect()
}

/// A frame (columns x̄, ȳ, z̄) rotated by `angle` about the unit `axis`.
fn frame(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let rot = |v: [f64; 3]| {
        let (s, c) = angle.sin_cos();
        let kv = cross(&axis, &v);
        let kd = dot(&axis, &v);
        [0, 1, 2].map(|i| c * v[i] + s * kv[i] + (1.0 - c) * kd * axis[i])
    };
    [
        rot([1.0, 0.0, 0.0]),
        rot([0.0, 1.0, 0.0]),
        rot([0.0, 0.0, 1.0]),
    ]
}

/// A bent, stretched and twisted element (and a rate), deterministic.
fn deformed<const D: usize>(p: &Ancf3Props, seed: u64) -> ([f64; D], [f64; D]) {
    let n3 = 1.0 / 3f64.sqrt();
    let f = frame([n3, -n3, n3], 0.7);
    let mut e: [f64; D] = straight([0.1, -0.2, 0.3], f, p.length, p.director)
        .try_into()
        .unwrap();
    let r = noise(seed, 2 * D);
    for k in 0..D {
        // positions move by ≤ 2 mm, slopes and directors by ≤ 0.15
        let s = if k % 9 < 3 && p.director || !p.director && k % 6 < 3 {
            2e-3
        } else {
            0.15
        };
        e[k] += s * r[k];
    }
    let ed: [f64; D] = std::array::from_fn(|k| 3.0 * r[D + k]);
    (e, ed)
}

fn check_tangent<const D: usize>(p: &Ancf3Props) {
    let tab = p.tables();
    let (e, ed) = deformed::<D>(p, 7);
    let (f, k, c) = p.tangent(&tab, &e, &ed);
    let fast = p.internal_force(&tab, &e, &ed);
    let fmax = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for i in 0..D {
        assert!((f[i] - fast[i]).abs() <= 1e-13 * fmax, "force {i}");
    }
    let kmax = k.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let cmax = c.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let (mut ek, mut ec) = (0.0f64, 0.0f64);
    for j in 0..D {
        let h = 1e-6;
        let (mut ep, mut em) = (e, e);
        ep[j] += h;
        em[j] -= h;
        let (fp, fm) = (
            p.internal_force(&tab, &ep, &ed),
            p.internal_force(&tab, &em, &ed),
        );
        let (mut vp, mut vm) = (ed, ed);
        vp[j] += h;
        vm[j] -= h;
        let (gp, gm) = (
            p.internal_force(&tab, &e, &vp),
            p.internal_force(&tab, &e, &vm),
        );
        for i in 0..D {
            ek = ek.max((((fp[i] - fm[i]) / (2.0 * h)) - k[i][j]).abs());
            ec = ec.max((((gp[i] - gm[i]) / (2.0 * h)) - c[i][j]).abs());
        }
    }
    eprintln!(
        "torsion {} tau {}: |K| {kmax:.3e}, FD error {:.1e}; |C| {cmax:.3e}, FD error {:.1e}",
        p.director,
        p.damping_time,
        ek / kmax,
        ec / cmax.max(1e-300)
    );
    assert!(ek <= 1e-6 * kmax, "K: {ek:e} of {kmax:e}");
    assert!(ec <= 1e-6 * cmax.max(kmax * p.damping_time), "C: {ec:e}");
    if p.damping_time == 0.0 {
        assert_eq!(cmax, 0.0);
        // symmetric (a Hessian) without damping
        for i in 0..D {
            for j in 0..D {
                assert!((k[i][j] - k[j][i]).abs() <= 1e-9 * kmax, "K sym {i} {j}");
            }
        }
    } else {
        assert!(cmax > 0.0);
    }
}

/// Stiffnesses with EA/l ≈ EI/l³ ≈ GJ/l, so that no part hides behind the axial one in
/// the relative error.
fn balanced(torsion: bool, tau: f64) -> Ancf3Props {
    Ancf3Props {
        ea: 1.0,
        ei_y: 2e-3,
        ei_z: if torsion { 3e-3 } else { 2e-3 },
        gj: 1.0,
        ..props(torsion, tau, 1.0)
    }
}

#[test]
fn tangent_and_damping_match_central_differences() {
    for tau in [0.0, 7e-4] {
        check_tangent::<18>(&props(true, tau, 1.0));
        check_tangent::<18>(&props(true, tau, 0.3));
        check_tangent::<12>(&props(false, tau, 1.0));
        check_tangent::<18>(&balanced(true, tau));
        check_tangent::<12>(&balanced(false, tau));
    }
}

fn check_gradient<const D: usize>(p: &Ancf3Props) {
    let tab = p.tables();
    let (e, _) = deformed::<D>(p, 11);
    let f = p.internal_force(&tab, &e, &[0.0; D]);
    let fmax = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for j in 0..D {
        let h = 1e-6;
        let (mut ep, mut em) = (e, e);
        ep[j] += h;
        em[j] -= h;
        let fd =
            (p.strain_energy(&p.tables(), &ep) - p.strain_energy(&p.tables(), &em)) / (2.0 * h);
        assert!((fd - f[j]).abs() <= 1e-6 * fmax, "{j}: {fd} vs {}", f[j]);
    }
}

#[test]
fn force_is_the_gradient_of_the_strain_energy() {
    check_gradient::<18>(&props(true, 0.0, 1.0));
    check_gradient::<18>(&props(true, 0.0, 2.5));
    check_gradient::<12>(&props(false, 0.0, 1.0));
    check_gradient::<18>(&balanced(true, 0.0));
    check_gradient::<12>(&balanced(false, 0.0));
}

fn check_rigid<const D: usize>(p: &Ancf3Props) {
    let tab = p.tables();
    let n3 = 1.0 / 3f64.sqrt();
    for (axis, angle) in [
        ([1.0, 0.0, 0.0], 0.0),
        ([n3, n3, -n3], 2.1),
        ([0.0, 0.6, 0.8], -1.0),
    ] {
        let f = frame(axis, angle);
        let e: [f64; D] = straight([0.3, -0.1, 2.0], f, p.length, p.director)
            .try_into()
            .unwrap();
        // rigid velocity: ω × (x − x0) + v0 for every position, ω × director
        let (w, v0) = ([1.5, -2.0, 0.7], [0.2, 0.1, -0.3]);
        let mut ed = [0.0; D];
        let st = if p.director { 9 } else { 6 };
        for node in 0..2 {
            let b = st * node;
            let r = [e[b] - e[0], e[b + 1] - e[1], e[b + 2] - e[2]];
            let wr = cross(&w, &r);
            for c in 0..3 {
                ed[b + c] = v0[c] + wr[c];
            }
            for blk in (3..st).step_by(3) {
                let d = [e[b + blk], e[b + blk + 1], e[b + blk + 2]];
                let wd = cross(&w, &d);
                ed[b + blk..b + blk + 3].copy_from_slice(&wd);
            }
        }
        let force = p.internal_force(&tab, &e, &ed);
        let fmax = force.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(fmax < 1e-14 * p.ea, "{axis:?} {angle}: {fmax:e}");
        let u = p.strain_energy(&p.tables(), &e);
        assert!(u < 1e-25, "{u:e}");
    }
}

/// ½ρI_p (l/2) Σ_nodes |v|² with v = ṙ_y − w_t × r_y written out here with the cross
/// product (w_t = r_x × ṙ_x/|r_x|²) on the nodal slopes and directors, independent of the
/// kernel's expanded form and of its tables.
fn director_energy(p: &Ancf3Props, e: &[f64; 18], ed: &[f64; 18]) -> f64 {
    let mut t = 0.0;
    for (x, y) in [(3, 6), (12, 15)] {
        let v3 = |v: &[f64; 18], s: usize| [v[s], v[s + 1], v[s + 2]];
        let (a, c) = (v3(e, x), v3(e, y));
        let (ad, cd) = (v3(ed, x), v3(ed, y));
        let w = cross(&a, &ad).map(|x| x / dot(&a, &a));
        let wc = cross(&w, &c);
        let v = [0, 1, 2].map(|i| cd[i] - wc[i]);
        t += 0.5 * (0.5 * p.length) * p.rho_ip * dot(&v, &v);
    }
    t
}

#[test]
fn director_inertia_is_lagrange_of_its_kinetic_energy() {
    // ρI_p∫NᵀN ë_y + director_inertia = d/dt ∂T_y/∂ė − ∂T_y/∂e by central differences of
    // the energy (T_y is quadratic in ė: its ė-gradient by differences is exact)
    for p in [props(true, 0.0, 1.0), balanced(true, 7e-4)] {
        let tab = p.tables();
        let (e, ed) = deformed::<18>(&p, 5);
        let r = noise(9, 18);
        let ea: [f64; 18] = std::array::from_fn(|k| 40.0 * r[k]);
        let mut f = p.director_inertia(&tab, &e, &ed, &ea);
        let mut pat = p.mass_patterns();
        pat.hermite = [[0.0; 4]; 4];
        pat.add_product(&ea, &mut f);
        let grad_rate = |e: &[f64; 18], ed: &[f64; 18], i: usize| {
            let (mut vp, mut vm) = (*ed, *ed);
            vp[i] += 1.0;
            vm[i] -= 1.0;
            0.5 * (director_energy(&p, e, &vp) - director_energy(&p, e, &vm))
        };
        let h = 1e-6;
        let fmax = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(fmax > 0.0);
        for i in 0..18 {
            let ep: [f64; 18] = std::array::from_fn(|k| e[k] + h * ed[k]);
            let em: [f64; 18] = std::array::from_fn(|k| e[k] - h * ed[k]);
            let vp: [f64; 18] = std::array::from_fn(|k| ed[k] + h * ea[k]);
            let vm: [f64; 18] = std::array::from_fn(|k| ed[k] - h * ea[k]);
            let ddt = (grad_rate(&ep, &vp, i) - grad_rate(&em, &vm, i)) / (2.0 * h);
            let (mut xp, mut xm) = (e, e);
            xp[i] += h;
            xm[i] -= h;
            let dq = (director_energy(&p, &xp, &ed) - director_energy(&p, &xm, &ed)) / (2.0 * h);
            let want = ddt - dq;
            assert!(
                (f[i] - want).abs() < 1e-7 * fmax,
                "{i}: {} vs {want} (of {fmax:e})",
                f[i]
            );
        }
        // the element's kinetic energy is the constant pattern's translational part plus T_y
        let mut m = p.mass_patterns();
        m.twist = [[0.0; 2]; 2];
        let mut mv = [0.0; 18];
        m.add_product(&ed, &mut mv);
        let tr: f64 = 0.5 * (0..18).map(|k| ed[k] * mv[k]).sum::<f64>();
        let want = tr + director_energy(&p, &e, &ed);
        let got = p.kinetic_energy(&p.mass_matrix(), &p.tables(), &e, &ed);
        assert!((got - want).abs() < 1e-13 * want, "{got} vs {want}");
    }
}

#[test]
fn director_inertia_tangent_matches_central_differences() {
    let p = props(true, 0.0, 1.0);
    let tab = p.tables();
    let (e, ed) = deformed::<18>(&p, 3);
    let r = noise(4, 18);
    let ea: [f64; 18] = std::array::from_fn(|k| 40.0 * r[k]);
    let mut k = Box::new([[0.0; 18]; 18]);
    let mut c = Box::new([[0.0; 18]; 18]);
    let (f, m) = p.director_tangent(&tab, (&e, &ed, &ea), &mut k, &mut c, [true; 3]);
    let f0 = p.director_inertia(&tab, &e, &ed, &ea);
    let fmax = f0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for i in 0..18 {
        assert!((f[i] - f0[i]).abs() <= 1e-14 * fmax, "force {i}");
    }
    check_jacobians([e, ed, ea], &[(0, &k), (1, &c), (2, &m)], 1e-6, 1e-6, |x| {
        p.director_inertia(&tab, &x[0], &x[1], &x[2])
    });
}

/// Central differences (step `h`) of `f` at x = (q, q̇, q̈) against each `(which, matrix)`
/// (∂f/∂x[which]), to `tol` of the matrix's largest entry, which must not vanish.
pub(crate) fn check_jacobians<const D: usize>(
    x: [[f64; D]; 3],
    mats: &[(usize, &[[f64; D]; D])],
    h: f64,
    tol: f64,
    f: impl Fn(&[[f64; D]; 3]) -> [f64; D],
) {
    for &(which, mat) in mats {
        let big = mat.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        assert!(big > 0.0, "{which}");
        for j in 0..D {
            let (mut xp, mut xm) = (x, x);
            xp[which][j] += h;
            xm[which][j] -= h;
            let (fp, fm) = (f(&xp), f(&xm));
            for i in 0..D {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                assert!(
                    (fd - mat[i][j]).abs() < tol * big,
                    "{which} ({i},{j}): {fd} vs {}",
                    mat[i][j]
                );
            }
        }
    }
}

#[test]
fn rigid_rotation_carries_director_inertia_for_the_twist_only() {
    // a bent, sheared, stretched element turning rigidly about Ω: T_y = ½ρI_p Σ w (Ω·t)²|t × r_y|²
    // over the nodes (w = l/2)
    let p = props(true, 0.0, 1.0);
    let (e, _) = deformed::<18>(&p, 2);
    let tab = p.tables();
    let (rs, ys) = p.slots();
    for om in [[0.0, 3.0, -2.0], [1.5, -2.0, 0.7], [4.0, 0.0, 0.0]] {
        let mut ed = [0.0; 18];
        for b in 0..6 {
            let s = 3 * b;
            let x = [e[s], e[s + 1], e[s + 2]];
            ed[s..s + 3].copy_from_slice(&cross(&om, &x));
        }
        let mut want = 0.0;
        for q in &tab.director {
            let (a, c) = (comb(&q.ds, &rs, &e), comb(&q.ny, &ys, &e));
            let t = a.map(|x| x / dot(&a, &a).sqrt());
            let tc = cross(&t, &c);
            let wt = dot(&om, &t);
            want += 0.5 * q.w * p.rho_ip * wt * wt * dot(&tc, &tc);
        }
        let got = director_energy(&p, &e, &ed);
        assert!(
            (got - want).abs() < 1e-12 * want.max(1e-12),
            "{om:?}: {got} vs {want}"
        );
    }
}

#[test]
fn rigid_motion_gives_zero_energy_and_force() {
    check_rigid::<18>(&props(true, 7e-4, 1.0));
    check_rigid::<18>(&props(true, 7e-4, 0.4));
    check_rigid::<12>(&props(false, 7e-4, 1.0));
}

#[test]
fn rigid_rotation_of_a_bent_element_is_not_damped() {
    // bent in the x–y plane, spinning about ẑ (⟂ every tangent): the damping force is zero
    // for both variants (the cable's curvature rate is taken relative to the tangent)
    for torsion in [true, false] {
        let p = props(torsion, 7e-4, 1.0);
        let st = p.dofs() / 2;
        let l = p.length;
        let mut e = vec![0.0; p.dofs()];
        let mut ed = vec![0.0; p.dofs()];
        let w = [0.0, 0.0, 3.0];
        for node in 0..2 {
            let (ang, b) = (0.4 * node as f64, st * node);
            let (sn, cs) = f64::sin_cos(ang);
            let r = [
                l * sn / 0.4 * node as f64,
                l * (1.0 - cs) / 0.4 * node as f64,
                0.0,
            ];
            let mut vecs = vec![r, [cs, sn, 0.0]];
            if torsion {
                vecs.push([-sn, cs, 0.0]);
            }
            for (k, v) in vecs.iter().enumerate() {
                e[b + 3 * k..b + 3 * k + 3].copy_from_slice(v);
                ed[b + 3 * k..b + 3 * k + 3].copy_from_slice(&cross(&w, v));
            }
        }
        let tab = p.tables();
        let (f, f0): (Vec<f64>, Vec<f64>) = if torsion {
            let e: [f64; 18] = e.clone().try_into().unwrap();
            let ed: [f64; 18] = ed.clone().try_into().unwrap();
            let f = p.internal_force(&tab, &e, &ed).to_vec();
            (f, p.internal_force(&tab, &e, &[0.0; 18]).to_vec())
        } else {
            let e: [f64; 12] = e.clone().try_into().unwrap();
            let ed: [f64; 12] = ed.clone().try_into().unwrap();
            let f = p.internal_force(&tab, &e, &ed).to_vec();
            (f, p.internal_force(&tab, &e, &[0.0; 12]).to_vec())
        };
        let fmax = f0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(fmax > 1.0, "bent: {fmax}");
        for (a, b) in f.iter().zip(&f0) {
            assert!((a - b).abs() < 1e-12 * fmax, "{torsion}: {a} vs {b}");
        }
    }
}

/// The viewer's samples carry the element's own strain measures ([`Ancf3Props::strains_at`]
/// with torsion; the cable's curvature |r_x × r_xx|/|r_x|²), the Hermite position and an
/// orthonormal section frame whose d2 lies in the plane of r_x and r_y.
#[test]
fn samples_carry_the_elements_own_strains() {
    let p = props(true, 0.0, 1.0);
    let (e, ed) = deformed::<18>(&p, 7);
    for xi in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let s = p.sample(&e, &ed, xi);
        let [eps, k2, k3, tau] = p.strains_at(&e, xi);
        assert_eq!(
            [s.axial_strain, s.curvature[0], s.curvature[1], s.twist],
            [eps, k2, k3, tau]
        );
        let (h, _, _) = hermite(xi, p.length);
        for c in 0..3 {
            let r = h[0] * e[c] + h[1] * e[3 + c] + h[2] * e[9 + c] + h[3] * e[12 + c];
            assert!((s.position[c] - r).abs() < 1e-15, "{xi}");
        }
        let [t, d2, d3] = s.frame;
        let ry: [f64; 3] = std::array::from_fn(|c| (1.0 - xi) * e[6 + c] + xi * e[15 + c]);
        assert!(dot(&t, &d2).abs() < 1e-14 && dot(&d2, &d3).abs() < 1e-14);
        assert!(
            dot(&cross(&t, &ry), &d2).abs() < 1e-14,
            "d2 in the plane of r_x, r_y"
        );
    }
    let p = props(false, 0.0, 1.0);
    let (e, ed) = deformed::<12>(&p, 11);
    for xi in [0.1, 0.5, 0.9] {
        let s = p.sample(&e, &ed, xi);
        let (_, ds, dds) = hermite(xi, p.length);
        let v = |w: &[f64; 4], o: usize| -> [f64; 3] {
            std::array::from_fn(|c| {
                w[0] * e[c + o] + w[1] * e[3 + c + o] + w[2] * e[6 + c + o] + w[3] * e[9 + c + o]
            })
        };
        let (a, b) = (v(&ds, 0), v(&dds, 0));
        let k = cross(&a, &b);
        let want = dot(&k, &k).sqrt() / dot(&a, &a);
        assert!(
            (s.bending() - want).abs() < 1e-12 * want,
            "{xi}: {} vs {want}",
            s.bending()
        );
        assert_eq!(s.axial_strain, dot(&a, &a).sqrt() - 1.0);
        assert_eq!(s.twist, 0.0);
    }
}

#[test]
fn strain_measures_of_a_helix_match_the_closed_form() {
    // Helix of radius ρ, pitch parameter h, arc length s: curvature k = ρ/λ²
    // (λ² = ρ² + h²); Frenet frame t, n, b. Director d2 = cos φ n + sin φ b with
    // φ = φ0 + φ1 s; the reference arc length x = s/(1 + ε). Then, per reference length,
    // κ2 = (1+ε) k sin φ, κ3 = (1+ε) k cos φ. r_y = α d2 + β t (stretched and sheared
    // director: the measures must not see α, β). (The twist is the element's, from its
    // nodal frames: `twist_is_zero_for_parallel_transported_frames`.)
    let (rho, h, eps, phi0, phi1, al, be): (f64, f64, f64, f64, f64, f64, f64) =
        (0.3, 0.12, 0.02, 0.4, 2.0, 1.3, 0.2);
    let lam = (rho * rho + h * h).sqrt();
    let k = rho / (lam * lam);
    let st = 1.0 + eps;
    for s in [0.0, 0.37, 1.9] {
        let th = s / lam;
        let (sn, cs) = th.sin_cos();
        let t = [-rho * sn / lam, rho * cs / lam, h / lam];
        let n = [-cs, -sn, 0.0];
        let b = cross(&t, &n);
        // Frenet: t′ = k n (per s)
        let phi = phi0 + phi1 * s;
        let (sp, cp) = phi.sin_cos();
        let d2 = lin2(cp, &n, sp, &b);
        let ts = [k * n[0], k * n[1], k * n[2]];
        // derivatives by the reference length x: d/dx = (1 + ε) d/ds
        let rx = t.map(|v| st * v);
        let rxx = ts.map(|v| st * st * v);
        let ry = lin2(al, &d2, be, &t);
        let [e, k2, k3] = strains(rx, rxx, ry);
        let want = [eps, st * k * sp, st * k * cp];
        for (g, w) in [e, k2, k3].iter().zip(want) {
            assert!(
                (g - w).abs() < 1e-13,
                "s {s}: {:?} vs {want:?}",
                [e, k2, k3]
            );
        }
    }
}

#[test]
fn uniformly_twisted_element_has_the_twist_of_its_nodes() {
    // r_y turns by Δ about the axis between the nodes: τ_e = Δ/l and the twist energy is
    // ½GJΔ²/l exactly for any Δ ∈ (−π, π) (the linear r_y's pointwise twist at 3 Gauss
    // points was too stiff by 1.0005 at 30°, 1.072 at 90°: docs/references.md §7.1).
    let p = props(true, 0.0, 1.0);
    let l = p.length;
    for deg in [-170.0, -45.0, 10.0, 30.0, 45.0, 90.0, 150.0, 179.0] {
        let delta: f64 = deg * PI / 180.0;
        let n3 = 1.0 / 3f64.sqrt();
        let f0 = frame([n3, n3, n3], 0.4);
        // frame rotated about its own axis by Δ: y1 = R(x̄, Δ) ȳ
        let y1 = {
            let (s, c) = delta.sin_cos();
            lin2(c, &f0[1], s, &f0[2])
        };
        let mut e: [f64; 18] = straight([0.0; 3], f0, l, true).try_into().unwrap();
        e[15..18].copy_from_slice(&y1);
        for xi in [0.0, 0.2, 0.5, 0.9] {
            let [eps, k2, k3, tau] = p.strains_at(&e, xi);
            assert!(eps.abs() < 1e-15 && k2.abs() < 1e-12 && k3.abs() < 1e-12);
            assert!((tau * l - delta).abs() < 1e-14, "{deg}° ξ {xi}: {tau}");
        }
        let u = p.strain_energy(&p.tables(), &e);
        let got = u / (0.5 * p.gj * delta * delta / l);
        assert!((got - 1.0).abs() < 1e-12, "{deg}: {got}");
    }
}

/// Nodal frames of an element bent in the plane ⟂ `normal` (arc of angle `bend`), the
/// section directors turned by `theta` about the tangents from the in-plane normal
/// (twist-free: d2 at node 1 is d2 at node 0 carried along the arc), node 1 turned by
/// `extra` more about its tangent.
fn arc_element(p: &Ancf3Props, f: [[f64; 3]; 3], bend: f64, theta: f64, extra: f64) -> [f64; 18] {
    let l = p.length;
    let (x, y, z) = (f[0], f[1], f[2]);
    let mut e = [0.0; 18];
    for node in 0..2 {
        let a = bend * node as f64;
        let (sa, ca) = a.sin_cos();
        let rad = l / bend;
        let r = lin2(rad * sa, &x, rad * (1.0 - ca), &y);
        let t = lin2(ca, &x, sa, &y);
        let nrm = lin2(-sa, &x, ca, &y);
        let th = theta + extra * node as f64;
        let (st, ct) = th.sin_cos();
        let d2 = lin2(ct, &nrm, st, &z);
        e[9 * node..9 * node + 3].copy_from_slice(&r);
        e[9 * node + 3..9 * node + 6].copy_from_slice(&t);
        e[9 * node + 6..9 * node + 9].copy_from_slice(&d2);
    }
    e
}

#[test]
fn written_out_twist_gradient_equals_nested_ad() {
    // the written-out gradient of the element twist against forward-mode AD of the angle,
    // on bent, stretched, sheared and twisted elements
    for (k, p) in [props(true, 0.0, 1.0), balanced(true, 0.0)]
        .iter()
        .enumerate()
    {
        for seed in [2, 5, 7, 11] {
            let (e, _) = deformed::<18>(p, seed + k as u64);
            let tab = p.tables();
            let (rs, _) = p.slots();
            let [a, b, c, d] = TWIST_SLOTS.map(|s| [e[s], e[s + 1], e[s + 2]]);
            let u = [a, b, c, d, comb(&tab.mid, &rs, &e)];
            let (phi, g) = twist_gradient(&u);
            let (phi_ad, g_ad) = twist_gradient_ad(&u);
            assert_eq!(phi, phi_ad);
            assert!(phi.abs() > 1e-3, "{phi}");
            let big = g_ad.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
            for (x, y) in g.iter().flatten().zip(g_ad.iter().flatten()) {
                assert!((x - y).abs() <= 1e-13 * big, "{seed}: {x} vs {y}");
            }
        }
    }
}

#[test]
fn twist_is_zero_for_parallel_transported_frames() {
    // an element bent into an arc in any plane, its section turned by any angle about the
    // tangent without twisting: τ_e = 0 to rounding, so a round rod's energy is the same
    // whatever the bending plane relative to the section (the issue-23 isotropy); an
    // extra turn Δ of node 1 gives τ_e = Δ/l
    let p = props(true, 0.0, 1.0);
    let n3 = 1.0 / 3f64.sqrt();
    for (axis, ang) in [([0.0, 0.0, 1.0], 0.0), ([n3, -n3, n3], 1.3)] {
        let f = frame(axis, ang);
        for bend in [0.05, 0.4, 1.2] {
            let u0 = p.strain_energy(&p.tables(), &arc_element(&p, f, bend, 0.0, 0.0));
            for theta in [0.3, 1.0, 2.5, -2.0] {
                let e = arc_element(&p, f, bend, theta, 0.0);
                let tau = p.twist_rate(&e);
                assert!(tau.abs() * p.length < 1e-15, "{bend} {theta}: {tau:e}");
                let u = p.strain_energy(&p.tables(), &e);
                assert!((u - u0).abs() <= 1e-13 * u0, "{bend} {theta}: {u} vs {u0}");
                for extra in [0.2, -1.0] {
                    let e = arc_element(&p, f, bend, theta, extra);
                    let tau = p.twist_rate(&e);
                    assert!((tau * p.length - extra).abs() < 1e-14, "{tau}");
                }
            }
        }
    }
}

#[test]
fn in_plane_element_equals_the_planar_element() {
    // an in-plane (x–y) bent, stretched element: κ3 is the planar signed curvature, κ2 = τ
    // = 0 and the penalty vanishes for r_y = ẑ × t; energy, force and mass equal the planar
    // kernel's (Exact strain) to rounding.
    let p3 = props(true, 0.0, 1.7);
    let p2 = AncfProps {
        length: p3.length,
        rho_a: p3.rho_a,
        ea: p3.ea,
        ei: p3.ei_z,
        damping_time: 0.0,
        strain: StrainModel::Exact,
        reference: None,
        taper: None,
    };
    let e2 = Vec8::from_column_slice(&[0.01, -0.02, 0.9, 0.3, 0.055, 0.01, 0.7, 0.75]);
    for torsion in [true, false] {
        let p = Ancf3Props {
            director: torsion,
            reference: None,
            ..p3
        };
        let p = if torsion {
            p
        } else {
            Ancf3Props { ei_y: p.ei_z, ..p }
        };
        let st = p.dofs() / 2;
        let mut e3 = vec![0.0; p.dofs()];
        for node in 0..2 {
            let b = st * node;
            let (sx, sy) = (e2[4 * node + 2], e2[4 * node + 3]);
            e3[b..b + 6].copy_from_slice(&[e2[4 * node], e2[4 * node + 1], 0.0, sx, sy, 0.0]);
            if torsion {
                let n = (sx * sx + sy * sy).sqrt();
                e3[b + 6..b + 9].copy_from_slice(&[-sy / n, sx / n, 0.0]);
            }
        }
        let (u2, u3) = (p2.strain_energy(&e2), p.strain_energy(&p.tables(), &e3));
        assert!((u2 - u3).abs() <= 1e-14 * u2, "{torsion}: {u2} vs {u3}");
        let f2 = p2.elastic(&e2, &Vec8::zeros(), false).force;
        let tab = p.tables();
        let f3: Vec<f64> = if torsion {
            p.internal_force(
                &tab,
                &<[f64; 18]>::try_from(e3.clone()).unwrap(),
                &[0.0; 18],
            )
            .to_vec()
        } else {
            p.internal_force(
                &tab,
                &<[f64; 12]>::try_from(e3.clone()).unwrap(),
                &[0.0; 12],
            )
            .to_vec()
        };
        let fmax = f2.amax();
        for node in 0..2 {
            let b = st * node;
            for (k2, k3) in [(0, 0), (1, 1), (2, 3), (3, 4)] {
                let (x2, x3) = (f2[4 * node + k2], f3[b + k3]);
                assert!(
                    (x2 - x3).abs() <= 1e-12 * fmax,
                    "{torsion} {node} {k2}: {x2} {x3}"
                );
            }
            for k3 in [2, 5] {
                assert!(
                    f3[b + k3].abs() <= 1e-12 * fmax,
                    "out of plane {}",
                    f3[b + k3]
                );
            }
            if torsion {
                for k3 in 6..9 {
                    assert!(f3[b + k3].abs() <= 1e-12 * fmax, "r_y force {}", f3[b + k3]);
                }
            }
        }
        let (m2, m3) = (p2.mass_matrix(), p.mass_matrix());
        let d = p.dofs();
        for i in 0..8 {
            for j in 0..8 {
                let map = |k: usize| st * (k / 4) + [0, 1, 3, 4][k % 4];
                assert_eq!(m2[(i, j)], m3[map(i) * d + map(j)]);
            }
        }
    }
}

#[test]
fn mass_and_gravity_match_quadrature() {
    // independent: ρA ∫SᵀS by 5-point Gauss (exact for this degree), ρI_p ∫NᵀN lumped; total
    // translational mass ρA l
    let p = props(true, 0.0, 1.0);
    let l = p.length;
    let m = p.mass_matrix();
    let g = p.gravity_force([0.3, -9.81, 1.2]);
    let d = 18;
    let rs = [0, 3, 9, 12];
    let ys = [6, 15];
    let mut mi = [[0.0; 4]; 4];
    let mut yi = [[0.0; 2]; 2];
    let mut gi = [0.0; 4];
    for (xg, wg) in GAUSS5 {
        let xi = 0.5 * (xg + 1.0);
        let (s, _, _) = hermite(xi, l);
        for j in 0..4 {
            gi[j] += wg * 0.5 * l * p.rho_a * s[j];
            for k in 0..4 {
                mi[j][k] += wg * 0.5 * l * p.rho_a * s[j] * s[k];
            }
        }
    }
    // the director's ρI_p∫NᵀN lumped at the nodes (2-point Lobatto: the trapezoid rule)
    for (xi, wl) in [(0.0, 0.5 * l), (1.0, 0.5 * l)] {
        let n = [1.0 - xi, xi];
        for j in 0..2 {
            for k in 0..2 {
                yi[j][k] += wl * p.rho_ip * n[j] * n[k];
            }
        }
    }
    for c in 0..3 {
        for j in 0..4 {
            let want = gi[j] * [0.3, -9.81, 1.2][c];
            assert!((g[rs[j] + c] - want).abs() < 1e-15);
            for k in 0..4 {
                assert!((m[(rs[j] + c) * d + rs[k] + c] - mi[j][k]).abs() < 1e-17);
            }
        }
        for j in 0..2 {
            for k in 0..2 {
                assert!((m[(ys[j] + c) * d + ys[k] + c] - yi[j][k]).abs() < 1e-20);
            }
        }
    }
    let tot: f64 = [0, 2].iter().flat_map(|&j| [0, 2].map(|k| mi[j][k])).sum();
    assert!((tot - p.rho_a * l).abs() < 1e-16);
    // the patterns' product equals the dense matrix
    let a: [f64; 18] = std::array::from_fn(|k| (k as f64 * 0.37).sin());
    let mut ma = [0.0; 18];
    p.mass_patterns().add_product(&a, &mut ma);
    for i in 0..18 {
        let want: f64 = (0..18).map(|j| m[i * d + j] * a[j]).sum();
        assert!((ma[i] - want).abs() < 1e-16, "{i}");
    }
}

#[test]
fn segment_properties_and_refusals() {
    let text = r#"
        name = "rod"
        kind = "ancf"
        length = 0.4
        diameter = 2e-3
        youngs_modulus = 210e9
        poisson_ratio = 0.3
        density = 7850.0
        elements = 8
        damping_time = 7e-4
    "#;
    let seg: Segment = toml::from_str(text).unwrap();
    let p = Ancf3Props::of_segment(&seg, true).unwrap();
    // independent: the round rod by hand
    let want = props(true, 7e-4, 1.0);
    for (got, want) in [
        (p.length, want.length),
        (p.rho_a, want.rho_a),
        (p.rho_ip, want.rho_ip),
        (p.ea, want.ea),
        (p.ei_y, want.ei_y),
        (p.ei_z, want.ei_z),
        (p.gj, want.gj),
    ] {
        assert!((got - want).abs() <= 1e-14 * want, "{got} vs {want}");
    }
    assert_eq!(p.damping_time, 7e-4);
    let paper = Segment {
        strain: StrainModel::Paper,
        ..seg.clone()
    };
    let msg = Ancf3Props::of_segment(&paper, true).unwrap_err();
    assert!(msg.contains("\"rod\"") && msg.contains("strain"), "{msg}");
    let rect: Segment = toml::from_str(&format!(
        "{}\nsection = \"rectangle\"\nwidth = 2e-3\nheight = 4e-3",
        text.replace("diameter = 2e-3", "")
    ))
    .unwrap();
    assert!(Ancf3Props::of_segment(&rect, true).is_ok());
    let msg = Ancf3Props::of_segment(&rect, false).unwrap_err();
    assert!(
        msg.contains("\"rod\"") && msg.contains("torsion = false"),
        "{msg}"
    );
}

#[test]
fn cable_force_is_the_generic_path_bit_for_bit() {
    // undamped and damped, uniform and tapered, straight and with an axial reference
    let taper = SectionTable3 {
        ea: [1.0, 0.9, 0.8, 0.7, 0.6].map(|s| s * 660.0),
        ei: [0.9, 0.8, 0.7].map(|s| [s * 8.2e-3; 2]),
        rho_a: [0.0246; 5],
    };
    let reference = Reference3 {
        axial: [1e-3, -2e-3, 3e-3, 0.0, -1e-4],
        bending: [[0.0; 2]; 3],
        twist: 0.0,
        curvature: [0.0; 2],
    };
    for tau in [0.0, 1e-3] {
        for (taper, reference) in [(None, None), (Some(taper), Some(reference))] {
            let p = Ancf3Props {
                taper,
                reference,
                ..props(false, tau, 1.0)
            };
            let tab = p.tables();
            for seed in 1..5 {
                let (e, ed) = deformed::<CABLE_DOFS>(&p, seed);
                let fast = p.cable_force(&tab, &e, &ed);
                let generic = p.force_generic(&tab, &e, &ed);
                assert_eq!(fast.map(f64::to_bits), generic.map(f64::to_bits));
            }
        }
    }
}

#[test]
fn cable_refuses_unequal_bending_stiffness() {
    assert!(props(false, 0.0, 1.0).check().is_ok());
    assert!(props(true, 0.0, 2.0).check().is_ok());
    let msg = props(false, 0.0, 2.0).check().unwrap_err();
    assert!(
        msg.contains("torsion = false") && msg.contains("E·I_y"),
        "{msg}"
    );
}
