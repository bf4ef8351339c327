//! The held coordinates of a mounted root: a moving frame the root of a `root = "mounted"` beam
//! is clamped to. The held root coordinates are rigid functions of the mount's motion (values,
//! rates and accelerations: the elements' residuals then carry the base's inertial loads, and
//! the held rows' residual is the reaction including them); the free coordinates are carried
//! rigidly to place the initial state and to re-anchor the beam when a host's pose differs
//! from the predicted one; the rigid field of a turning mount gives the relative static start.
//! Dimension-free: a [`Space`] supplies the rigid motion of each kind of coordinate group.

use super::assembly::Model;
use super::component::{Env, LocalState};
use super::dofs::{Dof, RigidGroup};
use super::inertia::{MountInertia, MountWork, MAX_FIELDS};
use super::space::{Motion, Space};

/// A fixed-size scratch of a group's coordinates.
type G = [f64; 4];

impl<S: Space> Model<S> {
    /// The mount motion of the last Newton-matrix evaluation (`None` unless mounted).
    pub fn mount_at_matrix(&self) -> Option<Motion<S>> {
        self.mount_at_matrix.as_deref().copied()
    }

    /// The mount motion the held coordinates follow now (`None` unless mounted).
    pub fn mount_motion(&self) -> Option<&Motion<S>> {
        self.mount.as_deref()
    }

    /// Moves the held root coordinates with the mount: values, rates and accelerations of the
    /// frame moving as `m` (a mounted model only; otherwise nothing happens).
    pub fn set_mount(&mut self, m: &Motion<S>) {
        match &mut self.mount {
            Some(b) => **b = *m,
            None => return,
        }
        let zero = [0.0; 4];
        for g in self.groups.iter().filter(|g| is_held(g)) {
            let k = S::rigid_len(g.kind);
            let (mut q, mut v, mut a) = (zero, zero, zero);
            let rel = gather_held(g, &self.held_ref);
            S::carry(
                g.kind,
                m,
                [&rel[..k], &zero[..k], &zero[..k]],
                [&mut q[..k], &mut v[..k], &mut a[..k]],
            );
            for (c, d) in g.dofs.iter().enumerate() {
                if let Dof::Held(j) = *d {
                    let j = j as usize;
                    (self.held[j], self.held_v[j], self.held_a[j]) = (q[c], v[c], a[c]);
                }
            }
        }
    }

    /// Carries free coordinates given in the mount frame (`q`, e.g. the build's) to the frame
    /// moving as `m`, at rest relative to it: `q` becomes world values, `v` the rigid velocity
    /// field.
    pub fn carry_state(&self, m: &Motion<S>, q: &mut [f64], v: &mut [f64]) {
        let zero = [0.0; 4];
        for g in self.groups.iter().filter(|g| !is_held(g)) {
            let k = S::rigid_len(g.kind);
            let rel = gather_free(g, q);
            let (mut qo, mut vo, mut ao) = (zero, zero, zero);
            S::carry(
                g.kind,
                m,
                [&rel[..k], &zero[..k], &zero[..k]],
                [&mut qo[..k], &mut vo[..k], &mut ao[..k]],
            );
            scatter_free(g, &qo, q);
            scatter_free(g, &vo, v);
        }
    }

    /// Rates `v` and accelerations `a` of the free coordinates `q` (world values) at rest
    /// relative to the frame moving as `m`: each rigid group's values taken relative to the
    /// frame and carried back with the frame's rates (affine in `q`); the other coordinates
    /// (modal amplitudes, which are relative already) zero.
    pub fn rest_rates(&self, m: &Motion<S>, q: &[f64], v: &mut [f64], a: &mut [f64]) {
        v.fill(0.0);
        a.fill(0.0);
        for g in self.groups.iter().filter(|g| !is_held(g)) {
            let (vo, ao) = rest_of_group::<S>(g, m, &gather_free(g, q));
            scatter_free(g, &vo, v);
            scatter_free(g, &ao, a);
        }
    }

