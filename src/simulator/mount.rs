//! The mount's motion in time, as the simulator drives it: a path from the last communication
//! point (the host's pose, velocities and accelerations there, and the accelerations' rates of
//! change if the host gives input derivatives), the input set for the next step, and the
//! estimate of the accelerations from velocity inputs (`motion_input = "pose_velocity"`).

use super::SpaceModel;
use crate::error::Refusal;
use crate::model::{Motion, MotionRates};
use crate::scene::{MotionInput, Mount, Scene};
use serde::{Deserialize, Serialize};

/// One mount input from a host: the motion at the current time and, optionally, the rates of
/// change of its accelerations.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct MountInput<S: SpaceModel> {
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
pub struct MountState<S: SpaceModel> {
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
}

impl<S: SpaceModel> MountState<S> {
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
        })
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

    /// A host input checked and normalized (finite, a defined orientation), with estimated
    /// accelerations when it gives none.
    pub fn checked(&self, input: MountInput<S>, t: f64) -> Result<MountInput<S>, Refusal> {
        let mut input = input;
        let m = &mut input.motion;
        let finite = m.components().iter().all(|x| x.is_finite())
            && S::attitude_components(&m.attitude)
                .iter()
                .all(|x| x.is_finite());
        if !finite {
            return Err(Refusal::MountInput(
                "a mount position, orientation, velocity or acceleration input is not finite"
                    .into(),
            ));
        }
        m.attitude = S::normalized_attitude(&m.attitude).ok_or_else(|| {
            Refusal::MountInput(
                "root.orientation is the zero quaternion: give unit Euler parameters (identity: e0 = 1, e1 = e2 = e3 = 0)".into(),
            )
        })?;
        if !input.accelerations {
            // backward difference of the velocity inputs (previous input, else the path)
            let (tp, prev) = self.last.unwrap_or((self.t0, self.base));
            let dt = t - tp;
            if dt > 0.0 {
                for k in 0..S::DIM {
                    m.acceleration[k] = (m.velocity[k] - prev.velocity[k]) / dt;
                }
                let (w, wp) = (
                    S::moment_components(&m.angular_velocity).to_vec(),
                    S::moment_components(&prev.angular_velocity).to_vec(),
                );
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
fn motion_of<S: SpaceModel>(m: &Mount) -> Motion<S> {
    let mut out = Motion::<S>::default();
    let vec = |v: &[f64]| {
        let mut x = S::Vec::default();
        for (k, c) in v.iter().enumerate().take(S::DIM) {
            x[k] = *c;
        }
        x
    };
    let mom = |v: &[f64]| {
        let mut x = S::Moment::default();
        for (o, c) in S::moment_components_mut(&mut x).iter_mut().zip(v) {
            *o = *c;
        }
        x
    };
    out.position = vec(&m.position);
    out.velocity = vec(&m.velocity);
    out.acceleration = vec(&m.acceleration);
    out.angular_velocity = mom(&m.angular_velocity);
    out.angular_acceleration = mom(&m.angular_acceleration);
    out.attitude = S::attitude_from(m);
    out
}
