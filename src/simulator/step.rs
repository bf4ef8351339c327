//! The step: [`Simulator::advance`] to a time in equal internal steps with halving, or in the
//! steps the ESDIRK4's error control chooses (`solver.error_tolerance`), and one roll-back; the
//! refusals of a converged state outside the model's validity, and the static solve.

use super::partner::{PartnerFailure, PartnerStep};
use super::*;
use crate::integrator::{control, StepFailure};

/// Internal step control carried from one communication step to the next.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepControl {
    /// Largest internal step that recently succeeded [s] (≤ `solver.max_step`); with error
    /// control (`solver.error_tolerance`) the step it proposes for the next internal step
    /// (`solver.max_step` at the start).
    pub h_ok: f64,
    /// Communication steps completed without a rejected attempt since `h_ok` last changed.
    pub calm: u32,
}

/// Relative rounding guard of the step count: a span of k·h_max computed as a difference of
/// times carries rounding of this order, so an internal step may exceed `solver.max_step` by
/// this fraction.
pub(super) const STEP_ROUNDING: f64 = 1e-9;

impl<S: Space> Simulator<S> {
    /// Keeps the state and mount path at the start of a communication step in `backup`
    /// (copied into its vectors: no allocation once their sizes are set).
    fn save(&mut self) {
        let (state, mount) = &mut self.backup;
        state.copy_from(&self.state);
        mount.clone_from(&self.mount);
    }

    /// Returns to the state, step control `step` and mount path at the start of a failed or
    /// refused communication step (the held Newton matrix belongs to the abandoned attempt;
    /// the applied inputs change only when a step succeeds).
    fn roll_back(&mut self, step: StepControl) {
        // the applied loads (an attempt left the pending ones, or their values within the step)
        self.applied.apply(&mut self.model);
        let (state, mount) = &mut self.backup;
        if let Some(ms) = mount.as_deref() {
            self.model.set_mount(&ms.held(state.t));
        }
        std::mem::swap(&mut self.mount, mount);
        std::mem::swap(&mut self.state, state);
        self.step = step;
        self.integ.invalidate();
    }

    /// Advances to `t_end` in equal internal steps no larger than `solver.max_step`, halving
    /// a step that fails (at most [`MAX_HALVINGS`] times, never below [`MIN_STEP`]) — with
    /// `solver.error_tolerance`, in the steps its error control chooses up to
    /// `solver.max_step`, the last ending on `t_end` ([`Simulator::controlled_steps`]) — with at
    /// most `solver.max_internal_steps` internal steps, accepted or rejected, in the call. A
    /// span that needs more steps of `solver.max_step` is refused before any work. On failure
    /// the state is the one at the start of the call and the error says why and what to
    /// change.
    ///
    /// Inputs set since the last step (tip force, tip moment, gravity) are a discontinuity at the current
    /// time: the step starts from accelerations and multipliers consistent with them
    /// ([`GeneralizedAlpha::change_inputs`]), so a force held over a communication step is
    /// integrated as exactly that force. Constant inputs leave the integrator untouched.
    pub fn advance(&mut self, t_end: f64) -> Result<(), SimError> {
        let t0 = self.state.t;
        let span = t_end - t0;
        if span.is_nan() || span <= 0.0 || !span.is_finite() {
            return Err(SimError::BadTime { t0, t_end });
        }
        let h_max = self.scene.solver.max_step;
        let cap = self.scene.solver.max_internal_steps;
        let needed = (span / h_max * (1.0 - STEP_ROUNDING)).ceil();
        if needed > cap as f64 {
            return Err(SimError::WorkCap {
                t0,
                t_end,
                needed,
                h_max,
                cap,
            });
        }
        // start from the step that last worked; grow back after a few calm calls (the error
        // control's proposal is its own)
        let controlled = self.scene.solver.error_tolerance.is_some();
        if !controlled && self.step.h_ok < h_max && self.step.calm >= CALM_BEFORE_GROWTH {
            self.step = StepControl {
                h_ok: (2.0 * self.step.h_ok).min(h_max),
                calm: 0,
            };
        }
        self.save();
        let saved = self.step;
        let inputs = self.pending;
        let done = self.take_mount_input().and_then(|jump| {
            self.jump_inputs(t0, &inputs, jump)?;
            let (steps, halvings) = self.internal_steps(t0, t_end, &inputs)?;
            self.state.t = t_end;
            self.refusal(t_end)?;
            Ok((steps, halvings))
        });
        match done {
            Ok((steps, halvings)) => {
                self.commit(&inputs, span, steps, halvings);
                Ok(())
            }
            Err(e) => {
                // the one roll-back: every failure returns to the start of the call
                self.roll_back(saved);
                Err(e)
            }
        }
    }