    /// ∂v/∂q and ∂a/∂q of [`Model::rest_rates`] as (row, column, value) entries: per rigid
    /// group, by unit differences of its coordinates (exact, the map being affine).
    fn rest_rate_jacobians(&self, m: &Motion<S>, q: &[f64]) -> [Vec<(usize, usize, f64)>; 2] {
        let mut out = [Vec::new(), Vec::new()];
        for g in self.groups.iter().filter(|g| !is_held(g)) {
            let k = S::rigid_len(g.kind);
            let field = |qg: &G| rest_of_group::<S>(g, m, qg);
            let q0 = gather_free(g, q);
            let (v0, a0) = field(&q0);
            for (c, dc) in g.dofs.iter().enumerate().take(k) {
                let Dof::Free(col) = *dc else { continue };
                let mut qp = q0;
                qp[c] += 1.0;
                let (v1, a1) = field(&qp);
                for (r, dr) in g.dofs.iter().enumerate().take(k) {
                    let Dof::Free(row) = *dr else { continue };
                    let (dv, da) = (v1[r] - v0[r], a1[r] - a0[r]);
                    if dv != 0.0 {
                        out[0].push((row as usize, col as usize, dv));
                    }
                    if da != 0.0 {
                        out[1].push((row as usize, col as usize, da));
                    }
                }
            }
        }
        out
    }

    /// Static equilibrium relative to a mount turning at a constant rate (the motion `m`, in
    /// world axes): [`crate::integrator::solve_relative_static`] with this model's rigid field
    /// ([`Model::rest_rates`]: the beam at rest in the mount frame) and its Jacobians. On
    /// success `state` holds q, the rest rates, accelerations and λ.
    pub fn solve_relative_static(
        &mut self,
        m: &Motion<S>,
        state: &mut crate::integrator::State,
        tol: f64,
    ) -> Result<usize, crate::integrator::StaticFailure> {
        crate::integrator::solve_relative_static(
            self,
            |model: &Self, q: &[f64], v: &mut [f64], a: &mut [f64]| model.rest_rates(m, q, v, a),
            |model: &Self, q: &[f64]| model.rest_rate_jacobians(m, q),
            state,
            tol,
        )
    }

    /// Re-anchors free coordinates, rates and accelerations (`acc` and any further
    /// acceleration-like vectors in `more`) from the frame moving as `from` to the frame moving
    /// as `to`: every group keeps its values, rates and accelerations relative to the frame, so
    /// strains and joint rows are unchanged.
    pub fn reanchor(
        &self,
        from: &Motion<S>,
        to: &Motion<S>,
        q: &mut [f64],
        v: &mut [f64],
        acc: &mut [&mut [f64]],
    ) {
        let zero = [0.0; 4];
        for g in self.groups.iter().filter(|g| !is_held(g)) {
            let k = S::rigid_len(g.kind);
            let (qg, vg) = (gather_free(g, q), gather_free(g, v));
            let (mut qr, mut vr, mut scratch) = (zero, zero, zero);
            S::uncarry(
                g.kind,
                from,
                [&qg[..k], &vg[..k], &zero[..k]],
                [&mut qr[..k], &mut vr[..k], &mut scratch[..k]],
            );
            for a in acc.iter_mut() {
                let ag = gather_free(g, a);
                let (mut ar, mut an) = (zero, zero);
                let (mut q2, mut v2) = (zero, zero);
                S::uncarry(
                    g.kind,
                    from,
                    [&qg[..k], &vg[..k], &ag[..k]],
                    [&mut q2[..k], &mut v2[..k], &mut ar[..k]],
                );
                S::carry(
                    g.kind,
                    to,
                    [&qr[..k], &vr[..k], &ar[..k]],
                    [&mut q2[..k], &mut v2[..k], &mut an[..k]],
                );
                scatter_free(g, &an, a);
            }
            let (mut qn, mut vn) = (zero, zero);
            S::carry(
                g.kind,
                to,
                [&qr[..k], &vr[..k], &zero[..k]],
                [&mut qn[..k], &mut vn[..k], &mut scratch[..k]],
            );
            scatter_free(g, &qn, q);
            scatter_free(g, &vn, v);
        }
    }

