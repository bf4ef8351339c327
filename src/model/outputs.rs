//! What a state means: tip kinematics, energies, the support reaction and the validity checks
//! of the elements. Dimension-free, read through ports, elements and the support.

use super::assembly::Model;
use super::component::{Element, Env, LocalState, LocalVec};
use super::dofs::Dof;
use super::load::{moment_residual, point_force_residual};
use super::space::{is_nonzero_moment, PortKin, Space};

/// Scalar results of one state.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Outputs<S: Space> {
    /// Tip position [m], global.
    pub tip_position: S::Vec,
    /// Tip velocity [m/s], global.
    pub tip_velocity: S::Vec,
    /// Orientation of the tip section: in the plane the angle of the tip tangent from global x
    /// [rad], in (−π, π].
    pub tip_angle: S::Attitude,
    /// Angular velocity of the tip section [rad/s], global axes (in the plane: about z,
    /// counter-clockwise positive).
    pub tip_angular_velocity: S::Moment,
    /// Tip acceleration [m/s²], global: J q̈ + q̇ᵀ(∂²p/∂q²)q̇ at the state's accelerations
    /// (which satisfy the equations of motion at the state's time).
    pub tip_acceleration: S::Vec,
    /// Angular acceleration of the tip section [rad/s²], global axes: the time derivative of
    /// `tip_angular_velocity`.
    pub tip_angular_acceleration: S::Moment,
    /// Kinetic energy [J].
    pub kinetic: f64,
    /// Strain energy [J].
    pub strain: f64,
    /// Gravity potential energy −∫ρA gᵀr dx [J] (zero at the origin), with the point masses'
    /// −Σ m gᵀr and the segments' line loads' −∫qᵀr dx (a conservative dead load).
    pub potential: f64,
    /// Force of the support on the beam at the root [N], global axes.
    pub root_force: S::Vec,
    /// Moment of the support on the beam about the root point [N m] (in the plane:
    /// counter-clockwise positive; zero for a pinned root).
    pub root_moment: S::Moment,
    /// The beam's rigid inertia at the mount (`root = "mounted"` only).
    pub mount: Option<super::inertia::MountInertia<S>>,
    /// The reaction beyond the rigid inertia's own at the current mount motion and gravity
    /// ([`MountInertia::rigid_reaction`](super::mount::MountInertia::rigid_reaction)): force
    /// [N] (`root = "mounted"` only, else zero), what a host that carries `mount` as interface
    /// mass applies.
    pub elastic_force: S::Vec,
    /// The moment [N m] beyond the rigid inertia's, about the mount point (as
    /// `elastic_force`).
    pub elastic_moment: S::Moment,
    /// The loads at each station of the scene, in `[[stations]]` order (zero beyond them;
    /// [`Model::station_loads`]).
    pub stations: [super::stations::StationLoads; crate::scene::MAX_STATIONS],
    /// With `outputs.stress`: the largest von Mises stress along the beam [Pa] and its arc
    /// length from the root [m] ([`Model::beam_stress`]); zero without.
    pub stress_max: (f64, f64),
}

/// Validity measures of a model at one configuration.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ModelValidity {
    /// Largest |axial strain| over the elements [-] (0 without elements that measure it).
    pub max_axial_strain: f64,
    /// Largest elastic deflection of a modal segment: (segment index in the scene, the
    /// element's deflection measure).
    pub modal_deflection: Option<(usize, f64)>,
    /// Largest twist within one ANCF element [rad] (segment index, value).
    pub max_twist: Option<(usize, f64)>,
    /// Smallest sine of the angle between r_x and r_y at an ANCF node (segment index, value).
    pub min_section_sine: Option<(usize, f64)>,
    /// Smallest chart margin 1 + t⁰·t of a node of an element with nodal twist angles
    /// (segment index, value).
    pub min_chart_margin: Option<(usize, f64)>,
}

