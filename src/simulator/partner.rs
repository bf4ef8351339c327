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
//! the deviation from the host's path integrated by the trapezoidal rule and its end
//! acceleration solved with the step: at the communication step's start exactly (a jump, with
//! I − G M_app, M_app the beam's apparent mass at the mount, [`Simulator::apparent_mass`]),
//! then per internal step by a quasi-Newton iteration on the deviation's end acceleration
//! (Broyden's update of the matrix from (I − G M_app)⁻¹, each iteration the beam's step
//! repeated) to [`PARTNER_TOLERANCE`] × `solver.tolerance` of the equation's terms, or, where
//! the step's reaction does not resolve that, to the Newton tolerance; a step that meets
//! neither within [`PARTNER_ITERATIONS`] fails, is halved, and at the halving limit is refused
//! naming the residual (`SimError::Partner`; the FMU's fmi2Discard, the state kept). So at
//! every communication point the mount's acceleration the beam used meets the equation.
//!
//! The stiff, fast part of the coupling is thereby implicit in the beam; the host's next input
//! re-anchors the beam at the host's motion. The mount's path continues from the deviated pose
//! and velocity with the host's accelerations, which hold until the host sets them again (an
//! FMI input keeps its value), the deviation of the accelerations held beside it: a host that
//! does not send unchanged inputs again steps as one that does. This is the interface-mass
//! idea of Morandini & Masarati (`docs/references.md` §8) with the host's mass on the beam's
//! side given as its mobility. A zero mobility (the default) leaves the step exactly as
//! without the model.

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

    /// The partner's slot of this input (`None` for another input or a component outside
    /// the partner's arrays).
    pub(super) fn slot(&mut self, id: InputId) -> Option<&mut f64> {
        let (p, k) = (self, id.component);
        match id.kind {
            InputKind::MountMobility => p
                .mobility
                .get_mut(k / PARTNER_COMPONENTS)
                .map(|row| &mut row[k % PARTNER_COMPONENTS]),
            InputKind::MountReactionReference => p.reference.get_mut(k),
            _ => None,
        }
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

/// A matrix of the partner's components as rows (the plane's 3 × 3 in the upper left).
pub(super) type PartnerMatrix = [[f64; PARTNER_COMPONENTS]; PARTNER_COMPONENTS];

/// A vector of the partner's components (the plane's 3 in the first places, the others zero).
type Vector = nalgebra::Vector6<f64>;

/// A matrix of the partner's components (the plane's 3 × 3 in the upper left, the identity in
/// the rest).
type Matrix = nalgebra::Matrix6<f64>;

/// The partner model over one communication step: the mobility and the iteration's matrix.
pub(super) struct PartnerStep {
    partner: Partner,
    n: usize,
    /// The relative tolerance of the equation ([`PARTNER_TOLERANCE`] · solver.tolerance).
    tolerance: f64,
    /// Per component, the largest correction of a₁ within the Newton tolerance at a step h,
    /// times h²: 4 · solver.tolerance · ℓᵢ ([`PARTNER_TOLERANCE`]).
    newton: [f64; PARTNER_COMPONENTS],
    /// (I − G M_app)⁻¹: the start's exact solve, and the iteration's matrix at a new step size.
    start: Matrix,
    /// The iteration's approximation of (∂res/∂a₁)⁻¹, res = a₁ − G (R(a₁) − R_ref) after an
    /// internal step of `learned_h`: (I − G M_app)⁻¹ to begin with, then corrected by Broyden's
    /// update with each iteration's secant, held over the internal steps of that size.
    inverse: Matrix,
    /// The internal step `inverse` was learned at (0: none yet).
    learned_h: f64,
    /// The change of the deviation's acceleration over the last internal step, per second
    /// (the next step's first guess extrapolates it).
    trend: [f64; PARTNER_COMPONENTS],
}

/// Why an internal step with the partner model failed.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum PartnerFailure {
    /// The beam's step failed.
    Step(crate::integrator::StepFailure),
    /// The partner equation was not met within [`PARTNER_ITERATIONS`] iterations.
    Unconverged {
        /// The internal step [s].
        h: f64,
        /// The last iteration's residual relative to the magnitude of the terms.
        residual: f64,
        /// The tolerance it missed.
        tolerance: f64,
        /// The correction of a₁ left, relative to the one within the Newton tolerance.
        correction: f64,
    },
}