    /// The beam's rigid inertia at the mount at the coordinates `q`: mass, centre of mass and
    /// inertia tensor about the mount point in the mount frame, exact for the elements' mass
    /// distributions (the generalized mass matrix M, all coordinates held ones included, read
    /// through the rigid translation and rotation fields u: uᵢᵀ M uⱼ). `None` unless mounted.
    pub fn mount_inertia(&self, q: &[f64]) -> Option<MountInertia<S>> {
        let m = self.mount.as_deref()?;
        let (dim, rot) = (S::DIM, S::moment_components(&m.angular_velocity).len());
        let nf = dim + rot;
        let n = q.len();
        let nh = self.held.len();
        let mut gram = [[0.0; MAX_FIELDS]; MAX_FIELDS];
        self.mount_work.with(|w| {
            w.size(n, nh);
            let MountWork {
                free,
                held: held_fields,
                zeros,
                r0,
                r1,
                ul,
            } = w;
            // fields: translations along each axis, rotations about each axis through the
            // mount point (field f: free[f n..], held[f nh..])
            for f in 0..nf {
                let mut w = Motion::<S>::at_rest(m.position, m.attitude);
                if f < dim {
                    w.velocity[f] = 1.0;
                } else {
                    S::moment_components_mut(&mut w.angular_velocity)[f - dim] = 1.0;
                }
                self.rigid_field(
                    &w,
                    q,
                    &mut free[f * n..(f + 1) * n],
                    &mut held_fields[f * nh..(f + 1) * nh],
                );
            }
            let field = |f: usize| {
                (
                    &free[f * n..(f + 1) * n],
                    &held_fields[f * nh..(f + 1) * nh],
                )
            };
            let zeros = (&zeros[..n], &zeros[..nh]);
            let env = Env {
                gravity: S::Vec::default(),
                load: 1.0,
            };
            // sized anew per element from empty, as fresh vectors would be
            r0.clear();
            r1.clear();
            ul.clear();
            for e in &self.elements {
                let dofs = &e.at.dofs;
                let held = (&self.held[..], zeros.1, zeros.1);
                let x0 = LocalState::moving(dofs, held, (q, zeros.0, zeros.0));
                r0.resize(dofs.len(), 0.0);
                r1.resize(dofs.len(), 0.0);
                ul.resize(dofs.len(), 0.0);
                // M uᵢ directly where the element gives it, else r(q̈ = uᵢ) − r(0)
                for i in 0..nf {
                    let (ui, hi) = field(i);
                    let held = (&self.held[..], zeros.1, hi);
                    let xi = LocalState::moving(dofs, held, (q, zeros.0, ui));
                    if !e.at.part.inertia_times(&xi, r1) {
                        if i == 0 {
                            e.at.part.residual(&x0, &env, r0);
                        }
                        e.at.part.residual(&xi, &env, r1);
                        for (a, b) in r1.iter_mut().zip(r0.iter()) {
                            *a -= b;
                        }
                    }
                    for j in 0..nf {
                        let (uj, hj) = field(j);
                        for (k, d) in dofs.dofs().iter().enumerate() {
                            ul[k] = match *d {
                                Dof::Free(a) => uj[a as usize],
                                Dof::Held(b) => hj[b as usize],
                            };
                        }
                        gram[i][j] += (0..dofs.len()).map(|k| ul[k] * r1[k]).sum::<f64>();
                    }
                }
            }
        });
        let mass = (0..dim).map(|i| gram[i][i]).sum::<f64>() / dim as f64;
        // Tᵢᵀ M Rⱼ = eᵢ·(eⱼ × S), S = m c: the static moment from the mixed entries
        let mut s = S::Vec::default();
        let mut inertia = [0.0; 9];
        if dim == 2 {
            s[0] = gram[1][2];
            s[1] = -gram[0][2];
            inertia[0] = gram[2][2];
        } else {
            s[0] = 0.5 * (gram[1][5] - gram[2][4]);
            s[1] = 0.5 * (gram[2][3] - gram[0][5]);
            s[2] = 0.5 * (gram[0][4] - gram[1][3]);
            // I_frame = Aᵀ I_world A, column by column through to_frame
            let mut iw = [[0.0; 3]; 3];
            for (a, row) in iw.iter_mut().enumerate() {
                for (b, x) in row.iter_mut().enumerate() {
                    *x = gram[3 + a][3 + b];
                }
            }
            let mut cols = [[0.0; 3]; 3];
            for (b, col) in cols.iter_mut().enumerate() {
                let mut v = S::Vec::default();
                for a in 0..3 {
                    v[a] = iw[a][b];
                }
                let f = S::to_frame(&m.attitude, &v);
                *col = [f[0], f[1], f[2]];
            }
            // rows of Aᵀ I (as columns above), then (Aᵀ I) A = (Aᵀ (Aᵀ I)ᵀ)ᵀ
            for a in 0..3 {
                let mut v = S::Vec::default();
                for b in 0..3 {
                    v[b] = cols[b][a];
                }
                let f = S::to_frame(&m.attitude, &v);
                for b in 0..3 {
                    inertia[3 * a + b] = f[b];
                }
            }
        }
        let sf = S::to_frame(&m.attitude, &s);
        let mut c = S::Vec::default();
        for k in 0..dim {
            c[k] = if mass > 0.0 { sf[k] / mass } else { 0.0 };
        }
        Some(MountInertia {
            mass,
            center_of_mass: c,
            inertia,
        })
    }

