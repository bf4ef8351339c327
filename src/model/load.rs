//! A dead point force at a port (the tip force): generalized force −(∂p/∂q)ᵀF and stiffness
//! −F·∂²p/∂q∂q on the port's local coordinates. Dimension-free.

use super::space::{dot, PortKin, Space};

/// Residual contribution `r_k = −(∂p/∂q_k)·F` on each of the `d` local coordinates.
pub fn point_force_residual<S: Space>(kin: &S::PortKin, force: &S::Vec, r: &mut [f64]) {
    for (k, rk) in r.iter_mut().enumerate() {
        *rk = -dot::<S>(&kin.jacobian(k), force);
    }
}

/// Stiffness `∂r/∂q = −F·∂²p/∂q∂q` through `add(i, j, value)` (local indices).
pub fn point_force_stiffness<S: Space>(
    kin: &S::PortKin,
    force: &S::Vec,
    add: impl FnMut(usize, usize, f64),
) {
    let mut mu = *force;
    for x in mu.as_mut() {
        *x = -*x;
    }
    kin.add_point_hessian(&mu, add);
}