impl PartnerStep {
    /// The step's model from the partner, the beam's apparent mass now, the solver's Newton
    /// tolerance and the Newton scale of positions (the beam's length) in a space of `dim`
    /// dimensions; `None` if I − G M_app is singular (to rounding).
    fn new(
        partner: Partner,
        (apparent, n): (&PartnerMatrix, usize),
        newton_tolerance: f64,
        (length, dim): (f64, usize),
    ) -> Option<Self> {
        let jac = Matrix::from_fn(|i, j| {
            let gm: f64 = if i < n && j < n {
                (0..n)
                    .map(|k| partner.mobility[i][k] * apparent[k][j])
                    .sum()
            } else {
                0.0
            };
            f64::from(u8::from(i == j)) - gm
        });
        let lu = jac.lu();
        // singular to rounding: a pivot below 1e-9 of the largest or of the identity's
        let pivots = lu.u().diagonal().map(f64::abs);
        let regular = pivots.min() > 1e-9 * pivots.max().max(1.0);
        if !regular {
            return None;
        }
        let start = lu.try_inverse()?;
        Some(Self {
            partner,
            n,
            tolerance: PARTNER_TOLERANCE * newton_tolerance,
            newton: std::array::from_fn(|i| {
                4.0 * newton_tolerance * if i < dim { length } else { 1.0 }
            }),
            start,
            inverse: start,
            learned_h: 0.0,
            trend: [0.0; PARTNER_COMPONENTS],
        })
    }

    /// The host's answer G (R − R_ref) to the reaction `r` (components as [`Partner`]).
    fn answer(&self, r: &[f64; PARTNER_COMPONENTS]) -> Vector {
        let (g, r_ref) = (&self.partner.mobility, &self.partner.reference);
        Vector::from_fn(|i, _| {
            (0..self.n)
                .map(|j| {
                    if i < self.n {
                        g[i][j] * (r[j] - r_ref[j])
                    } else {
                        0.0
                    }
                })
                .sum::<f64>()
        })
    }

    /// The magnitude of the terms of component `i` of the equation at `a1` and the reaction
    /// `r`: |a₁ᵢ| + Σⱼ |Gᵢⱼ| (|Rⱼ| + |R_ref,ⱼ|).
    fn scale(
        &self,
        i: usize,
        a1: &[f64; PARTNER_COMPONENTS],
        r: &[f64; PARTNER_COMPONENTS],
    ) -> f64 {
        let (g, r_ref) = (&self.partner.mobility, &self.partner.reference);
        a1[i].abs()
            + (0..self.n)
                .map(|j| g[i][j].abs() * (r[j].abs() + r_ref[j].abs()))
                .sum::<f64>()
    }

    /// The residual a₁ − G (R − R_ref) of the deviation's end acceleration `a1` with the
    /// reaction `r`, and its largest component relative to the magnitude of its terms
    /// ([`PartnerStep::scale`], [`PARTNER_TOLERANCE`]).
    fn residual(
        &self,
        a1: &[f64; PARTNER_COMPONENTS],
        r: &[f64; PARTNER_COMPONENTS],
    ) -> (Vector, f64) {
        let answer = self.answer(r);
        let res = Vector::from_fn(|i, _| if i < self.n { a1[i] - answer[i] } else { 0.0 });
        let relative = (0..self.n)
            .map(|i| {
                if res[i] == 0.0 {
                    0.0
                } else {
                    res[i].abs() / self.scale(i, a1, r)
                }
            })
            .fold(0.0, f64::max);
        (res, relative)
    }

    /// The largest correction `delta` of a₁ at a step `h` relative to the one within the
    /// Newton tolerance (≤ 1: within it).
    fn correction(&self, delta: &Vector, h: f64) -> f64 {
        (0..self.n)
            .map(|i| h * h * delta[i].abs() / self.newton[i])
            .fold(0.0, f64::max)
    }

    /// The correction of a₁ for the residual `res`: the iteration's matrix times it, but for a
    /// component whose row of G is zero, whose equation a₁ᵢ = 0 is solved exactly (so that no
    /// secant's coupling leaves it a value the equation has no scale for).
    fn correct(&self, res: &Vector) -> Vector {
        let mut delta = self.inverse * res;
        for (i, row) in self.partner.mobility.iter().enumerate().take(self.n) {
            if row.iter().take(self.n).all(|g| *g == 0.0) {
                delta[i] = res[i];
            }
        }
        delta
    }

