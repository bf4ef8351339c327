//! The error control's step size (`solver.error_tolerance`): the step proposed after an
//! accepted step and the step retried after a rejected one, from the error estimate in units
//! of the tolerance. An elementary (integral) controller, Hairer, Nørsett & Wanner, *Solving
//! ODEs I*, §II.4, eq. (4.13), with RADAU5's band that keeps a step (and its factorized
//! Newton matrix) when it would grow only a little; the constants are in
//! [`super::parameters`].

use super::{STEP_GROWTH_MAX, STEP_KEEP_BAND, STEP_SAFETY, STEP_SHRINK_MIN};

/// err^(−1/4) (the embedded solution's local error goes as h⁴) with the safety factor: the
/// factor on the step that would bring the estimate to (0.9⁴ ≈ 0.66) × the tolerance. Square
/// roots are correctly rounded in IEEE 754: the same bits on every platform.
fn factor(err: f64) -> f64 {
    STEP_SAFETY / err.sqrt().sqrt()
}

/// The proposal after an accepted step of size `h` with error estimate `err` (≤ 1), taken
/// under the proposal `proposed` (h ≤ `proposed`: the steps of a communication step divide
/// what is left of it equally), `after_rejection` if the attempt before it was rejected, the
/// steps bounded by `h_max`. Growth is bounded relative to the proposal, not to a step the
/// communication point shortened; a proposal at most [`STEP_KEEP_BAND`] above the current
/// one keeps it.
pub fn after_accepted(h: f64, err: f64, proposed: f64, after_rejection: bool, h_max: f64) -> f64 {
    let most = if after_rejection {
        proposed
    } else {
        STEP_GROWTH_MAX * proposed
    };
    let next = (h * factor(err))
        .max(STEP_SHRINK_MIN * h)
        .min(most)
        .min(h_max);
    if next >= proposed && next <= STEP_KEEP_BAND * proposed {
        proposed
    } else {
        next
    }
}

/// The step retried after a rejected step of size `h`: by the error estimate `err` (> 1; at
/// least [`STEP_SHRINK_MIN`] × h), or halved when the step failed otherwise (`None`: Newton
/// did not converge, a singular matrix; or a non-finite estimate), as the fixed step halves.
pub fn after_rejected(h: f64, err: Option<f64>) -> f64 {
    match err {
        Some(e) if !e.is_nan() => h * factor(e).clamp(STEP_SHRINK_MIN, STEP_SAFETY),
        _ => 0.5 * h,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On err ∝ h⁴ the proposal lands where the estimate is 0.9⁴ of the tolerance; growth and
    /// shrinking are bounded; the band keeps the step.
    #[test]
    fn proposals_follow_the_fourth_root() {
        let h = 1e-3;
        // err = 1/16: twice the step would reach 1; with the safety, 1.8
        let next = after_accepted(h, 1.0 / 16.0, h, false, 1.0);
        assert!((next / h - 1.8).abs() < 1e-12, "{next}");
        // err = 0: bounded growth, and never above h_max
        assert_eq!(after_accepted(h, 0.0, h, false, 1.0), 2.0 * h);
        assert_eq!(after_accepted(h, 0.0, h, false, 1.5e-3), 1.5e-3);
        // right after a rejection: no growth
        assert_eq!(after_accepted(h, 0.0, h, true, 1.0), h);
        // within the band: the same step, bit for bit
        assert_eq!(after_accepted(h, 0.5, h, false, 1.0), h);
        // a step shortened to a communication point: growth bounded by the proposal
        assert_eq!(after_accepted(1e-5, 0.0, h, false, 1.0), 2.0 * h);
        // an estimate near 1 shrinks a little
        let next = after_accepted(h, 1.0, h, false, 1.0);
        assert!((next / h - 0.9).abs() < 1e-12, "{next}");
        // rejections: by the estimate, at least 0.2 of the step; halved on a failure
        let retry = after_rejected(h, Some(16.0));
        assert!((retry / h - 0.45).abs() < 1e-12, "{retry}");
        assert_eq!(after_rejected(h, Some(1e6)), 0.2 * h);
        assert_eq!(after_rejected(h, Some(f64::INFINITY)), 0.2 * h);
        let retry = after_rejected(h, Some(1.0 + 1e-9));
        assert!((retry / h - 0.9).abs() < 1e-8, "{retry}");
        assert_eq!(after_rejected(h, None), 0.5 * h);
        assert_eq!(after_rejected(h, Some(f64::NAN)), 0.5 * h);
    }
}
