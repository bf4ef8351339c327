//! The partner model: the host's response at the mount, kept inside the beam's step so that a
//! host that only exchanges values (a fixed-step co-simulation) couples a heavy beam stably.
//!
//! A mounted beam's host (a vehicle) computes the mount's accelerations `a_host` with a
//! reaction `R_ref` it was given (the reaction of the support on the beam, force then moment).
//! Over the next communication step the beam's reaction R changes, and with a stiff mount of a
//! heavy beam that change, answered only one step later, drives the explicit exchange unstable
//! (the added-mass instability: `docs/coupling.md`). With the partner model the host also gives
//! its mobility G = ∂a/∂R at the mount, and inside each internal step the beam lets the mount's
//! acceleration answer its own reaction:
//!
//! a(t) = a_host(t) + G (R(t) − R_ref),
//!
//! the deviation from the host's path integrated by the trapezoidal rule and solved with the
//! step (Newton on the deviation's end acceleration with the matrix I − G M_app, M_app the
//! beam's apparent mass at the mount, [`Simulator::apparent_mass`]). The stiff, fast part of the
//! coupling is thereby implicit in the beam; the host's next input re-anchors the beam at the
//! host's motion. This is the interface-mass idea of Morandini & Masarati (`docs/references.md`
//! §8) with the host's mass on the beam's side given as its mobility. A zero mobility (the
//! default) leaves the step exactly as without the model.

use super::*;
use crate::model::MotionRates;

/// Reaction or acceleration components at the mount: the space's vector components, then its
/// moment components (the plane: x, y, z-moment; space: x, y, z, then about x, y, z).
pub const PARTNER_COMPONENTS: usize = 6;

/// The host's linear response at the mount, as a host sets it with the mount's motion.
/// Component order: [`PARTNER_COMPONENTS`]; only the space's first `n` (3 planar, 6 spatial) are
/// used.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Partner {
    /// G = ∂(a, α)/∂(F, M): the partials of the mount's acceleration [m/s²] and angular
    /// acceleration [rad/s²] (rows, world axes) by the reaction force [N] and moment [N m] of
    /// the support on the beam (columns, world axes): 1/kg, 1/(kg m), 1/(kg m²).
    pub mobility: [[f64; PARTNER_COMPONENTS]; PARTNER_COMPONENTS],
    /// The reaction [N, N m] the host's acceleration input was computed with.
    pub reference: [f64; PARTNER_COMPONENTS],
}

impl Partner {
    /// Whether the model acts (some mobility is nonzero).
    pub fn is_active(&self) -> bool {
        self.mobility.iter().flatten().any(|x| *x != 0.0)
    }

    /// Whether every value is finite.
    pub fn is_finite(&self) -> bool {
        self.mobility
            .iter()
            .flatten()
            .chain(&self.reference)
            .all(|x| x.is_finite())
    }
}

/// Newton iterations of the partner's deviation per internal step, at most.
pub const PARTNER_ITERATIONS: usize = 8;

/// Relative tolerance of the deviation's end acceleration (of the largest of it and 1e-9).
const PARTNER_TOLERANCE: f64 = 1e-10;

/// The partner model over one communication step: the mobility and the Newton matrix.
pub(super) struct PartnerStep {
    partner: Partner,
    n: usize,
    /// LU factors of I − G M_app.
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
}

impl PartnerStep {
    /// The step's model from the partner and the beam's apparent mass now; `None` if the
    /// Newton matrix is singular (to rounding).
    fn new(partner: Partner, apparent: &[Vec<f64>]) -> Option<Self> {
        let n = apparent.len();
        let jac = nalgebra::DMatrix::from_fn(n, n, |i, j| {
            let gm: f64 = (0..n)
                .map(|k| partner.mobility[i][k] * apparent[k][j])
                .sum();
            f64::from(u8::from(i == j)) - gm
        });
        let lu = jac.lu();
        // singular to rounding: a pivot below 1e-9 of the largest or of the identity's
        let pivots = lu.u().diagonal().map(f64::abs);
        (pivots.min() > 1e-9 * pivots.max().max(1.0)).then_some(Self { partner, n, lu })
    }

    /// The host's answer G (R − R_ref) to the reaction `r` (components as [`Partner`]).
    fn answer(&self, r: &[f64; PARTNER_COMPONENTS]) -> nalgebra::DVector<f64> {
        let (g, r_ref) = (&self.partner.mobility, &self.partner.reference);
        nalgebra::DVector::from_fn(self.n, |i, _| {
            (0..self.n)
                .map(|j| g[i][j] * (r[j] - r_ref[j]))
                .sum::<f64>()
        })
    }
}