impl<S: Space> Model<S> {
    /// Outputs at a state (q, q̇, q̈, λ).
    pub fn outputs(&self, q: &[f64], v: &[f64], acc: &[f64], lam: &[f64]) -> Outputs<S> {
        let mut buf = LocalVec::from_elem(0.0, self.max_local_len());
        let tip = &self.tip.dofs;
        let x = &mut buf[..tip.len()];
        tip.gather(q, &self.held, x);
        // the full kinematics: its first derivatives give the velocities, its second the
        // accelerations' velocity terms
        let kin = self.tip.part.kinematics(x);
        let (rates, accs) = self.tip_rates(v, acc);
        // J q̇ and J q̈ of the position and the rotation
        let (mut vel, mut tip_acceleration) = (S::Vec::default(), S::Vec::default());
        let (mut omega, mut tip_angular_acceleration) =
            (S::Moment::default(), S::Moment::default());
        for (k, (rate, a)) in rates.iter().zip(&accs).enumerate() {
            let dp = kin.jacobian(k);
            for c in 0..S::DIM {
                vel[c] += dp[c] * rate;
                tip_acceleration[c] += dp[c] * a;
            }
            let dth = kin.rotation_jacobian(k);
            let d = S::moment_components(&dth);
            for (w, d) in S::moment_components_mut(&mut omega).iter_mut().zip(d) {
                *w += d * rate;
            }
            for (w, d) in S::moment_components_mut(&mut tip_angular_acceleration)
                .iter_mut()
                .zip(d)
            {
                *w += d * a;
            }
        }
        self.add_tip_velocity_terms(
            x,
            &kin,
            &rates,
            &mut tip_acceleration,
            &mut tip_angular_acceleration,
        );
        let mut o = Outputs {
            tip_position: kin.position(),
            tip_velocity: vel,
            tip_angle: kin.attitude(),
            tip_angular_velocity: omega,
            tip_acceleration,
            tip_angular_acceleration,
            ..Default::default()
        };
        for e in &self.elements {
            let x = LocalState::moving(&e.at.dofs, self.held_state(), (q, v, acc));
            let en = e.at.part.energies(&x, &self.gravity);
            o.kinetic += en.kinetic;
            o.strain += en.strain;
            o.potential += en.potential;
        }
        let r = self.held_residual((q, v, acc), lam, &mut buf);
        (o.root_force, o.root_moment) = self.support.reaction(&r, &self.held);
        o.stations = self.station_loads((q, v, acc), (&o.root_force, &o.root_moment));
        o.stress_max = self.beam_stress((q, v, acc)).unwrap_or_default();
        o.mount = self.mount_inertia(q);
        if let (Some(mi), Some(m)) = (&o.mount, self.mount.as_deref()) {
            let (f, mo) = mi.rigid_reaction(m, &self.gravity);
            for k in 0..S::DIM {
                o.elastic_force[k] = o.root_force[k] - f[k];
            }
            let rm = S::moment_components(&o.root_moment);
            for ((e, r), f) in S::moment_components_mut(&mut o.elastic_moment)
                .iter_mut()
                .zip(rm)
                .zip(S::moment_components(&mo))
            {
                *e = r - f;
            }
        }
        o
    }

    /// Rates and accelerations of the tip port's local coordinates: the state's for free ones,
    /// the mount's for held ones (a modal tip port holds its root frame; zero for a fixed root).
    fn tip_rates(&self, v: &[f64], acc: &[f64]) -> (LocalVec, LocalVec) {
        self.tip
            .dofs
            .dofs()
            .iter()
            .map(|dof| match *dof {
                Dof::Free(i) => (v[i as usize], acc[i as usize]),
                Dof::Held(j) => (
                    self.held_v.get(j as usize).copied().unwrap_or(0.0),
                    self.held_a.get(j as usize).copied().unwrap_or(0.0),
                ),
            })
            .unzip()
    }

    /// Adds the velocity terms of the tip's acceleration and angular acceleration,
    /// d/dt(J q̇) − J q̈ = Σᵢⱼ ∂Jᵢ/∂qⱼ q̇ᵢ q̇ⱼ, at the tip port's local coordinates `x` (kinematics
    /// `kin`, with second derivatives) and local `rates` ([`Model::tip_rates`]): from the port's
    /// point Hessian and its moment stiffness (the derivative of the rotation Jacobian).
    fn add_tip_velocity_terms(
        &self,
        x: &[f64],
        kin: &S::PortKin,
        rates: &[f64],
        lin: &mut S::Vec,
        ang: &mut S::Moment,
    ) {
        for c in 0..S::DIM {
            let mut mu = S::Vec::default();
            mu[c] = 1.0;
            let mut sum = 0.0;
            kin.add_point_hessian(&mu, |i, j, h| sum += h * rates[i] * rates[j]);
            lin[c] += sum;
        }
        let curvature = self.tip.part.rotation_second_derivative_along(x, rates);
        for (a, c) in S::moment_components_mut(ang)
            .iter_mut()
            .zip(S::moment_components(&curvature))
        {
            *a += c;
        }
    }

