//! The mount's motion in time, as the simulator drives it: a path from the last communication
//! point (the host's pose, velocities and accelerations there, and the accelerations' rates of
//! change if the host gives input derivatives), the input set for the next step, and the
//! estimate of the accelerations from velocity inputs (`motion_input = "pose_velocity"`).

use super::*;
use crate::error::Refusal;
use crate::model::space::{moment_from, vec_from};
use crate::model::{Motion, MotionRates};
use crate::scene::{MotionInput, Mount, Scene};
use serde::{Deserialize, Serialize};

/// One mount input from a host: the motion at the current time and, optionally, the rates of
/// change of its accelerations.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct MountInput<S: Space> {
    /// Pose, velocities and accelerations (world axes; the accelerations are ignored when
    /// `accelerations` is false).
    pub motion: Motion<S>,
    /// Jerk and snap of the accelerations over the coming step (zero: constant acceleration).
    pub rates: MotionRates<S>,
    /// Whether `motion`'s accelerations are given; if not they are estimated by backward
    /// differences of the velocities between communication points.
    pub accelerations: bool,
}

/// The mount's path as integrated, and what the host set for the next step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct MountState<S: Space> {
    /// Start of the current path [s].
    pub t0: f64,
    /// The motion at `t0`.
    pub base: Motion<S>,
    /// Rates of its accelerations.
    pub rates: MotionRates<S>,
    /// Input for the next step (taken at the next `advance`).
    pub pending: Option<MountInput<S>>,
    /// The last input taken and its time (backward differences of velocities).
    pub last: Option<(f64, Motion<S>)>,
    /// Whether accelerations are inputs (`pose_velocity_acceleration`).
    pub accelerations_given: bool,
    /// The host's response at the mount (zero: none), held until set again.
    pub partner: Partner,
    /// The partner model's deviation of the mount's accelerations at `t0` from the path's
    /// (components as [`Partner`]), which the state's accelerations are consistent with: zero
    /// but after a communication step with the partner model, whose deviation the path does
    /// not carry (its accelerations stay the host's inputs); the next step takes the mount back
    /// to the path ([`MountState::held`]).
    pub deviation: [f64; PARTNER_COMPONENTS],
}

impl<S: Space> MountState<S> {
    /// The scene's start motion at `t0`, or `None` without a mount.
    pub fn of_scene(scene: &Scene, t0: f64) -> Option<Self> {
        let m = scene.mount_start()?;
        Some(Self {
            t0,
            base: motion_of::<S>(&m),
            rates: MotionRates::default(),
            pending: None,
            last: None,
            accelerations_given: m.motion_input == MotionInput::PoseVelocityAcceleration,
            partner: Partner::default(),
            deviation: [0.0; PARTNER_COMPONENTS],
        })
    }

    /// The motion the model holds at `t` (a communication point): the path's with the partner
    /// model's [`MountState::deviation`] of the accelerations.
    pub fn held(&self, t: f64) -> Motion<S> {
        let m = self.at(t);
        if self.deviation == [0.0; PARTNER_COMPONENTS] {
            m
        } else {
            super::partner::accelerated(&m, &self.deviation)
        }
    }

    /// The motion at time `t` along the path.
    pub fn at(&self, t: f64) -> Motion<S> {
        if t == self.t0 {
            return self.base;
        }
        S::advance_motion(&self.base, &self.rates, t - self.t0)
    }

    /// The input a host set for the next step, else the motion now (what a host reads back).
    pub fn input_or_now(&self, t: f64) -> MountInput<S> {
        self.pending.unwrap_or(MountInput {
            motion: self.at(t),
            rates: MotionRates::default(),
            accelerations: self.accelerations_given,
        })
    }