/// The mount's deviation from the host's path (components as [`Partner`]): displacement and
/// small rotation, their rates, their accelerations.
#[derive(Debug, Clone, Default)]
pub(super) struct Deviation {
    d: [f64; PARTNER_COMPONENTS],
    v: [f64; PARTNER_COMPONENTS],
    a: [f64; PARTNER_COMPONENTS],
}

impl Deviation {
    /// The deviation `h` later with the end acceleration `a1` (trapezoidal rule).
    fn advanced(&self, a1: &[f64; PARTNER_COMPONENTS], h: f64) -> Deviation {
        let mut out = Deviation {
            a: *a1,
            ..Deviation::default()
        };
        for i in 0..PARTNER_COMPONENTS {
            out.v[i] = self.v[i] + 0.5 * h * (self.a[i] + a1[i]);
            out.d[i] = self.d[i] + h * self.v[i] + 0.25 * h * h * (self.a[i] + a1[i]);
        }
        out
    }

    /// `m` moved by the deviation (the rotation as a world rotation vector).
    fn applied<S: Space>(&self, m: &Motion<S>) -> Motion<S> {
        let mut m = *m;
        let dim = S::DIM;
        for k in 0..dim {
            m.position[k] += self.d[k];
            m.velocity[k] += self.v[k];
            m.acceleration[k] += self.a[k];
        }
        let mut phi = S::Moment::default();
        for (k, x) in S::moment_components_mut(&mut phi).iter_mut().enumerate() {
            *x = self.d[dim + k];
        }
        m.attitude = S::rotated(&m.attitude, &phi);
        for (k, x) in S::moment_components_mut(&mut m.angular_velocity)
            .iter_mut()
            .enumerate()
        {
            *x += self.v[dim + k];
        }
        for (k, x) in S::moment_components_mut(&mut m.angular_acceleration)
            .iter_mut()
            .enumerate()
        {
            *x += self.a[dim + k];
        }
        m
    }
}

impl<S: Space> Simulator<S> {
    /// The partner model set by the host (zero without a mount or when none was set).
    pub fn partner(&self) -> Partner {
        self.mount.as_ref().map(|m| m.partner).unwrap_or_default()
    }

    /// Sets the partner model for the following steps (it holds until set again; a mounted
    /// root only: `false` otherwise). Checked at the next [`Simulator::advance`].
    pub fn set_partner(&mut self, partner: Partner) -> bool {
        match &mut self.mount {
            Some(m) => {
                m.partner = partner;
                true
            }
            None => false,
        }
    }

    /// The support's reaction on the beam at the current state, components as [`Partner`].
    fn reaction_now(&self) -> [f64; PARTNER_COMPONENTS] {
        let s = &self.state;
        let (f, m) = self.model.reaction(&s.q, &s.v, &s.acc, &s.lambda);
        let mut out = [0.0; PARTNER_COMPONENTS];
        for (o, x) in out
            .iter_mut()
            .zip(f.as_ref().iter().chain(S::moment_components(&m)))
        {
            *o = *x;
        }
        out
    }

    /// The partner model of a communication step starting now: `Ok(None)` when it does not
    /// act; refused when its inputs are not finite or its Newton matrix is singular.
    pub(super) fn partner_step(&mut self) -> Result<Option<PartnerStep>, SimError> {
        let t = self.state.t;
        let partner = self.partner();
        if !partner.is_active() {
            return Ok(None);
        }
        let refused = |why: &str| SimError::Refused {
            t,
            refusal: Refusal::MountInput(why.into()),
        };
        if !partner.is_finite() {
            return Err(refused(
                "a root.mobility or root.reaction_reference input is not finite",
            ));
        }
        let apparent = self
            .apparent_mass()
            .ok_or_else(|| refused("the beam's apparent mass at the mount could not be solved"))?;
        PartnerStep::new(partner, &apparent)
            .map(Some)
            .ok_or_else(|| {
                refused(
                "I - root.mobility x apparent mass is singular: the host's mobility cancels the \
                 beam's inertia; give the host's own mobility (without the beam's inertia)",
            )
            })
    }