    /// The support's force [N] and moment [N m] on the beam at a state (the reaction of
    /// [`Outputs`] alone).
    pub fn reaction(&self, q: &[f64], v: &[f64], acc: &[f64], lam: &[f64]) -> (S::Vec, S::Moment) {
        let mut buf = LocalVec::from_elem(0.0, self.max_local_len());
        let r = self.held_residual((q, v, acc), lam, &mut buf);
        self.support.reaction(&r, &self.held)
    }

    /// The held values, rates and accelerations.
    pub(crate) fn held_state(&self) -> (&[f64], &[f64], &[f64]) {
        (&self.held, &self.held_v, &self.held_a)
    }

    /// Residual `M q̈ + f − f_ext + Φ_qᵀλ` of the held coordinates at full load: the generalized
    /// force the support exerts on the beam, summed in the order of the assembly.
    fn held_residual(
        &self,
        (q, v, acc): (&[f64], &[f64], &[f64]),
        lam: &[f64],
        buf: &mut [f64],
    ) -> LocalVec {
        // −0 is the exact additive identity: a coordinate reached once gets its term's bits
        let mut r = LocalVec::from_elem(-0.0, self.held.len());
        let env = Env {
            gravity: self.gravity,
            load: 1.0,
        };
        let mut local = LocalVec::new();
        for e in self.elements.iter().filter(|e| e.at.dofs.has_held()) {
            let x = LocalState::moving(&e.at.dofs, self.held_state(), (q, v, acc));
            local.resize(x.len(), 0.0);
            e.at.part.residual(&x, &env, &mut local);
            e.at.dofs.scatter_held(&local, &mut r);
        }
        let tip = &self.tip.dofs;
        if tip.has_held() {
            let x = &mut buf[..tip.len()];
            tip.gather(q, &self.held, x);
            let kin = self.tip.part.kinematics_first(x);
            local.resize(tip.len(), 0.0);
            point_force_residual::<S>(&kin, &self.tip_force, &mut local);
            tip.scatter_held(&local, &mut r);
            if is_nonzero_moment::<S>(&self.tip_moment) {
                moment_residual::<S>(&kin, &self.tip_moment, &mut local);
                tip.scatter_held(&local, &mut r);
            }
        }
        self.constraint_out.with(|out| {
            for c in self.constraints.iter().filter(|c| c.at.dofs.has_held()) {
                let dofs = &c.at.dofs;
                let d = dofs.len();
                let x = &mut buf[..d];
                dofs.gather(q, &self.held, x);
                out.reset(c.rows, d);
                c.at.part.eval(x, None, out);
                for row in 0..c.rows {
                    let l = lam[c.row + row];
                    local.clear();
                    local.extend(out.jac[row * d..(row + 1) * d].iter().map(|j| j * l));
                    dofs.scatter_held(&local, &mut r);
                }
            }
        });
        r
    }

    /// The validity measures of all elements at `q`, in one pass.
    pub fn validity(&self, q: &[f64]) -> ModelValidity {
        let mut out = ModelValidity::default();
        // on the stack (this runs after every step)
        let mut buf = LocalVec::from_elem(0.0, self.max_local_len());
        for e in &self.elements {
            let x = &mut buf[..e.at.dofs.len()];
            e.at.dofs.gather(q, &self.held, x);
            let v = e.at.part.validity(x);
            out.max_axial_strain = out.max_axial_strain.max(v.axial_strain);
            if let Some(d) = v.modal_deflection {
                if out.modal_deflection.is_none_or(|(_, w)| d > w) {
                    out.modal_deflection = Some((e.segment, d));
                }
            }
            if let Some(m) = v.chart_margin {
                if out.min_chart_margin.is_none_or(|(_, w)| m < w) {
                    out.min_chart_margin = Some((e.segment, m));
                }
            }
            if let Some((twist, sine)) = v.section {
                if out.max_twist.is_none_or(|(_, w)| twist > w) {
                    out.max_twist = Some((e.segment, twist));
                }
                if out.min_section_sine.is_none_or(|(_, w)| sine < w) {
                    out.min_section_sine = Some((e.segment, sine));
                }
            }
        }
        out
    }

    /// The elements of one kind `E` in summation order (e.g. the modal bodies).
    pub fn elements_of<E: Element<S>>(&self) -> impl Iterator<Item = &E> + '_ {
        self.elements
            .iter()
            .filter_map(|e| e.at.part.as_any().downcast_ref::<E>())
    }
}
