//! The step: [`Simulator::advance`] to a time in equal internal steps with halving and one
//! roll-back, the refusals of a converged state outside the model's validity, and the static
//! solve.

use super::*;

/// Internal step control carried from one communication step to the next.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepControl {
    /// Largest internal step that recently succeeded [s] (≤ `solver.max_step`).
    pub h_ok: f64,
    /// Communication steps completed without a rejected attempt since `h_ok` last changed.
    pub calm: u32,
}

/// Relative rounding guard of the step count: a span of k·h_max computed as a difference of
/// times carries rounding of this order, so an internal step may exceed `solver.max_step` by
/// this fraction.
pub(super) const STEP_ROUNDING: f64 = 1e-9;

impl<S: SpaceModel> Simulator<S> {
    /// Returns to the state, step control and mount path of the start of an `advance` call
    /// after a failed or refused communication step (the held Newton matrix belongs to the
    /// abandoned attempt).
    pub(super) fn roll_back(
        &mut self,
        saved: State,
        saved_step: StepControl,
        mount: Option<Box<MountState<S>>>,
        inputs: &Inputs<S>,
    ) {
        // the loads set for the step (an attempt may have left them at a time within it)
        inputs.apply(&mut self.model);
        if let Some(ms) = &mount {
            self.model.set_mount(&ms.at(saved.t));
        }
        self.mount = mount;
        self.state = saved;
        self.step = saved_step;
        self.integ.invalidate();
    }

    /// Advances to `t_end` in equal internal steps no larger than `solver.max_step`, halving
    /// a step that fails (at most [`MAX_HALVINGS`] times, never below [`MIN_STEP`]), with at
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
        // start from the step that last worked; grow back after a few calm calls
        if self.step.h_ok < h_max && self.step.calm >= CALM_BEFORE_GROWTH {
            self.step = StepControl {
                h_ok: (2.0 * self.step.h_ok).min(h_max),
                calm: 0,
            };
        }
        let h_start = self.step.h_ok;
        let saved = self.state.clone();
        let saved_step = self.step;
        let saved_mount = self.mount.clone();
        let inputs = Inputs::of(&self.model);
        let mount_jump = match self.take_mount_input() {
            Ok(j) => j,
            Err(e) => {
                self.roll_back(saved, saved_step, saved_mount, &inputs);
                return Err(e);
            }
        };
        if inputs != self.applied || mount_jump.is_some() {
            self.applied.apply(&mut self.model);
            let changed = self
                .integ
                .change_inputs(&mut self.model, &mut self.state, |m| {
                    inputs.apply(m);
                    if let Some(j) = &mount_jump {
                        m.set_mount(j);
                    }
                })
                .map_err(|source| SimError::InputJump { t: t0, source });
            if let Err(e) = changed {
                self.roll_back(saved, saved_step, saved_mount, &inputs);
                return Err(e);
            }
        }
        // more steps of a reduced h_ok than the cap allows: start from span / cap (≤ h_max)
        let mut steps = ((span / h_start * (1.0 - STEP_ROUNDING)).ceil().max(1.0) as u64).min(cap);
        let mut done = 0u64;
        let mut attempts = 0u64;
        let mut halvings = 0;
        let varying = self.load_rates.any();
        while done < steps {
            let h = span / steps as f64;
            attempts += 1;
            let t_next = if done + 1 == steps {
                t_end
            } else {
                t0 + span * ((done + 1) as f64 / steps as f64)
            };
            if let Some(ms) = &self.mount {
                self.model.set_mount(&ms.at(t_next));
            }
            if varying {
                // the loads at the step's end, where its equations hold
                self.load_rates
                    .advanced(&inputs, t_next - t0)
                    .apply(&mut self.model);
            }
            match self.integ.step(&mut self.model, &mut self.state, h) {
                Ok(_) => {
                    done += 1;
                    self.min_step_used = self.min_step_used.min(h);
                    self.state.t = t0 + span * (done as f64 / steps as f64);
                }
                Err(e) => {
                    self.integ.counters.rejected += 1;
                    halvings += 1;
                    // a halving doubles the steps still to go
                    let limit = if halvings > MAX_HALVINGS {
                        Some(StepLimit::MaxHalvings)
                    } else if 0.5 * h < MIN_STEP {
                        Some(StepLimit::MinStep { h })
                    } else if attempts + 2 * (steps - done) > cap {
                        Some(StepLimit::WorkCap {
                            halvings: halvings - 1,
                            cap,
                        })
                    } else {
                        None
                    };
                    if let Some(limit) = limit {
                        self.roll_back(saved, saved_step, saved_mount, &inputs);
                        return Err(SimError::Step {
                            t: self.state.t,
                            halvings: halvings - 1,
                            limit,
                            source: e,
                        });
                    }
                    steps *= 2;
                    done *= 2;
                }
            }
        }
        self.state.t = t_end;
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
            self.roll_back(saved, saved_step, saved_mount, &inputs);
            return Err(SimError::Refused {
                t: t_end,
                refusal: Refusal::ModalDeflection {
                    segment: self.scene.segments[si].name.clone(),
                    value: d,
                },
            });
        }
        if let Some(refusal) = self.section_refusal(&validity, true).filter(|_| finite) {
            self.roll_back(saved, saved_step, saved_mount, &inputs);
            return Err(SimError::Refused { t: t_end, refusal });
        }
        if !finite || strain > MAX_AXIAL_STRAIN {
            self.roll_back(saved, saved_step, saved_mount, &inputs);
            return Err(if finite {
                SimError::Refused {
                    t: t_end,
                    refusal: Refusal::AxialStrain { value: strain },
                }
            } else {
                SimError::NonFinite { t: t_end }
            });
        }
        self.applied = if varying {
            // the loads went on to their values at t_end, which stay set (the derivatives held
            // for this step)
            let end = self.load_rates.advanced(&inputs, span);
            self.load_rates = LoadRates::default();
            end
        } else {
            inputs
        };
        if halvings > 0 {
            self.step = StepControl {
                h_ok: span / steps as f64,
                calm: 0,
            };
        } else {
            self.step.calm = self.step.calm.saturating_add(1);
        }
        Ok(())
    }

    /// The refusal of a configuration whose ANCF section directors the elements cannot
    /// represent: a director (nearly) parallel to its slope ([`MIN_SECTION_SINE`]) and, with
    /// `twist`, more twist within one element than [`MAX_TWIST_PER_ELEMENT`].
    pub(super) fn section_refusal(&self, v: &ModelValidity, twist: bool) -> Option<Refusal> {
        let name = |si: usize| self.scene.segments[si].name.clone();
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