    /// The start of a communication step with the partner model: the mount's acceleration
    /// made to answer the reaction now, a₀ = G (R(a_host + a₀) − R_ref), solved exactly (the
    /// reaction is linear in the mount's acceleration with the apparent mass:
    /// (I − G M_app) a₀ = G (R(a_host) − R_ref)) and applied as a jump of the inputs. Without
    /// it the host's acceleration, computed with the reaction of one step earlier, would drive
    /// the step's start, and with it the explicit exchange's loop the model is there to cut.
    pub(super) fn partner_start(&mut self, p: &PartnerStep) -> Result<Deviation, SimError> {
        let t = self.state.t;
        let b = p.answer(&self.reaction_now());
        let a0 = p.lu.solve(&b).unwrap_or(b);
        let mut dev = Deviation::default();
        for i in 0..p.n {
            dev.a[i] = a0[i];
        }
        let Some(path) = self.mount.as_deref().map(|ms| ms.at(t)) else {
            return Ok(dev);
        };
        let start = dev.applied(&path);
        self.integ
            .change_inputs(&mut self.model, &mut self.state, |m| m.set_mount(&start))
            .map_err(|source| SimError::InputJump { t, source })?;
        Ok(dev)
    }

    /// One internal step to `t_next` with the partner model: the deviation's end acceleration
    /// solved with the step so that it equals G (R − R_ref) there. On failure the state is
    /// the one at the step's start.
    pub(super) fn step_with_partner(
        &mut self,
        p: &PartnerStep,
        dev: &mut Deviation,
        (t0, t_next, h): (f64, f64, f64),
        inputs: &Inputs<S>,
    ) -> Result<(), crate::integrator::StepFailure> {
        let varying = self.load_rates.any();
        let t_start = self.state.t;
        let n = p.n;
        let start = self.state.clone();
        let mut a1 = dev.a;
        for it in 0..PARTNER_ITERATIONS {
            let next = dev.advanced(&a1, h);
            // the loads and the deviated mount at the step's end (each stage time of a
            // multi-stage method: the deviation's acceleration linear over the step)
            let (mount, rates, d0) = (self.mount.as_deref(), &self.load_rates, &*dev);
            let at = |m: &mut Model<S>, dt: f64| {
                let t = super::step::stage_time(t_start, t_next, h, dt);
                if varying {
                    rates.advanced(inputs, t - t0).apply(m);
                }
                if let Some(ms) = mount {
                    let d = if dt == h {
                        next.clone()
                    } else {
                        let f = dt / h;
                        let a: [f64; PARTNER_COMPONENTS] =
                            std::array::from_fn(|i| d0.a[i] + f * (a1[i] - d0.a[i]));
                        d0.advanced(&a, dt)
                    };
                    m.set_mount(&d.applied(&ms.at(t)));
                }
            };
            if let Err(e) = self.integ.step(&mut self.model, &mut self.state, h, at) {
                self.state = start;
                return Err(e);
            }
            if self.mount.is_none() {
                *dev = next;
                return Ok(());
            }
            let answer = p.answer(&self.reaction_now());
            let res = nalgebra::DVector::from_fn(n, |i, _| a1[i] - answer[i]);
            let size = res.amax();
            let scale = a1[..n].iter().fold(1e-9f64, |m, x| m.max(x.abs()));
            if size <= PARTNER_TOLERANCE * scale || it + 1 == PARTNER_ITERATIONS {
                *dev = next;
                return Ok(());
            }
            let delta = p.lu.solve(&res).unwrap_or(res);
            for i in 0..n {
                a1[i] -= delta[i];
            }
            self.state = start.clone();
        }
        Ok(())
    }

    /// After a communication step with the partner model: the mount's path continues from
    /// where the deviation took it (the host's next input re-anchors the beam from there).
    pub(super) fn continue_deviated(&mut self, dev: &Deviation, t_end: f64) {
        if let Some(ms) = &mut self.mount {
            ms.base = dev.applied(&ms.at(t_end));
            ms.t0 = t_end;
            ms.rates = MotionRates::default();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Planar;

    /// The trapezoidal deviation under a constant acceleration is exact (d = a t²/2).
    #[test]
    fn a_constant_deviation_acceleration_integrates_exactly() {
        let mut d = Deviation::default();
        let a = [2.0, -1.0, 0.5, 0.0, 0.0, 0.0];
        d.a = a;
        for _ in 0..10 {
            d = d.advanced(&a, 0.1);
        }
        for i in 0..3 {
            assert!((d.d[i] - 0.5 * a[i]).abs() < 1e-14, "{i}: {}", d.d[i]);
            assert!((d.v[i] - a[i]).abs() < 1e-14);
        }
        let m = d.applied::<Planar>(&Motion::default());
        assert_eq!(m.attitude, d.d[2]);
    }
}