    /// Makes the state consistent with inputs that changed since the last step (or a mount
    /// acceleration `jump`): a jump of the inputs at the current time.
    fn jump_inputs(
        &mut self,
        t0: f64,
        inputs: &Inputs<S>,
        jump: Option<Motion<S>>,
    ) -> Result<(), SimError> {
        if *inputs == self.applied && jump.is_none() {
            return Ok(());
        }
        // the model holds the applied inputs; the jump moves it to the pending ones
        self.integ
            .change_inputs(&mut self.model, &mut self.state, |m| {
                inputs.apply(m);
                if let Some(j) = &jump {
                    m.set_mount(j);
                }
            })
            .map_err(|source| SimError::InputJump { t: t0, source })
    }

    /// The internal steps from `t0` to `t_end`: equal steps halving a failing one
    /// ([`Simulator::equal_steps`]), or with `solver.error_tolerance` the steps the error
    /// control chooses ([`Simulator::controlled_steps`]); returns the number of steps the span
    /// ended in and the halvings (none with error control).
    fn internal_steps(
        &mut self,
        t0: f64,
        t_end: f64,
        inputs: &Inputs<S>,
    ) -> Result<(u64, u32), SimError> {
        // the partner model: its iteration's matrix from the apparent mass once per
        // communication step
        let mut partner = self.partner_step()?;
        let mut dev = match &partner {
            Some(p) => self.partner_start(p)?,
            None => partner::Deviation::default(),
        };
        let done = if self.scene.solver.error_tolerance.is_some() {
            self.controlled_steps(t0, t_end, inputs, (&mut partner, &mut dev))?
        } else {
            self.equal_steps(t0, t_end, inputs, (&mut partner, &mut dev))?
        };
        if partner.is_some() {
            self.continue_deviated(&dev, t_end);
        }
        Ok(done)
    }

    /// Equal internal steps from `t0` to `t_end`, halving a failing one (which doubles the
    /// steps still to go); returns the number of steps the span ended in and the halvings.
    fn equal_steps(
        &mut self,
        t0: f64,
        t_end: f64,
        inputs: &Inputs<S>,
        (partner, dev): (&mut Option<PartnerStep>, &mut partner::Deviation),
    ) -> Result<(u64, u32), SimError> {
        let span = t_end - t0;
        let cap = self.scene.solver.max_internal_steps;
        let h_start = self.step.h_ok;
        // more steps of a reduced h_ok than the cap allows: start from span / cap (≤ h_max)
        let mut steps = ((span / h_start * (1.0 - STEP_ROUNDING)).ceil().max(1.0) as u64).min(cap);
        let mut done = 0u64;
        let mut attempts = 0u64;
        let mut halvings = 0;
        while done < steps {
            let h = span / steps as f64;
            attempts += 1;
            let t_next = if done + 1 == steps {
                t_end
            } else {
                t0 + span * ((done + 1) as f64 / steps as f64)
            };
            match self.attempt(partner, dev, (t0, t_next, h), inputs) {
                Ok(()) => done += 1,
                Err(e) => {
                    halvings += 1;
                    // a halving doubles the steps still to go
                    let work = attempts + 2 * (steps - done);
                    self.rejected(t0, halvings, (h, 0.5 * h), work, e)?;
                    steps *= 2;
                    done *= 2;
                }
            }
        }
        Ok((steps, halvings))
    }