    /// Broyden's ("good") update of [`PartnerStep::inverse`] with the secant of an iteration:
    /// the step `s` of a₁ changed the residual by `y`.
    fn learn(&mut self, s: &Vector, y: &Vector) {
        let hy = self.inverse * y;
        let sh = s.transpose() * self.inverse;
        let denom = s.dot(&hy);
        if denom.abs() > 1e-12 * s.norm() * hy.norm() && denom.is_finite() {
            self.inverse += (s - hy) * sh / denom;
        }
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
    pub(super) fn reaction_now(&self) -> [f64; PARTNER_COMPONENTS] {
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
        let (apparent, n) = self
            .apparent_mass_array()
            .ok_or_else(|| refused("the beam's apparent mass at the mount could not be solved"))?;
        let scale = (self.scene.total_length(), S::DIM);
        PartnerStep::new(
            partner,
            (&apparent, n),
            self.scene.solver.newton_tolerance(),
            scale,
        )
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
    /// The mount is at the host's path here ([`Simulator::take_mount_input`] took it back from
    /// the last step's deviation).
    pub(super) fn partner_start(&mut self, p: &PartnerStep) -> Result<Deviation, SimError> {
        let t = self.state.t;
        let a0 = p.start * p.answer(&self.reaction_now());
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
    /// a₁ solved with the step so that it equals G (R − R_ref) there to the partner tolerance
    /// ([`PARTNER_TOLERANCE`]). Each iteration is the beam's step with the deviation of a₁,
    /// then a quasi-Newton update of a₁ from the residual with [`PartnerStep::inverse`], which
    /// Broyden's update corrects by each iteration's secant; the first guess extrapolates the
    /// last step's change. (I − G M_app, the start's exact matrix, holds for a jump at a fixed
    /// state; over a step the reaction answers a₁ through the step's own apparent mass M_h,
    /// which the elastic coordinates' motion within the step makes differ from M_app. With the
    /// fixed matrix the iteration contracts by ‖(I − G M_app)⁻¹ G (M_h − M_app)‖, which for a
    /// host lighter than the beam, ‖G M_app‖ > 1, tends to ‖M_app⁻¹ (M_h − M_app)‖ whatever
    /// the host's mass: 8 iterations of it left up to 2e-3 of the deviation there. The secants
    /// learn M_h, which barely changes from one internal step to the next.) Each attempt
    /// starts from the step's start with the same Newton rate estimate, so that the beam's
    /// Newton iteration stops by the same rule and the reaction is a smooth function of a₁: a
    /// rate estimate carried from attempt to attempt moved the stopping point, a noise in R
    /// that stalled the iteration at up to 1e-6 of the terms. On failure, of the beam's step or
    /// of the iteration after [`PARTNER_ITERATIONS`], the state is the one at the step's start.
    pub(super) fn step_with_partner(
        &mut self,
        p: &mut PartnerStep,
        dev: &mut Deviation,
        span: (f64, f64, f64),
        inputs: &Inputs<S>,
    ) -> Result<(), PartnerFailure> {
        // the step's start, copied into a kept state (no allocation), taken out for the step
        let mut start = std::mem::replace(&mut self.work.1, State::at_rest(0.0, Vec::new(), 0));
        start.copy_from(&self.state);
        let done = self.partner_iterations(p, dev, span, inputs, &start);
        if done.is_err() {
            // the state at the step's start (its vectors swapped, not moved: both stay sized)
            std::mem::swap(&mut self.state, &mut start);
        }
        self.work.1 = start;
        done
    }

    /// [`Simulator::step_with_partner`]'s iteration from the state `start` (on failure the
    /// caller returns to it).
    fn partner_iterations(
        &mut self,
        p: &mut PartnerStep,
        dev: &mut Deviation,
        span: (f64, f64, f64),
        inputs: &Inputs<S>,
        start: &State,
    ) -> Result<(), PartnerFailure> {
        let h = span.2;
        // each attempt repeats the step from the same state, its Newton iteration stopped by
        // the same rule
        let eta = self.integ.rate_estimate();
        if (h - p.learned_h).abs() > 1e-9 * h {
            // a new step size (a halving): its own apparent mass, learned anew
            p.inverse = p.start;
            p.learned_h = h;
            p.trend = [0.0; PARTNER_COMPONENTS];
        }
        let mut a1: [f64; PARTNER_COMPONENTS] = std::array::from_fn(|i| dev.a[i] + h * p.trend[i]);
        // the previous iteration's a₁ and residual: the secant
        let mut last: Option<(Vector, Vector)> = None;
        let (mut residual, mut correction) = (f64::NAN, f64::NAN);
        for it in 0..PARTNER_ITERATIONS {
            let (next, res, relative) =
                match self.partner_attempt(p, dev, &a1, (start, eta), span, inputs) {
                    Ok(x) => x,
                    Err(e) => return Err(PartnerFailure::Step(e)),
                };
            let x = Vector::from_column_slice(&a1);
            if let Some((x0, r0)) = &last {
                p.learn(&(x - x0), &(res - r0));
            }
            let delta = p.correct(&res);
            (residual, correction) = (relative, p.correction(&delta, h));
            if relative <= p.tolerance || (it + 1 == PARTNER_ITERATIONS && correction <= 1.0) {
                p.trend = std::array::from_fn(|i| (a1[i] - dev.a[i]) / h);
                *dev = next;
                return Ok(());
            }
            for (a, d) in a1.iter_mut().zip(delta.iter()).take(p.n) {
                *a -= d;
            }
            last = Some((x, res));
        }
        Err(PartnerFailure::Unconverged {
            h,
            residual,
            tolerance: p.tolerance,
            correction,
        })
    }

    /// One attempt of the internal step of `span` (t₀ of the communication step, the step's
    /// end, h) from `start` (the state, the Newton rate estimate) with the deviation's end
    /// acceleration `a1`: the deviation at the end, the residual and its relative size
    /// ([`PartnerStep::residual`]).
    fn partner_attempt(
        &mut self,
        p: &PartnerStep,
        dev: &Deviation,
        a1: &[f64; PARTNER_COMPONENTS],
        (start, eta): (&State, f64),
        (t0, t_next, h): (f64, f64, f64),
        inputs: &Inputs<S>,
    ) -> Result<(Deviation, Vector, f64), crate::integrator::StepFailure> {
        let varying = self.load_rates.any();
        let t_start = start.t;
        self.state.copy_from(start);
        self.integ.set_rate_estimate(eta);
        let next = dev.advanced(a1, h);
        // the loads and the deviated mount at the step's end (each stage time of a
        // multi-stage method: the deviation's acceleration linear over the step)
        let (mount, rates) = (self.mount.as_deref(), &self.load_rates);
        let at = |m: &mut Model<S>, dt: f64| {
            let t = super::inputs::stage_time(t_start, t_next, h, dt);
            if varying {
                rates.advanced(inputs, t - t0).apply(m);
            }
            if let Some(ms) = mount {
                let d = if dt == h {
                    next.clone()
                } else {
                    let f = dt / h;
                    let a: [f64; PARTNER_COMPONENTS] =
                        std::array::from_fn(|i| dev.a[i] + f * (a1[i] - dev.a[i]));
                    dev.advanced(&a, dt)
                };
                m.set_mount(&d.applied(&ms.at(t)));
            }
        };
        self.integ.step(&mut self.model, &mut self.state, h, at)?;
        let (res, relative) = p.residual(a1, &self.reaction_now());
        Ok((next, res, relative))
    }

    /// After a communication step with the partner model: the mount's path continues from
    /// where the deviation took it, its pose and velocity, with the host's accelerations (the
    /// inputs, which hold until set again); the deviation's acceleration, which the state is
    /// consistent with, is kept beside it ([`MountState::deviation`]) and the next step takes
    /// the mount back to the path before it solves its own. So a host that holds its
    /// acceleration inputs steps as one that sends the same values again, and the deviation is
    /// answered once, never added to the host's acceleration. The host's next pose or velocity
    /// input re-anchors the beam from there.
    pub(super) fn continue_deviated(&mut self, dev: &Deviation, t_end: f64) {
        if let Some(ms) = &mut self.mount {
            let host = ms.at(t_end);
            ms.base = dev.applied(&host).with_accelerations_of(&host);
            ms.deviation = dev.a;
            ms.t0 = t_end;
            ms.rates = MotionRates::default();
        }
    }
}

/// `m` with the accelerations `a` (components as [`Partner`]) added, as
/// [`Deviation::applied`] adds them.
pub(super) fn accelerated<S: Space>(m: &Motion<S>, a: &[f64; PARTNER_COMPONENTS]) -> Motion<S> {
    let mut m = *m;
    let dim = S::DIM;
    for k in 0..dim {
        m.acceleration[k] += a[k];
    }
    for (k, x) in S::moment_components_mut(&mut m.angular_acceleration)
        .iter_mut()
        .enumerate()
    {
        *x += a[dim + k];
    }
    m
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