    /// A host input checked and normalized (finite, a defined orientation, normalized unless it
    /// is the path's own at `t`), with estimated accelerations when it gives none.
    pub fn checked(&self, input: MountInput<S>, t: f64) -> Result<MountInput<S>, Refusal> {
        let mut input = input;
        let m = &mut input.motion;
        // every component (Motion::components, read in place)
        let finite = [&m.position, &m.velocity, &m.acceleration]
            .iter()
            .flat_map(|v| v.as_ref())
            .chain(S::moment_components(&m.angular_velocity))
            .chain(S::moment_components(&m.angular_acceleration))
            .all(|x| x.is_finite())
            && S::attitude_components(&m.attitude)
                .iter()
                .all(|x| x.is_finite());
        if !finite {
            return Err(Refusal::MountInput(
                "a mount position, orientation, velocity or acceleration input is not finite"
                    .into(),
            ));
        }
        let unit = S::normalized_attitude(&m.attitude).ok_or_else(|| {
            Refusal::MountInput(
                "root.orientation is the zero quaternion: give unit Euler parameters (identity: e0 = 1, e1 = e2 = e3 = 0)".into(),
            )
        })?;
        // the path's own orientation (a host sending back what it reads) is kept as it is:
        // normalizing it anew may move its last bits, which would re-anchor the beam by them,
        // and a host that sends back the motion it reads would not step as one that sends
        // nothing
        if m.attitude != self.at(t).attitude {
            m.attitude = unit;
        }
        if !input.accelerations {
            // backward difference of the velocity inputs (previous input, else the path)
            let (tp, prev) = self.last.unwrap_or((self.t0, self.base));
            let dt = t - tp;
            if dt > 0.0 {
                for k in 0..S::DIM {
                    m.acceleration[k] = (m.velocity[k] - prev.velocity[k]) / dt;
                }
                let (w, wp) = (m.angular_velocity, prev.angular_velocity);
                let (w, wp) = (S::moment_components(&w), S::moment_components(&wp));
                for (k, a) in S::moment_components_mut(&mut m.angular_acceleration)
                    .iter_mut()
                    .enumerate()
                {
                    *a = (w[k] - wp[k]) / dt;
                }
            } else {
                m.acceleration = prev.acceleration;
                m.angular_acceleration = prev.angular_acceleration;
            }
        }
        Ok(input)
    }
}

/// The motion of a scene's `[mount]` table (vectors complete, orientation normalized).
fn motion_of<S: Space>(m: &Mount) -> Motion<S> {
    Motion {
        position: vec_from::<S>(&m.position),
        attitude: S::attitude_from(m),
        velocity: vec_from::<S>(&m.velocity),
        angular_velocity: moment_from::<S>(&m.angular_velocity),
        acceleration: vec_from::<S>(&m.acceleration),
        angular_acceleration: moment_from::<S>(&m.angular_acceleration),
    }
}

impl<S: Space> Simulator<S> {
    /// Sets the mount's motion at the current time for the next step (`root = "mounted"`):
    /// checked (finite, a defined orientation, which is normalized), with accelerations
    /// estimated from the velocities when `input.accelerations` is false. It takes effect at
    /// the next [`Simulator::advance`]: a pose or velocity that differs from the path's
    /// prediction re-anchors the beam rigidly, an acceleration that differs is a jump of the
    /// inputs; a pose further than [`MAX_MOUNT_JUMP_LENGTH`] · length or
    /// [`MAX_MOUNT_JUMP_ANGLE`] from the prediction is refused there.
    pub fn set_mount(&mut self, input: MountInput<S>) -> Result<(), SimError> {
        let t = self.state.t;
        let Some(ms) = &mut self.mount else {
            return Err(SimError::Refused {
                t,
                refusal: Refusal::MountInput(
                    "this scene's root is not mounted (set root = \"mounted\" to drive it)".into(),
                ),
            });
        };
        ms.checked(input, t)
            .map_err(|refusal| SimError::Refused { t, refusal })?;
        ms.pending = Some(input);
        Ok(())
    }

    /// The mount input set for the next step, else the motion now (`None` for a fixed root).
    pub fn mount_input(&self) -> Option<MountInput<S>> {
        self.mount.as_ref().map(|m| m.input_or_now(self.state.t))
    }

    /// Sets the mount input for the next step without checking it (a host writing one scalar
    /// at a time; [`Simulator::advance`] checks it): `false` for a fixed root.
    pub fn set_mount_unchecked(&mut self, input: MountInput<S>) -> bool {
        match &mut self.mount {
            Some(m) => {
                m.pending = Some(input);
                true
            }
            None => false,
        }
    }

    /// The beam's apparent mass at the mount: the exact partial derivatives of the reaction
    /// (`root.force` then `root.moment` components, rows) with respect to the mount's
    /// acceleration and angular acceleration (columns), at the current state — what the
    /// reaction's direct feedthrough is ([`Outputs::root_force`] after an acceleration input
    /// changes by Δa is the current one plus this matrix times Δa). Each column is the
    /// acceleration jump of a unit input change (`[M Φ_qᵀ; Φ_q 0]` solve, linear in it) on a
    /// scratch state, with the held Newton matrix set aside ([`Model::set_matrix_aside`]), so
    /// the run continues bit for bit. `None` for a fixed root or when the solve fails.
    pub fn apparent_mass(&mut self) -> Option<Vec<Vec<f64>>> {
        let (a, n) = self.apparent_mass_array()?;
        Some(a[..n].iter().map(|row| row[..n].to_vec()).collect())
    }