    /// The internal steps from `t0` to `t_end` that the error control chooses
    /// (`solver.error_tolerance`, [`control`]): what is left of the span in equal steps no
    /// larger than the proposed step (so the last lands on `t_end` exactly, and a proposal that
    /// holds gives the same step, and Newton matrix, from one communication step to the next),
    /// a step whose error estimate is above the tolerance retried smaller (a failing one
    /// halved) from the same state, the proposal after each accepted step kept in the step
    /// control (`h_ok`) for the next call. Returns the accepted steps and no halvings.
    fn controlled_steps(
        &mut self,
        t0: f64,
        t_end: f64,
        inputs: &Inputs<S>,
        (partner, dev): (&mut Option<PartnerStep>, &mut partner::Deviation),
    ) -> Result<(u64, u32), SimError> {
        let h_max = self.scene.solver.max_step;
        let mut proposed = self.step.h_ok;
        let (mut steps, mut attempts, mut rejections) = (0u64, 0u64, 0u32);
        loop {
            let t = self.state.t;
            let left = t_end - t;
            let n = (left / proposed * (1.0 - STEP_ROUNDING)).ceil().max(1.0);
            let (h, t_next) = if n <= 1.0 {
                (left, t_end)
            } else {
                (left / n, t + left / n)
            };
            attempts += 1;
            match self.attempt(partner, dev, (t0, t_next, h), inputs) {
                Ok(()) => {
                    steps += 1;
                    let err = self.integ.step_error().unwrap_or(0.0);
                    proposed = control::after_accepted(h, err, proposed, rejections > 0, h_max)
                        .max(MIN_STEP);
                    rejections = 0;
                    if t_next == t_end {
                        self.step.h_ok = proposed;
                        return Ok((steps, 0));
                    }
                }
                Err(e) => {
                    rejections += 1;
                    let estimate = match &e {
                        PartnerFailure::Step(StepFailure::ErrorEstimate { error, .. }) => {
                            Some(*error)
                        }
                        _ => None,
                    };
                    let next = control::after_rejected(h, estimate);
                    let work = attempts + (left / next).ceil() as u64;
                    self.rejected(t0, rejections, (h, next), work, e)?;
                    proposed = next;
                }
            }
        }
    }

    /// One internal step attempt of size `h` from the current state to `t_next` (in the
    /// communication step from `t0`), with the partner model if it acts: the time-dependent
    /// inputs set where the step's equations hold (its end; each stage time of a multi-stage
    /// method). On success the state is at `t_next`; on failure at the step's start.
    fn attempt(
        &mut self,
        partner: &mut Option<PartnerStep>,
        dev: &mut partner::Deviation,
        (t0, t_next, h): (f64, f64, f64),
        inputs: &Inputs<S>,
    ) -> Result<(), PartnerFailure> {
        let stepped = match partner {
            Some(p) => self.step_with_partner(p, dev, (t0, t_next, h), inputs),
            None => {
                let varying = self.load_rates.any();
                let t_start = self.state.t;
                let (mount, rates) = (self.mount.as_deref(), &self.load_rates);
                let at = |m: &mut Model<S>, dt: f64| {
                    let t = inputs::stage_time(t_start, t_next, h, dt);
                    if let Some(ms) = mount {
                        m.set_mount(&ms.at(t));
                    }
                    if varying {
                        rates.advanced(inputs, t - t0).apply(m);
                    }
                };
                self.integ
                    .step(&mut self.model, &mut self.state, h, at)
                    .map(|_| ())
                    .map_err(PartnerFailure::Step)
            }
        };
        if stepped.is_ok() {
            self.min_step_used = self.min_step_used.min(h);
            self.state.t = t_next;
        }
        stepped
    }

    /// A failed attempt (`e`) of size `h` in the communication step from `t0`, the `tries`-th
    /// in a row, counted as a rejection; the communication step's error if it may not be
    /// retried with `next`, `work` the attempts done and still to do then: the real-time mode
    /// never retries; [`MAX_HALVINGS`], [`MIN_STEP`], `solver.max_internal_steps`.
    fn rejected(
        &mut self,
        t0: f64,
        tries: u32,
        (h, next): (f64, f64),
        work: u64,
        e: PartnerFailure,
    ) -> Result<(), SimError> {
        self.integ.counters_mut().rejected += 1;
        let cap = self.scene.solver.max_internal_steps;
        let limit = if self.scene.solver.mode == crate::integrator::Mode::Realtime {
            StepLimit::Realtime
        } else if tries > MAX_HALVINGS {
            StepLimit::MaxHalvings
        } else if next < MIN_STEP {
            StepLimit::MinStep { h }
        } else if work > cap {
            StepLimit::WorkCap {
                halvings: tries - 1,
                cap,
            }
        } else {
            return Ok(());
        };
        Err(failed(t0, tries - 1, limit, e))
    }

