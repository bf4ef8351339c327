//! The ANCF cable elements of degree p > 3 as components, written once over the space: an
//! element kernel ([`PKernel`]: the planar `ancf_p::CableP`, the spatial 3D cable
//! `ancf3d::cable_p::Cable3P`) with the mass, gravity, line load and point masses of its
//! hierarchic shapes ([`super::hierarchic`]). Local coordinates `[r0, r0′, r1, r1′, a_4, …,
//! a_p]` (DIM each), the bubble amplitudes a_k element-internal. Section bodies (an offset or a
//! rotary inertia) are not carried (the scene refuses them on such a segment).

use super::component::{Element, ElementOut, Energies, Env, LocalState, Validity};
use super::hierarchic::{partial_load, PKernel, PMat, PShape, PVec, MAX_DOFS, MAX_SHAPES};
use super::sample::ShapePoint;
use super::space::Space;
use std::any::Any;
use std::marker::PhantomData;

/// An ANCF cable element of degree p > 3 on its kernel `K` in the space `S` (K::DIM = S::DIM).
#[derive(Debug, Clone)]
pub struct ElementP<K, S> {
    /// The kernel.
    pub kernel: K,
    /// The scalar mass pattern ρA∫S_j S_k dx + Σ m S_j(ξ_m) S_k(ξ_m) (M = pattern ⊗ I_DIM).
    mass: [[f64; MAX_SHAPES]; MAX_SHAPES],
    /// Σ m S(ξ_m) over the point masses [kg, kg m].
    points: [f64; MAX_SHAPES],
    /// The point masses (ξ, m [kg]).
    point_list: Vec<(f64, f64)>,
    /// ∫Sᵀ(ρA g + q) dx + Σ m S(ξ_m)ᵀ g at the current gravity and line load.
    gravity_force: PVec,
    /// The current gravity [m/s²] (zero beyond DIM).
    g: [f64; 3],
    /// The segment's line load q [N/m] (zero without one, and beyond DIM).
    line: [f64; 3],
    /// Room for the kernel's stiffness and damping matrices (the leading d × d zeroed per use).
    mats: Box<(PMat, PMat)>,
    space: PhantomData<S>,
}

/// The first components of a vector of the space as a 3-vector.
fn vec3(v: &[f64]) -> [f64; 3] {
    std::array::from_fn(|k| v.get(k).copied().unwrap_or(0.0))
}

impl<K: PKernel, S: Space> ElementP<K, S> {
    /// The element of `kernel` carrying the point masses `points` (ξ ∈ [0, 1], mass [kg]) under
    /// the segment's line load `line` [N/m] (world axes; `None`: none).
    pub fn new(kernel: K, points: &[(f64, f64)], line: Option<&[f64]>) -> Self {
        assert_eq!(K::DIM, S::DIM, "a kernel of the element's space");
        let t = kernel.tables();
        let n = t.n;
        let mut mass = t.mass.map(|row| row.map(|x| x * kernel.rho_a()));
        let mut w = [0.0; MAX_SHAPES];
        for &(xi, m) in points {
            let s = PShape::at(t.degree, xi, t.length).s;
            for j in 0..n {
                w[j] += m * s[j];
                for k in 0..n {
                    mass[j][k] += m * s[j] * s[k];
                }
            }
        }
        Self {
            kernel,
            mass,
            points: w,
            point_list: points.to_vec(),
            gravity_force: [0.0; MAX_DOFS],
            g: [0.0; 3],
            line: line.map_or([0.0; 3], vec3),
            mats: Box::new(([[0.0; MAX_DOFS]; MAX_DOFS], [[0.0; MAX_DOFS]; MAX_DOFS])),
            space: PhantomData,
        }
    }

    fn n(&self) -> usize {
        self.kernel.tables().n
    }

    fn dofs(&self) -> usize {
        self.kernel.dofs()
    }

    /// (e, ė, ë) of the element.
    fn state(&self, x: &LocalState<'_>) -> (PVec, PVec, PVec) {
        let d = self.dofs();
        let (mut e, mut ed, mut ea) = ([0.0; MAX_DOFS], [0.0; MAX_DOFS], [0.0; MAX_DOFS]);
        x.gather(&mut e[..d], &mut ed[..d], &mut ea[..d]);
        (e, ed, ea)
    }

    /// M ë + f − load·f_ext into `res` (d entries): [`ElementP::residual_of`] of the element's
    /// number of shapes.
    fn residual_at(&self, ea: &PVec, force: &PVec, load: f64, res: &mut [f64]) {
        match self.n() {
            4 => self.residual_of::<4>(ea, force, load, res),
            5 => self.residual_of::<5>(ea, force, load, res),
            6 => self.residual_of::<6>(ea, force, load, res),
            7 => self.residual_of::<7>(ea, force, load, res),
            8 => self.residual_of::<8>(ea, force, load, res),
            n => unreachable!("{n} shapes"),
        }
    }