    /// [`Simulator::apparent_mass`] without allocating: the matrix in the upper left n × n of
    /// a partner-sized array (n = 3 planar, 6 spatial), and n.
    pub fn apparent_mass_array(
        &mut self,
    ) -> Option<([[f64; PARTNER_COMPONENTS]; PARTNER_COMPONENTS], usize)> {
        let m0 = *self.model.mount_motion()?;
        let base = self.reaction_now();
        let rot = S::moment_components(&m0.angular_velocity).len();
        let n = S::DIM + rot;
        // a unit change of acceleration component k
        let unit = |k: usize| {
            let mut m1 = m0;
            if k < S::DIM {
                m1.acceleration[k] += 1.0;
            } else {
                S::moment_components_mut(&mut m1.angular_acceleration)[k - S::DIM] += 1.0;
            }
            m1
        };
        let mut out = [[0.0; PARTNER_COMPONENTS]; PARTNER_COMPONENTS];
        self.model.set_matrix_aside(true);
        let (column, _, jumps) = &mut self.work;
        let solved = crate::integrator::input_jumps(
            &mut self.model,
            (&self.state, column),
            jumps,
            n,
            |model, k| model.set_mount(&unit(k)),
            |model, s, k| {
                let (f, mo) = model.reaction(&s.q, &s.v, &s.acc, &s.lambda);
                model.set_mount(&m0);
                for (r, x) in f.as_ref()[..S::DIM]
                    .iter()
                    .chain(S::moment_components(&mo))
                    .enumerate()
                {
                    out[r][k] = x - base[r];
                }
            },
        );
        // back at the current motion (a failed solve may leave a changed one)
        self.model.set_mount(&m0);
        self.model.set_matrix_aside(false);
        let factorizations = solved.ok()?;
        self.integ.counters_mut().factorizations += factorizations;
        Some((out, n))
    }

    /// The mass matrix at the mount of the rigid inertia in `outputs` (this state's,
    /// [`Simulator::outputs`]; [`MountInertia::mass_matrix`](crate::model::MountInertia::mass_matrix),
    /// ordered as [`Simulator::apparent_mass`]): the rigid reaction's partials by the mount
    /// accelerations, so the elastic part's are the apparent mass minus these. `None` for a
    /// fixed root.
    pub fn rigid_mass_matrix(&self, outputs: &Outputs<S>) -> Option<Vec<Vec<f64>>> {
        let m = self.model.mount_motion()?;
        Some(outputs.mount?.mass_matrix(&m.attitude))
    }

    /// [`Simulator::rigid_mass_matrix`] without allocating: the matrix in the upper left n × n
    /// of a partner-sized array (n = 3 planar, 6 spatial), and n.
    pub fn rigid_mass_array(
        &self,
        outputs: &Outputs<S>,
    ) -> Option<([[f64; PARTNER_COMPONENTS]; PARTNER_COMPONENTS], usize)> {
        let m = self.model.mount_motion()?;
        Some(outputs.mount?.mass_matrix_array(&m.attitude))
    }

    /// How the mount input set for the next step changes the accelerations now (the
    /// acceleration then the angular acceleration components, as checked and estimated by the
    /// next [`Simulator::advance`]): what the reaction's direct feedthrough multiplies. `None`
    /// without a pending input or when it would be refused.
    pub fn mount_acceleration_change(&self) -> Option<Vec<f64>> {
        let ms = self.mount.as_ref()?;
        let input = ms.checked(ms.pending?, self.state.t).ok()?;
        let now = ms.at(self.state.t);
        let (a, b) = (input.motion, now);
        let mut d: Vec<f64> = (0..S::DIM)
            .map(|k| a.acceleration[k] - b.acceleration[k])
            .collect();
        let (wa, wb) = (
            S::moment_components(&a.angular_acceleration),
            S::moment_components(&b.angular_acceleration),
        );
        d.extend(wa.iter().zip(wb).map(|(x, y)| x - y));
        Some(d)
    }

    /// The mount's motion now, as the state has it (`None` for a fixed root): the path's, with
    /// the partner model's deviation of the accelerations after a step with it.
    pub fn mount(&self) -> Option<Motion<S>> {
        self.mount.as_ref().map(|m| m.held(self.state.t))
    }

    /// Whether mount accelerations are inputs (else estimated from velocities).
    pub fn mount_accelerations_given(&self) -> Option<bool> {
        self.mount.as_ref().map(|m| m.accelerations_given)
    }

