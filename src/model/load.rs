//! Dead loads at a port (the tip force and moment). A point force F: generalized force
//! −(∂p/∂q)ᵀF and stiffness
//! −F·∂²p/∂q∂q on the port's local coordinates; a moment m: −m·∂θ/∂q (its stiffness comes from
//! the port, [`super::Port::add_moment_stiffness`]). Dimension-free.

use super::space::{dot, moment_dot, PortKin, Space};

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

/// Residual contribution of a dead moment `m` at a port: `r_k = −m·∂θ/∂q_k` on each of the `d`
/// local coordinates (see [`PortKin::rotation_jacobian`]).
pub fn moment_residual<S: Space>(kin: &S::PortKin, m: &S::Moment, r: &mut [f64]) {
    for (k, rk) in r.iter_mut().enumerate() {
        *rk = -moment_dot::<S>(m, &kin.rotation_jacobian(k));
    }
}