    /// The refusal of the state reached at `t_end`, if the model cannot accept it: non-finite,
    /// a modal segment beyond its deflection limit, an unrepresentable section, too much axial
    /// strain.
    fn refusal(&self, t_end: f64) -> Result<(), SimError> {
        let validity = self.model.validity(&self.state.q);
        let strain = validity.max_axial_strain;
        let finite = self
            .state
            .q
            .iter()
            .chain(&self.state.v)
            .all(|x| x.is_finite());
        let modal = validity
            .modal_deflection
            .filter(|&(_, d)| finite && d > MAX_MODAL_DEFLECTION);
        if let Some((si, d)) = modal {
            return Err(SimError::Refused {
                t: t_end,
                refusal: Refusal::ModalDeflection {
                    segment: self.scene.segments[si].name.clone(),
                    value: d,
                },
            });
        }
        if let Some(refusal) = self.section_refusal(&validity, true).filter(|_| finite) {
            return Err(SimError::Refused { t: t_end, refusal });
        }
        let limit = self.scene.solver.max_axial_strain;
        if !finite || strain > limit {
            return Err(if finite {
                SimError::Refused {
                    t: t_end,
                    refusal: Refusal::AxialStrain {
                        value: strain,
                        limit,
                    },
                }
            } else {
                SimError::NonFinite { t: t_end }
            });
        }
        Ok(())
    }

    /// Completes a communication step of `span` that ended in `steps` internal steps after
    /// `halvings`: the applied inputs (their values at its end when they had derivatives) and
    /// the step control for the next call.
    fn commit(&mut self, inputs: &Inputs<S>, span: f64, steps: u64, halvings: u32) {
        self.applied = if self.load_rates.any() {
            // the loads went on to their values at t_end, which stay set (the derivatives held
            // for this step)
            let end = self.load_rates.advanced(inputs, span);
            self.load_rates = LoadRates::default();
            self.pending = end;
            end
        } else {
            *inputs
        };
        if self.scene.solver.error_tolerance.is_some() {
            // the error control set its proposal
        } else if halvings > 0 {
            self.step = StepControl {
                h_ok: span / steps as f64,
                calm: 0,
            };
        } else {
            self.step.calm = self.step.calm.saturating_add(1);
        }
    }

    /// The refusal of a configuration whose ANCF section directors the elements cannot
    /// represent: a director (nearly) parallel to its slope ([`MIN_SECTION_SINE`]) and, with
    /// `twist`, more twist within one element than [`MAX_TWIST_PER_ELEMENT`]; a node of an
    /// element with twist angles turned too far from the initial axis ([`MIN_CHART_MARGIN`]).
    pub(super) fn section_refusal(&self, v: &ModelValidity, twist: bool) -> Option<Refusal> {
        let name = |si: usize| self.scene.segments[si].name.clone();
        if let Some((si, value)) = v.min_chart_margin.filter(|&(_, m)| m < MIN_CHART_MARGIN) {
            return Some(Refusal::TwistChart {
                segment: name(si),
                value,
            });
        }
        if let Some((si, value)) = v.min_section_sine.filter(|&(_, s)| s < MIN_SECTION_SINE) {
            return Some(Refusal::SectionDirector {
                segment: name(si),
                value,
            });
        }
        v.max_twist
            .filter(|&(_, w)| twist && w > MAX_TWIST_PER_ELEMENT)
            .map(|(si, value)| Refusal::Twist {
                segment: name(si),
                value,
            })
    }

    /// Solves the static equilibrium from the current state under the current loads.
    pub fn solve_static(&mut self) -> Result<usize, SimError> {
        let tol = self.scene.solver.static_tolerance();
        let it = solve_static(&mut self.model, &mut self.state, tol)?;
        self.integ.invalidate();
        Ok(it)
    }
}

/// The error of a communication step from `t0` whose internal step failed with `e` and could
/// not be retried (`limit`) after `halvings` (reported at the time the state returns to).
fn failed(t0: f64, halvings: u32, limit: StepLimit, e: PartnerFailure) -> SimError {
    match e {
        PartnerFailure::Step(source) => SimError::Step {
            t: t0,
            halvings,
            limit,
            source,
        },
        PartnerFailure::Unconverged {
            h,
            residual,
            tolerance,
            correction,
        } => SimError::Partner {
            t: t0,
            halvings,
            limit,
            h,
            residual,
            tolerance,
            correction,
        },
    }
}