    /// [`ElementP::residual_at`] of an element of `N` shapes (the loops unrolled).
    #[inline(always)]
    fn residual_of<const N: usize>(&self, ea: &PVec, force: &PVec, load: f64, res: &mut [f64]) {
        let dim = S::DIM;
        let res = &mut res[..dim * N];
        for j in 0..N {
            for c in 0..dim {
                let mut m = 0.0;
                for k in 0..N {
                    m += self.mass[j][k] * ea[dim * k + c];
                }
                let i = dim * j + c;
                res[i] = m + force[i] - load * self.gravity_force[i];
            }
        }
    }
}

impl<K: PKernel, S: Space> Element<S> for ElementP<K, S> {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<S>, mut out: ElementOut<'_>) {
        let (e, ed, ea) = self.state(x);
        let d = self.dofs();
        let mut res = [0.0; MAX_DOFS];
        match out.matrix {
            None => {
                let f = self.kernel.forces(&e, &ed, None);
                self.residual_at(&ea, &f, env.load, &mut res);
                out.add_residual(&res[..d]);
            }
            Some((ca, cv, cx)) => {
                let (k, c) = &mut *self.mats;
                for row in k[..d].iter_mut().chain(&mut c[..d]) {
                    row[..d].fill(0.0);
                }
                let f = self.kernel.forces(&e, &ed, Some((k, c)));
                self.residual_at(&ea, &f, env.load, &mut res);
                out.add_residual(&res[..d]);
                let ((k, c), mass, dim) = (&*self.mats, &self.mass, S::DIM);
                out.add_block(|r, col| {
                    let m = if r % dim == col % dim {
                        mass[r / dim][col / dim]
                    } else {
                        0.0
                    };
                    ca * m + cv * c[r][col] + cx * k[r][col]
                });
            }
        }
    }

    fn residual(&self, x: &LocalState<'_>, _env: &Env<S>, res: &mut [f64]) {
        let (e, ed, ea) = self.state(x);
        let f = self.kernel.forces(&e, &ed, None);
        self.residual_at(&ea, &f, 1.0, res);
    }

    fn energies(&self, x: &LocalState<'_>, _gravity: &S::Vec) -> Energies {
        let (e, ed, _) = self.state(x);
        let (n, dim) = (self.n(), S::DIM);
        let mut kinetic = 0.0;
        for j in 0..n {
            for k in 0..n {
                let v: f64 = (0..dim).map(|c| ed[dim * j + c] * ed[dim * k + c]).sum();
                kinetic += 0.5 * self.mass[j][k] * v;
            }
        }
        let d = self.dofs();
        Energies {
            kinetic,
            strain: self.kernel.strain_energy(&e[..d]),
            potential: -(0..d).map(|i| self.gravity_force[i] * e[i]).sum::<f64>(),
        }
    }

    fn set_gravity(&mut self, g: &S::Vec) {
        let t = self.kernel.tables();
        let (ra, dim) = (self.kernel.rho_a(), S::DIM);
        self.g = vec3(g.as_ref());
        self.gravity_force = [0.0; MAX_DOFS];
        for j in 0..t.n {
            for c in 0..dim {
                self.gravity_force[dim * j + c] =
                    t.load[j] * (ra * self.g[c] + self.line[c]) + self.points[j] * self.g[c];
            }
        }
    }

    fn set_line_load(&mut self, q: &S::Vec) {
        self.line = vec3(q.as_ref());
    }

    fn is_damped(&self) -> bool {
        self.kernel.damping_time() > 0.0
    }

    fn length(&self) -> f64 {
        self.kernel.tables().length
    }

    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (e, ed, _) = self.state(x);
        let d = self.dofs();
        out.extend(xi.iter().map(|&s| self.kernel.sample(&e[..d], &ed[..d], s)));
    }

    /// [`partial_load`] on the element's (p + 1)-point rule over [0, ξ], with the point masses
    /// before ξ.
    fn partial_load(
        &self,
        x: &LocalState<'_>,
        gravity: &S::Vec,
        xi: f64,
        about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        let (e, _, ea) = self.state(x);
        let ra = self.kernel.rho_a();
        let g = vec3(gravity.as_ref());
        let field = std::array::from_fn(|c| g[c] + self.line[c] / ra);
        let t = self.kernel.tables();
        let state = (&e[..], &ea[..]);
        let dim = S::DIM;
        Some(partial_load(
            t,
            dim,
            state,
            ra,
            field,
            g,
            &self.point_list,
            xi,
            about,
        ))
    }

    fn validity(&self, q: &[f64]) -> Validity {
        Validity {
            axial_strain: self.kernel.max_axial_strain(q),
            ..Validity::default()
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