    /// Takes the pending mount input at the start of a communication step: refuses a jump,
    /// re-anchors a pose or velocity that differs from the prediction, and returns the motion
    /// whose accelerations differ from the ones the state holds (a jump of the inputs), if
    /// any. After a step with the partner model that is the path's (the host's) accelerations
    /// whether the host set them again or not ([`MountState::deviation`]): the same jump, so
    /// the two step alike, bit for bit.
    pub(super) fn take_mount_input(&mut self) -> Result<Option<Motion<S>>, SimError> {
        let t0 = self.state.t;
        let length = self.scene.total_length();
        let Some(ms) = &mut self.mount else {
            return Ok(None);
        };
        // the motion the state is consistent with; the step starts from the path (a failed
        // step returns to the deviation with the rest of the mount's state)
        let held = ms.held(t0);
        let deviated = std::mem::take(&mut ms.deviation) != [0.0; PARTNER_COMPONENTS];
        let Some(raw) = ms.pending.take() else {
            // input derivatives hold for one step: continue the path without them
            if ms.rates != MotionRates::default() {
                ms.base = ms.at(t0);
                ms.t0 = t0;
                ms.rates = MotionRates::default();
            }
            return Ok(deviated.then(|| ms.at(t0)));
        };
        let input = match ms.checked(raw, t0) {
            Ok(i) => i,
            Err(refusal) => {
                ms.pending = Some(raw);
                return Err(SimError::Refused { t: t0, refusal });
            }
        };
        let pred = ms.at(t0);
        let target = input.motion;
        let d2: f64 = (0..S::DIM)
            .map(|k| (target.position[k] - pred.position[k]).powi(2))
            .sum();
        let (distance, angle) = (
            d2.sqrt(),
            S::attitude_angle(&pred.attitude, &target.attitude),
        );
        if !(distance <= MAX_MOUNT_JUMP_LENGTH * length && angle <= MAX_MOUNT_JUMP_ANGLE) {
            ms.pending = Some(raw);
            return Err(SimError::Refused {
                t: t0,
                refusal: Refusal::MountJump { distance, angle },
            });
        }
        let mid = target.with_accelerations_of(&held);
        if mid != held {
            let s = &mut self.state;
            self.model.reanchor(
                &held,
                &mid,
                &mut s.q,
                &mut s.v,
                &mut [&mut s.acc, &mut s.aux],
            );
            self.model.set_mount(&mid);
        }
        ms.t0 = t0;
        ms.base = target;
        ms.rates = input.rates;
        ms.last = Some((t0, target));
        Ok((target != mid).then_some(target))
    }
}

impl<S: Space> MountInput<S> {
    /// The slot of one mount input component (`None`: not a mount input, or a component this
    /// space does not have).
    pub(super) fn slot(&mut self, id: InputId) -> Option<&mut f64> {
        let (m, k) = (&mut self.motion, id.component);
        match id.kind {
            InputKind::MountPosition => m.position.as_mut().get_mut(k),
            InputKind::MountAttitude => S::attitude_components_mut(&mut m.attitude).get_mut(k),
            InputKind::MountVelocity => m.velocity.as_mut().get_mut(k),
            InputKind::MountAngularVelocity => {
                S::moment_components_mut(&mut m.angular_velocity).get_mut(k)
            }
            InputKind::MountAcceleration => m.acceleration.as_mut().get_mut(k),
            InputKind::MountAngularAcceleration => {
                S::moment_components_mut(&mut m.angular_acceleration).get_mut(k)
            }
            _ => None,
        }
    }

    /// The slot of a derivative of order 1 or 2 of one mount input that defines the motion:
    /// the accelerations' (jerk, snap), or, when the scene's accelerations are not inputs
    /// (`velocity_mode`), the velocities' (acceleration, jerk). `None` for the pose and for
    /// derivatives implied by other inputs.
    pub(super) fn derivative_slot(
        &mut self,
        id: InputId,
        order: u32,
        velocity_mode: bool,
    ) -> Option<&mut f64> {
        let k = id.component;
        let (r, m) = (&mut self.rates, &mut self.motion);
        match (id.kind, order, velocity_mode) {
            (InputKind::MountAcceleration, 1, false) => r.jerk.as_mut().get_mut(k),
            (InputKind::MountAcceleration, 2, false) => r.snap.as_mut().get_mut(k),
            (InputKind::MountAngularAcceleration, 1, false) => {
                S::moment_components_mut(&mut r.angular_jerk).get_mut(k)
            }
            (InputKind::MountAngularAcceleration, 2, false) => {
                S::moment_components_mut(&mut r.angular_snap).get_mut(k)
            }
            (InputKind::MountVelocity, 1, true) => m.acceleration.as_mut().get_mut(k),
            (InputKind::MountVelocity, 2, true) => r.jerk.as_mut().get_mut(k),
            (InputKind::MountAngularVelocity, 1, true) => {
                S::moment_components_mut(&mut m.angular_acceleration).get_mut(k)
            }
            (InputKind::MountAngularVelocity, 2, true) => {
                S::moment_components_mut(&mut r.angular_jerk).get_mut(k)
            }
            _ => None,
        }
    }
}