    /// The velocity field of the rigid motion `w` (rates only) over all coordinates at `q`,
    /// into `uf` (free, n) and `uh` (held); zero for coordinates in no rigid group.
    fn rigid_field(&self, w: &Motion<S>, q: &[f64], uf: &mut [f64], uh: &mut [f64]) {
        uf.fill(0.0);
        uh.fill(0.0);
        let zero = [0.0; 4];
        for g in &self.groups {
            let k = S::rigid_len(g.kind);
            let vals = if is_held(g) {
                gather_held(g, &self.held)
            } else {
                gather_free(g, q)
            };
            let (mut rel, mut rv, mut ra) = (zero, zero, zero);
            let (mut qo, mut vo, mut ao) = (zero, zero, zero);
            S::uncarry(
                g.kind,
                w,
                [&vals[..k], &zero[..k], &zero[..k]],
                [&mut rel[..k], &mut rv[..k], &mut ra[..k]],
            );
            S::carry(
                g.kind,
                w,
                [&rel[..k], &zero[..k], &zero[..k]],
                [&mut qo[..k], &mut vo[..k], &mut ao[..k]],
            );
            for (c, d) in g.dofs.iter().enumerate() {
                match *d {
                    Dof::Free(i) => uf[i as usize] = vo[c],
                    Dof::Held(j) => uh[j as usize] = vo[c],
                }
            }
        }
    }
}

/// Rates and accelerations of a group with world values `qg` at rest relative to the frame
/// moving as `m`: taken relative to the frame, carried back with its rates.
fn rest_of_group<S: Space>(g: &RigidGroup, m: &Motion<S>, qg: &G) -> (G, G) {
    let k = S::rigid_len(g.kind);
    let zero = [0.0; 4];
    let (mut rel, mut s1, mut s2) = (zero, zero, zero);
    S::uncarry(
        g.kind,
        m,
        [&qg[..k], &zero[..k], &zero[..k]],
        [&mut rel[..k], &mut s1[..k], &mut s2[..k]],
    );
    let (mut qo, mut vo, mut ao) = (zero, zero, zero);
    S::carry(
        g.kind,
        m,
        [&rel[..k], &zero[..k], &zero[..k]],
        [&mut qo[..k], &mut vo[..k], &mut ao[..k]],
    );
    (vo, ao)
}

fn is_held(g: &RigidGroup) -> bool {
    matches!(g.dofs.first(), Some(Dof::Held(_)))
}

fn gather_held(g: &RigidGroup, held: &[f64]) -> G {
    let mut out = [0.0; 4];
    for (o, d) in out.iter_mut().zip(&g.dofs) {
        if let Dof::Held(j) = *d {
            *o = held[j as usize];
        }
    }
    out
}

fn gather_free(g: &RigidGroup, x: &[f64]) -> G {
    let mut out = [0.0; 4];
    for (o, d) in out.iter_mut().zip(&g.dofs) {
        if let Dof::Free(i) = *d {
            *o = x[i as usize];
        }
    }
    out
}

fn scatter_free(g: &RigidGroup, vals: &G, x: &mut [f64]) {
    for (v, d) in vals.iter().zip(&g.dofs) {
        if let Dof::Free(i) = *d {
            x[i as usize] = *v;
        }
    }
}
