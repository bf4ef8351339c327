//! The vehicle side of the mounted-beam co-simulation example (issue 10): a pitch-plane car as
//! an FMI 2.0 co-simulation FMU on the generic `fmi2` layer (like `crates/fmi2-toy`).
//!
//! Model (resource `vehicle.toml`; x forward, y up, pitch θ nose-up positive, SI): a sprung
//! body (mass m, pitch inertia I about its centre of mass) on two suspensions (spring k, damper
//! c) at distances a (front) and b (rear) from the centre of mass, each on a wheel of mass m_w
//! with a linear tire spring k_t that never leaves the road. The car drives at constant speed V
//! (the drive absorbs every longitudinal force) over a one-period cosine bump h(x). States
//! y (body heave), θ, y_f, y_r (wheel heaves), all measured from the configuration with every
//! spring at free length (so gravity sags them), and their rates:
//!
//! ```text
//! F_f = k_f (y_f − y − aθ) + c_f (ẏ_f − ẏ − aθ̇)        suspension force on the body, front
//! F_r = k_r (y_r − y + bθ) + c_r (ẏ_r − ẏ + bθ̇)        rear
//! m ÿ  = F_f + F_r − m g + Q_y                           Q: generalized forces of the beam
//! I θ̈  = a F_f − b F_r + Q_θ
//! m_w ÿ_f = −F_f + k_t (h(x_f) − y_f) − m_w g           x_f = V t + a, x_r = V t − b
//! m_w ÿ_r = −F_r + k_t (h(x_r) − y_r) − m_w g
//! ```
//!
//! Small-angle suspension geometry; the mount point (body-frame offset s̄ from the centre of
//! mass) moves rigidly and exactly: r = R(θ) s̄, position (V t, h_cg + y) + r. The beam acts
//! through its reaction (inputs `beam.root.force.{x,y}`, `beam.root.moment.z`: the force and
//! moment of the support ON THE BEAM, as the beam FMU outputs them; the car takes their
//! negative at the mount point): Q_y = −F_y, Q_θ = (r × (−F))_z − M. Interface mass
//! (spatial.md §5.3): with the inputs `beam.root.mass`, `beam.root.center_of_mass.{x,y}`,
//! `beam.root.inertia.zz` (the beam FMU's rigid inertia at the mount) the body carries the beam
//! as a rigid payload, accelerated with it in one 2×2 mass matrix, and the reaction inputs are
//! then the part of the reaction the rigid payload does not account for (the host passes the
//! reaction minus the payload's own at the mount motion the beam was given). Integrated with
//! RK4 at a fixed internal step; the inputs are held over a communication step or follow the
//! host's input derivatives (orders 1, 2). The energy ledger (road work, beam work, damper
//! dissipation; and the drive's work on the beam, `energy.drive_work` = ∫ F_drive V dt with
//! F_drive the longitudinal force it adds for the beam: the reaction's x component as the car
//! was given it, plus the payload's inertia) is integrated with the state, so
//! E − E₀ = W_road + W_beam − D closes to the
//! integrator's accuracy (W_beam includes the payload's inertial and gravity forces). Not
//! modelled: tire lift-off, longitudinal dynamics.

pub mod package;

use serde::Deserialize;

use fmi2::hash::fnv1a64;
use fmi2::{Capabilities, Causality, CoSimModel, ModelInfo, StepError, Variability, Variable};

// the FMI 2.0 C entry points, only where the cdylib is built as an FMU binary (`--features
// export`, run.sh): two cars' exports in one test binary (the spatial car's tests compare it with
// the pitch-plane car) would be duplicate symbols
#[cfg(feature = "export")]
fmi2::export_fmi2!(Vehicle);

/// Solves `a x = b` (K×K) by Gaussian elimination with partial pivoting (the cars' static
/// states and mass matrices; the spatial car shares it).
pub fn solve<const K: usize>(mut a: [[f64; K]; K], mut b: [f64; K]) -> [f64; K] {
    for c in 0..K {
        let p = (c..K)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap_or(c);
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..K {
            let f = a[r][c] / a[c][c];
            for k in c..K {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; K];
    for r in (0..K).rev() {
        let s: f64 = (r + 1..K).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    x
}

/// Number of inputs (value references 1..=INPUTS).
const INPUTS: usize = 7;

/// Work cap of one communication step (internal steps).
const MAX_STEPS: f64 = 1e6;

/// The resource (`vehicle.toml`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Scene {
    model: SceneModel,
    experiment: Experiment,
    body: Body,
    suspension: Suspension,
    wheels: Wheels,
    road: Road,
    mount: Mount,
    solver: Solver,
}

/// A car resource's `[model]` table (the spatial car's too).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneModel {
    /// modelName of the FMU.
    pub name: String,
    /// Its description.
    #[serde(default)]
    pub description: String,
}

/// A car resource's `[experiment]` table: the FMU's DefaultExperiment [s].
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Experiment {
    /// Start time [s].
    pub start_time: f64,
    /// Stop time [s].
    pub stop_time: f64,
    /// Communication step [s].
    pub step_size: f64,
}

/// Sprung body.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Mass [kg].
    pub mass: f64,
    /// Pitch inertia about the centre of mass [kg m²].
    pub pitch_inertia: f64,
    /// Centre of mass above the road with unloaded springs [m].
    pub cg_height: f64,
    /// Centre of mass to front axle [m].
    pub front: f64,
    /// Centre of mass to rear axle [m].
    pub rear: f64,
}

/// Suspensions.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Suspension {
    /// [N/m].
    pub front_stiffness: f64,
    /// [N/m].
    pub rear_stiffness: f64,
    /// [N s/m].
    pub front_damping: f64,
    /// [N s/m].
    pub rear_damping: f64,
}

/// Wheels (each).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Wheels {
    /// [kg].
    pub mass: f64,
    /// [N/m].
    pub tire_stiffness: f64,
}

/// Road and speed.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Road {
    /// Constant forward speed [m/s].
    pub speed: f64,
    /// Start of the bump [m] (the centre of mass starts at x = 0).
    pub bump_start: f64,
    /// [m].
    pub bump_length: f64,
    /// [m].
    pub bump_height: f64,
}

/// Roof mount point.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mount {
    /// Body-frame offset from the centre of mass (forward, up) [m].
    pub position: [f64; 2],
}

/// Gravity and step.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Solver {
    /// [m/s²].
    pub gravity: f64,
    /// Fixed RK4 step [s].
    pub internal_step: f64,
    /// Start in static equilibrium under gravity and the beam reaction set before
    /// initialization (default: every spring at free length).
    #[serde(default)]
    pub static_start: bool,
}

/// The car's constant data.
#[derive(Debug, Clone, Copy)]
pub struct Car {
    /// Sprung body.
    pub body: Body,
    /// Suspensions.
    pub suspension: Suspension,
    /// Wheels.
    pub wheels: Wheels,
    /// Road and speed.
    pub road: Road,
    /// Mount point.
    pub mount: Mount,
    /// Gravity and step.
    pub solver: Solver,
}

/// A rigid payload at the mount (interface mass): mass [kg], centre of mass from the mount
/// point in the mount frame (x, y) [m], inertia about the mount point [kg m²]; the beam FMU's
/// `root.mass`, `root.center_of_mass.{x,y}`, `root.inertia.zz`. The body carries it as its own
/// (heave and pitch accelerate body and payload together); the beam reaction inputs then carry
/// only what the rigid payload does not account for (the beam's elastic part).
pub type Payload = [f64; 4];

/// State indices: y, θ, y_f, y_r, their rates, then the energy ledger.
const N: usize = 12;
const W_ROAD: usize = 8;
const W_BEAM: usize = 9;
const DISSIPATED: usize = 10;
const W_DRIVE: usize = 11;

impl Car {
    /// Road height h(x) [m] and slope dh/dx.
    pub fn road(&self, x: f64) -> (f64, f64) {
        let r = &self.road;
        let u = (x - r.bump_start) / r.bump_length;
        if !(0.0..=1.0).contains(&u) {
            return (0.0, 0.0);
        }
        let w = 2.0 * std::f64::consts::PI;
        (
            0.5 * r.bump_height * (1.0 - (w * u).cos()),
            0.5 * r.bump_height * w * (w * u).sin() / r.bump_length,
        )
    }

    /// Mount offset r = R(θ) s̄ [m] (world axes).
    pub fn offset(&self, theta: f64) -> [f64; 2] {
        let (s, c) = theta.sin_cos();
        let [x, y] = self.mount.position;
        [c * x - s * y, s * x + c * y]
    }

    /// Suspension forces on the body (front, rear) [N].
    fn suspension(&self, s: &[f64; N]) -> (f64, f64) {
        let (a, b, p) = (self.body.front, self.body.rear, &self.suspension);
        let ff = p.front_stiffness * (s[2] - s[0] - a * s[1])
            + p.front_damping * (s[6] - s[4] - a * s[5]);
        let fr =
            p.rear_stiffness * (s[3] - s[0] + b * s[1]) + p.rear_damping * (s[7] - s[4] + b * s[5]);
        (ff, fr)
    }

    /// Generalized forces (heave, pitch) of the beam reaction `f`, `m` (support on beam).
    pub fn beam_forces(&self, theta: f64, f: [f64; 2], m: f64) -> (f64, f64) {
        let r = self.offset(theta);
        // the car feels −f at the mount point and −m
        (-f[1], -(r[0] * f[1] - r[1] * f[0]) - m)
    }

    /// ds/dt at time `t` with the beam reaction `f`, `m` and the rigid payload `p` at the
    /// mount (see [`Payload`]; all zero: none).
    pub fn rate(&self, t: f64, s: &[f64; N], f: [f64; 2], m: f64, p: &Payload) -> [f64; N] {
        let (b, w, g) = (&self.body, &self.wheels, self.solver.gravity);
        let (ff, fr) = self.suspension(s);
        let (qy, qt) = self.beam_forces(s[1], f, m);
        let v = self.road.speed;
        let (hf, sf) = self.road(v * t + b.front);
        let (hr, sr) = self.road(v * t - b.rear);
        let (tf, tr) = (
            w.tire_stiffness * (hf - s[2]),
            w.tire_stiffness * (hr - s[3]),
        );
        let ps = &self.suspension;
        let dvf = s[6] - s[4] - b.front * s[5];
        let dvr = s[7] - s[4] + b.rear * s[5];
        let mut d = [0.0; N];
        d[..4].copy_from_slice(&s[4..8]);
        // the beam's generalized force on the body (heave, pitch)
        let (qby, qbt);
        // the longitudinal force the drive adds to hold V against the beam (and the payload)
        let mut drive = f[0];
        if *p == [0.0; 4] {
            d[4] = (ff + fr + qy) / b.mass - g;
            d[5] = (b.front * ff - b.rear * fr + qt) / b.pitch_inertia;
            (qby, qbt) = (qy, qt);
        } else {
            // body and payload accelerated together: (M + M_p) q̈ = Q + Q_p + Q_res, with the
            // payload's centre of mass at r_c = R(θ)(s̄ + c̄) from the body's, its Jacobian
            // (0, 1; −r_c.y, r_c.x), its centripetal acceleration −θ̇² r_c
            let [mp, cx, cy, io] = *p;
            let [rx, ry] = self.offset(s[1]);
            let (sn, cs) = s[1].sin_cos();
            let rc = [rx + cs * cx - sn * cy, ry + sn * cx + cs * cy];
            let ic = io - mp * (cx * cx + cy * cy);
            let mp_yt = mp * rc[0];
            let mp_tt = mp * (rc[0] * rc[0] + rc[1] * rc[1]) + ic;
            let (qpy, qpt) = (-mp * g + mp * s[5] * s[5] * rc[1], -mp * g * rc[0]);
            let a11 = b.mass + mp;
            let a22 = b.pitch_inertia + mp_tt;
            let r1 = ff + fr - b.mass * g + qpy + qy;
            let r2 = b.front * ff - b.rear * fr + qpt + qt;
            let det = a11 * a22 - mp_yt * mp_yt;
            d[4] = (a22 * r1 - mp_yt * r2) / det;
            d[5] = (a11 * r2 - mp_yt * r1) / det;
            qby = qy + qpy - mp * d[4] - mp_yt * d[5];
            qbt = qt + qpt - mp_yt * d[4] - mp_tt * d[5];
            // the payload's centre of mass accelerates along x by −θ̈ r_c.y − θ̇² r_c.x
            drive += mp * (-d[5] * rc[1] - s[5] * s[5] * rc[0]);
        }
        d[6] = (-ff + tf) / w.mass - g;
        d[7] = (-fr + tr) / w.mass - g;
        d[W_ROAD] = tf * sf * v + tr * sr * v;
        d[W_BEAM] = qby * s[4] + qbt * s[5];
        d[DISSIPATED] = ps.front_damping * dvf * dvf + ps.rear_damping * dvr * dvr;
        d[W_DRIVE] = drive * v;
        d
    }

    /// Mechanical energy of the car [J]: kinetic, springs and tires, gravity (heights from the
    /// free-length configuration).
    pub fn energy(&self, t: f64, s: &[f64; N]) -> f64 {
        let (b, w, p, g) = (
            &self.body,
            &self.wheels,
            &self.suspension,
            self.solver.gravity,
        );
        let v = self.road.speed;
        let kinetic = 0.5 * b.mass * s[4] * s[4]
            + 0.5 * b.pitch_inertia * s[5] * s[5]
            + 0.5 * w.mass * (s[6] * s[6] + s[7] * s[7]);
        let df = s[2] - s[0] - b.front * s[1];
        let dr = s[3] - s[0] + b.rear * s[1];
        let (hf, _) = self.road(v * t + b.front);
        let (hr, _) = self.road(v * t - b.rear);
        let springs = 0.5 * p.front_stiffness * df * df
            + 0.5 * p.rear_stiffness * dr * dr
            + 0.5 * w.tire_stiffness * ((hf - s[2]).powi(2) + (hr - s[3]).powi(2));
        kinetic + springs + g * (b.mass * s[0] + w.mass * (s[2] + s[3]))
    }

    /// The static equilibrium at `t` (velocities zero) under gravity, the beam reaction
    /// `f`, `m` and the payload `p`: Newton on the accelerations over the four positions (linear but for the
    /// mount's rotation of the beam moment arm), Jacobian by unit differences.
    pub fn static_state(&self, t: f64, f: [f64; 2], m: f64, p: &Payload) -> [f64; N] {
        let mut s = [0.0; N];
        for _ in 0..8 {
            let r = self.rate(t, &s, f, m, p);
            let res = [r[4], r[5], r[6], r[7]];
            if res.iter().all(|x| x.abs() < 1e-13) {
                break;
            }
            let mut jac = [[0.0; 4]; 4];
            for c in 0..4 {
                let mut sp = s;
                let h = 1e-6;
                sp[c] += h;
                let rp = self.rate(t, &sp, f, m, p);
                for (row, j) in jac.iter_mut().enumerate() {
                    j[c] = (rp[4 + row] - res[row]) / h;
                }
            }
            let dx = solve(jac, res.map(|x| -x));
            for k in 0..4 {
                s[k] += dx[k];
            }
        }
        s
    }

    /// One RK4 step of `dt` from `t` with the beam reaction and payload polynomials
    /// `input(τ)`.
    fn rk4(
        &self,
        t: f64,
        dt: f64,
        s: &[f64; N],
        input: impl Fn(f64) -> ([f64; 2], f64, Payload),
    ) -> [f64; N] {
        let at = |tau: f64, s: &[f64; N]| {
            let (f, m, p) = input(tau);
            self.rate(t + tau, s, f, m, &p)
        };
        let add = |s: &[f64; N], d: &[f64; N], h: f64| std::array::from_fn(|i| s[i] + h * d[i]);
        let k1 = at(0.0, s);
        let k2 = at(0.5 * dt, &add(s, &k1, 0.5 * dt));
        let k3 = at(0.5 * dt, &add(s, &k2, 0.5 * dt));
        let k4 = at(dt, &add(s, &k3, dt));
        std::array::from_fn(|i| s[i] + dt / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]))
    }
}

/// Value references (stable).
pub mod vr {
    /// Inputs: the beam's reaction (support on beam).
    pub const BEAM_FORCE_X: u32 = 1;
    /// .
    pub const BEAM_FORCE_Y: u32 = 2;
    /// .
    pub const BEAM_MOMENT_Z: u32 = 3;
    /// Inputs: the beam's rigid inertia at the mount (the payload, interface mass).
    pub const BEAM_MASS: u32 = 4;
    /// .
    pub const BEAM_COM_X: u32 = 5;
    /// .
    pub const BEAM_COM_Y: u32 = 6;
    /// .
    pub const BEAM_INERTIA: u32 = 7;
    /// Outputs: mount kinematics (world).
    pub const MOUNT_X: u32 = 10;
    /// .
    pub const MOUNT_Y: u32 = 11;
    /// .
    pub const MOUNT_ANGLE: u32 = 12;
    /// .
    pub const MOUNT_VX: u32 = 13;
    /// .
    pub const MOUNT_VY: u32 = 14;
    /// .
    pub const MOUNT_OMEGA: u32 = 15;
    /// .
    pub const MOUNT_AX: u32 = 16;
    /// .
    pub const MOUNT_AY: u32 = 17;
    /// .
    pub const MOUNT_ALPHA: u32 = 18;
    /// Body heave y [m].
    pub const HEAVE: u32 = 20;
    /// Body pitch θ [rad].
    pub const PITCH: u32 = 21;
    /// Energy ledger [J].
    pub const ENERGY: u32 = 22;
    /// .
    pub const W_ROAD: u32 = 23;
    /// .
    pub const W_BEAM: u32 = 24;
    /// .
    pub const DISSIPATED: u32 = 25;
    /// `energy.drive_work`
    pub const W_DRIVE: u32 = 26;
    /// Outputs: the mobility at the mount, `mount.mobility.<a>_<r>` at 30 + 3·i + j (i: ax,
    /// ay, alphaz; j: fx, fy, mz).
    pub const MOBILITY: u32 = 30;
    /// The last of them.
    pub const MOBILITY_LAST: u32 = 38;
    /// Outputs: the reaction inputs echoed, `mount.reaction_reference.{fx,fy,mz}` (40–42).
    pub const REACTION_REFERENCE: u32 = 40;
    /// The last of them.
    pub const REACTION_REFERENCE_LAST: u32 = 42;
}

/// The partner model's outputs of a car (`docs/coupling.md`): `mount.mobility.<a>_<r>` at
/// `mobility_vr` + n·i + j (the mount's acceleration `acc[i]` by the beam's reaction
/// `reaction[j]`, n = `acc.len()`, the first `dim` of each linear: 1/kg, 1/(kg.m), 1/(kg.m2)) and
/// `mount.reaction_reference.<r>` at `reference_vr` + j (the reaction inputs `reaction_inputs`
/// echoed, on which they depend directly). The names are the beam FMU's `root.mobility.*` and
/// `root.reaction_reference.*`.
pub fn partner_outputs(
    acc: &[&str],
    reaction: &[&str],
    dim: usize,
    (mobility_vr, reference_vr): (u32, u32),
    reaction_inputs: Vec<u32>,
) -> Vec<Variable> {
    let n = acc.len();
    let output = |name: String, vr, unit, description: String| Variable {
        name,
        vr,
        causality: Causality::Output,
        variability: Variability::Continuous,
        start: None,
        unit: Some(unit),
        description,
        depends_on: Vec::new(),
    };
    let mut out = Vec::new();
    for (i, a) in acc.iter().enumerate() {
        for (j, r) in reaction.iter().enumerate() {
            let unit = match (i < dim, j < dim) {
                (true, true) => "1/kg",
                (false, false) => "1/(kg.m2)",
                _ => "1/(kg.m)",
            };
            out.push(output(
                format!("mount.mobility.{a}_{r}"),
                mobility_vr + (n * i + j) as u32,
                unit,
                format!("Mobility at the mount (partner model): d{a}/d{r}, the mount acceleration by the beam's reaction input (with the payload), exact: the car is linear in the reaction"),
            ));
        }
    }
    for (j, r) in reaction.iter().enumerate() {
        out.push(Variable {
            depends_on: reaction_inputs.clone(),
            ..output(
                format!("mount.reaction_reference.{r}"),
                reference_vr + j as u32,
                if j < dim { "N" } else { "N.m" },
                "The beam reaction input the mount accelerations were computed with (partner model: the beam's root.reaction_reference)".into(),
            )
        });
    }
    out
}

/// The car as an FMU model.
#[derive(Debug, Clone)]
pub struct Vehicle {
    scene_hash: u64,
    info: ModelInfo,
    vars: Vec<Variable>,
    /// Constant data.
    pub car: Car,
    t: f64,
    s: [f64; N],
    /// Inputs (beam reaction x, y, z-moment, then the payload, [`Payload`]; indexed by
    /// value reference − 1) and their first two time derivatives over the next step.
    inputs: [[f64; INPUTS]; 3],
    /// Not yet initialized, with `static_start`: the state follows the inputs' static
    /// equilibrium.
    settling: bool,
}

fn variables() -> Vec<Variable> {
    use Causality::*;
    let v = |name: &str, vr, causality, unit: &'static str, description: &str| Variable {
        name: name.into(),
        vr,
        causality,
        variability: Variability::Continuous,
        start: (causality == Input).then_some(0.0),
        unit: Some(unit),
        description: description.into(),
        depends_on: Vec::new(),
    };
    let beam: Vec<u32> = (vr::BEAM_FORCE_X..=vr::BEAM_INERTIA).collect();
    // accelerations depend at once on the forces applied now
    let acc = |name: &str, vr, unit, description: &str| Variable {
        depends_on: beam.clone(),
        ..v(name, vr, Output, unit, description)
    };
    let mut out = vec![
        v("beam.root.force.x", vr::BEAM_FORCE_X, Input, "N", "Force of the mount on the beam, x (the beam FMU's root.force.x); the car feels its negative"),
        v("beam.root.force.y", vr::BEAM_FORCE_Y, Input, "N", "Force of the mount on the beam, y (root.force.y); the car feels its negative"),
        v("beam.root.moment.z", vr::BEAM_MOMENT_Z, Input, "N.m", "Moment of the mount on the beam about the mount point (root.moment.z); the car feels its negative"),
        v("beam.root.mass", vr::BEAM_MASS, Input, "kg", "Interface mass: the beam's mass (root.mass), carried by the body as a rigid payload at the mount; then beam.root.force/moment must be the reaction beyond the payload's (root.force_elastic, root.moment_elastic). 0: no payload"),
        v("beam.root.center_of_mass.x", vr::BEAM_COM_X, Input, "m", "Payload centre of mass from the mount point, mount frame x (root.center_of_mass.x)"),
        v("beam.root.center_of_mass.y", vr::BEAM_COM_Y, Input, "m", "Payload centre of mass, mount frame y (root.center_of_mass.y)"),
        v("beam.root.inertia.zz", vr::BEAM_INERTIA, Input, "kg.m2", "Payload inertia about the mount point (root.inertia.zz)"),
        v("mount.position.x", vr::MOUNT_X, Output, "m", "Roof mount point, x (world)"),
        v("mount.position.y", vr::MOUNT_Y, Output, "m", "Roof mount point, y (world)"),
        v("mount.angle", vr::MOUNT_ANGLE, Output, "rad", "Mount frame angle = body pitch (nose up positive)"),
        v("mount.velocity.x", vr::MOUNT_VX, Output, "m/s", "Mount point velocity, x"),
        v("mount.velocity.y", vr::MOUNT_VY, Output, "m/s", "Mount point velocity, y"),
        v("mount.angular_velocity", vr::MOUNT_OMEGA, Output, "rad/s", "Pitch rate"),
        acc("mount.acceleration.x", vr::MOUNT_AX, "m/s2", "Mount point acceleration, x"),
        acc("mount.acceleration.y", vr::MOUNT_AY, "m/s2", "Mount point acceleration, y"),
        acc("mount.angular_acceleration", vr::MOUNT_ALPHA, "rad/s2", "Pitch acceleration"),
        v("body.heave", vr::HEAVE, Output, "m", "Body centre-of-mass heave from the free-length configuration"),
        v("body.pitch", vr::PITCH, Output, "rad", "Body pitch"),
        v("energy.total", vr::ENERGY, Output, "J", "Kinetic + spring + tire + gravity energy of the car"),
        v("energy.road_work", vr::W_ROAD, Output, "J", "Work done by the road on the tires since the start"),
        v("energy.beam_work", vr::W_BEAM, Output, "J", "Work done by the beam on the car (heave and pitch) since the start"),
        v("energy.dissipated", vr::DISSIPATED, Output, "J", "Energy dissipated in the dampers since the start"),
        v("energy.drive_work", vr::W_DRIVE, Output, "J", "Work done by the drive, which holds the forward speed, against the beam's longitudinal reaction (and the payload's inertia) since the start: energy the drive puts into the beam"),
    ];
    out.extend(partner_outputs(
        &["ax", "ay", "alphaz"],
        &["fx", "fy", "mz"],
        2,
        (vr::MOBILITY, vr::REACTION_REFERENCE),
        (vr::BEAM_FORCE_X..=vr::BEAM_MOMENT_Z).collect(),
    ));
    out
}

impl Vehicle {
    /// The mobility at the mount now: ∂(a_x, a_y, α)/∂(F_x, F_y, M_z) of the beam's reaction
    /// input (rows, columns; with the payload). The car is linear in the reaction, so a unit
    /// change of it gives the partial exactly (up to rounding).
    pub fn mobility(&self) -> [[f64; 3]; 3] {
        let (f, m, _) = self.input_at(0.0);
        let u = [f[0], f[1], m];
        let base = self.mount_under(u);
        let mut g = [[0.0; 3]; 3];
        for j in 0..3 {
            let mut uj = u;
            uj[j] += 1.0;
            let a = self.mount_under(uj);
            for i in 0..3 {
                g[i][j] = a[6 + i] - base[6 + i];
            }
        }
        g
    }

    /// Inputs at `tau` into the current step: beam reaction (force, moment), payload.
    fn input_at(&self, tau: f64) -> ([f64; 2], f64, Payload) {
        let [u, d1, d2] = &self.inputs;
        let at = |k: usize| u[k] + d1[k] * tau + 0.5 * d2[k] * tau * tau;
        ([at(0), at(1)], at(2), [at(3), at(4), at(5), at(6)])
    }

    /// Mount kinematics now: position, angle, velocity, angular velocity, acceleration,
    /// angular acceleration (world).
    pub fn mount(&self) -> [f64; 9] {
        let (f, m, _) = self.input_at(0.0);
        self.mount_under([f[0], f[1], m])
    }

    /// [`Vehicle::mount`] with the beam reaction `u` (force x, y, moment z) in place of the
    /// inputs' (the payload the inputs').
    fn mount_under(&self, u: [f64; 3]) -> [f64; 9] {
        let (c, s) = (&self.car, &self.s);
        let (_, _, p) = self.input_at(0.0);
        let d = c.rate(self.t, s, [u[0], u[1]], u[2], &p);
        let r = c.offset(s[1]);
        let (w, al) = (s[5], d[5]);
        [
            c.road.speed * self.t + r[0],
            c.body.cg_height + s[0] + r[1],
            s[1],
            c.road.speed - w * r[1],
            s[4] + w * r[0],
            w,
            -al * r[1] - w * w * r[0],
            d[4] + al * r[0] - w * w * r[1],
            al,
        ]
    }
}

impl Vehicle {
    /// The car's OSP-IS port groups (`<modelName>_OspModelDescription.xml`: file name and
    /// text): the mirror of the beam FMU's mount groups (its outputs where the beam has
    /// inputs), with the same names and order: position, angle, the linear port (the beam's
    /// reaction `beam.root.force.*` as Force, the mount velocity), the angular port, the
    /// accelerations. A `<VariableGroupConnection>` per group joins the two
    /// (OspSystemStructure.xml).
    pub fn osp_model_description(&self) -> Result<(String, String), String> {
        let text = fmi2::osp::model_description(&Self::osp_groups(), &self.vars)?;
        Ok((
            format!("{}_OspModelDescription.xml", self.info.model_name),
            text,
        ))
    }

    /// The groups of [`Vehicle::osp_model_description`].
    pub fn osp_groups() -> Vec<fmi2::osp::VariableGroup> {
        use fmi2::osp::VariableGroup as G;
        vec![
            G::of(
                "LinearDisplacement",
                "mount.position",
                &["mount.position.x", "mount.position.y"],
            ),
            G::of("AngularDisplacement", "mount.angle", &["mount.angle"]),
            G::nest(
                "LinearMechanicalPort",
                "mount.linear",
                vec![
                    G::of(
                        "Force",
                        "mount.force",
                        &["beam.root.force.x", "beam.root.force.y"],
                    ),
                    G::of(
                        "LinearVelocity",
                        "mount.velocity",
                        &["mount.velocity.x", "mount.velocity.y"],
                    ),
                ],
            ),
            G::nest(
                "AngularMechanicalPort",
                "mount.angular",
                vec![
                    G::of("Torque", "mount.moment", &["beam.root.moment.z"]),
                    G::of(
                        "AngularVelocity",
                        "mount.angular_velocity",
                        &["mount.angular_velocity"],
                    ),
                ],
            ),
            G::of(
                "Generic",
                "mount.acceleration",
                &["mount.acceleration.x", "mount.acceleration.y"],
            ),
            G::of(
                "Generic",
                "mount.angular_acceleration",
                &["mount.angular_acceleration"],
            ),
        ]
    }
}

impl CoSimModel for Vehicle {
    const RESOURCE: &'static str = "vehicle.toml";
    const GUID_NAMESPACE: &'static str = "hybeam-vehicle";
    const BUILD_ID: &'static str = concat!("hybeam-vehicle/", env!("CARGO_PKG_VERSION"));
    const GENERATION_TOOL: &'static str = "hybeam fmi2 layer";
    const STATE_MAGIC: [u8; 8] = *b"HYBCAR01";

    fn from_resource(text: &str) -> Result<Self, String> {
        let scene: Scene = toml::from_str(text).map_err(|e| format!("vehicle.toml: {e}"))?;
        let car = Car {
            body: scene.body,
            suspension: scene.suspension,
            wheels: scene.wheels,
            road: scene.road,
            mount: scene.mount,
            solver: scene.solver,
        };
        let positive = [
            ("body.mass", car.body.mass),
            ("body.pitch_inertia", car.body.pitch_inertia),
            ("body.front", car.body.front),
            ("body.rear", car.body.rear),
            ("wheels.mass", car.wheels.mass),
            ("wheels.tire_stiffness", car.wheels.tire_stiffness),
            ("road.bump_length", car.road.bump_length),
            ("solver.internal_step", car.solver.internal_step),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("{name} = {v}: must be finite and > 0"));
            }
        }
        let e = &scene.experiment;
        Ok(Self {
            scene_hash: fnv1a64(text.as_bytes()),
            info: ModelInfo {
                model_name: scene.model.name,
                description: scene.model.description,
                start_time: e.start_time,
                stop_time: e.stop_time,
                step_size: e.step_size,
                capabilities: Capabilities {
                    input_derivative_order: 2,
                    output_derivative_order: 0,
                    directional_derivative: true,
                },
            },
            vars: variables(),
            car,
            t: 0.0,
            s: if car.solver.static_start {
                car.static_state(0.0, [0.0; 2], 0.0, &[0.0; 4])
            } else {
                [0.0; N]
            },
            inputs: [[0.0; INPUTS]; 3],
            settling: car.solver.static_start,
        })
    }

    fn model_info(&self) -> ModelInfo {
        self.info.clone()
    }

    fn variables(&self) -> &[Variable] {
        &self.vars
    }

    fn get_real(&self, index: usize) -> Result<f64, String> {
        let r = self.vars[index].vr;
        let m = self.mount();
        Ok(match r {
            vr::BEAM_FORCE_X..=vr::BEAM_INERTIA => self.inputs[0][(r - vr::BEAM_FORCE_X) as usize],
            vr::MOUNT_X..=vr::MOUNT_ALPHA => m[(r - vr::MOUNT_X) as usize],
            vr::HEAVE => self.s[0],
            vr::PITCH => self.s[1],
            vr::ENERGY => self.car.energy(self.t, &self.s),
            vr::W_ROAD => self.s[W_ROAD],
            vr::W_BEAM => self.s[W_BEAM],
            vr::DISSIPATED => self.s[DISSIPATED],
            vr::W_DRIVE => self.s[W_DRIVE],
            vr::MOBILITY..=vr::MOBILITY_LAST => {
                let k = (r - vr::MOBILITY) as usize;
                self.mobility()[k / 3][k % 3]
            }
            vr::REACTION_REFERENCE..=vr::REACTION_REFERENCE_LAST => {
                self.inputs[0][(r - vr::REACTION_REFERENCE) as usize]
            }
            _ => return Err(format!("value reference {r} is not a variable of the car")),
        })
    }

    fn set_real(&mut self, index: usize, value: f64) -> Result<(), String> {
        let r = self.vars[index].vr;
        match r {
            vr::BEAM_MASS | vr::BEAM_INERTIA if value < 0.0 => Err(format!(
                "{} = {value}: a payload's mass and inertia must be >= 0",
                self.vars[index].name
            )),
            vr::BEAM_FORCE_X..=vr::BEAM_INERTIA if value.is_finite() => {
                let k = (r - vr::BEAM_FORCE_X) as usize;
                self.inputs[0][k] = value;
                self.inputs[1][k] = 0.0;
                self.inputs[2][k] = 0.0;
                if self.settling {
                    // before initialization the outputs are those of the static start under
                    // the inputs set so far (a host may read them to place the beam)
                    let (f, m, p) = self.input_at(0.0);
                    self.s = self.car.static_state(self.t, f, m, &p);
                }
                Ok(())
            }
            _ => Err(format!("value reference {r} cannot be set to {value}")),
        }
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        self.t = start_time;
        self.s = [0.0; N];
        if self.car.solver.static_start {
            let (f, m, p) = self.input_at(0.0);
            self.s = self.car.static_state(start_time, f, m, &p);
        }
        self.settling = false;
        Ok(())
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), StepError> {
        let [mp, cx, cy, io] = self.input_at(0.0).2;
        if io < mp * (cx * cx + cy * cy) * (1.0 - 1e-12) {
            return Err(StepError::Discard(format!(
                "payload inertia about the mount {io} kg m2 < mass x distance^2 = {} kg m2: not a rigid body",
                mp * (cx * cx + cy * cy)
            )));
        }
        let n = (h / self.car.solver.internal_step - 1e-9).ceil().max(1.0);
        if n > MAX_STEPS {
            return Err(StepError::Discard(format!(
                "h = {h} s needs {n:e} internal steps, more than {MAX_STEPS:e}: split the communication step"
            )));
        }
        let dt = h / n;
        let mut s = self.s;
        for k in 0..n as u64 {
            let t0 = k as f64 * dt;
            s = self.car.rk4(t + t0, dt, &s, |tau| self.input_at(t0 + tau));
        }
        if s.iter().any(|x| !x.is_finite()) {
            return Err(StepError::Discard("the state became non-finite".into()));
        }
        self.s = s;
        self.t = t + h;
        self.inputs[1] = [0.0; INPUTS];
        self.inputs[2] = [0.0; INPUTS];
        Ok(())
    }

    fn reset(&mut self) -> Result<(), String> {
        self.t = 0.0;
        self.inputs = [[0.0; INPUTS]; 3];
        self.settling = self.car.solver.static_start;
        self.s = if self.settling {
            self.car.static_state(0.0, [0.0; 2], 0.0, &[0.0; 4])
        } else {
            [0.0; N]
        };
        Ok(())
    }

    fn save_state(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(8 * (2 + N + 3 * INPUTS));
        b.extend_from_slice(&self.scene_hash.to_le_bytes());
        let all = std::iter::once(self.t)
            .chain(self.s)
            .chain(self.inputs.iter().flatten().copied());
        for x in all {
            b.extend_from_slice(&x.to_le_bytes());
        }
        b
    }

    fn load_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        if bytes.len() != 8 * (2 + N + 3 * INPUTS) {
            return Err(format!("not a car state ({} bytes)", bytes.len()));
        }
        let word = |i: usize| u64::from_le_bytes(bytes[8 * i..8 * i + 8].try_into().unwrap());
        if word(0) != self.scene_hash {
            return Err("the state belongs to another vehicle.toml".into());
        }
        let f: Vec<f64> = (1..2 + N + 3 * INPUTS)
            .map(|i| f64::from_bits(word(i)))
            .collect();
        if f.iter().any(|x| !x.is_finite()) {
            return Err("the state holds non-finite values".into());
        }
        self.t = f[0];
        self.s.copy_from_slice(&f[1..1 + N]);
        for (k, row) in self.inputs.iter_mut().enumerate() {
            row.copy_from_slice(&f[1 + N + INPUTS * k..1 + N + INPUTS * (k + 1)]);
        }
        self.settling = false;
        Ok(())
    }

    /// ∂(mount acceleration, angular acceleration)/∂(inputs): by the reaction, the car's
    /// mobility ([`Vehicle::mobility`], exact up to rounding); the payload enters nonlinearly, its partials are central differences (relative step 1e-6).
    fn partial_derivative(&mut self, output: usize, input: usize) -> Result<f64, String> {
        let (o, i) = (self.vars[output].vr, self.vars[input].vr);
        if (vr::REACTION_REFERENCE..=vr::REACTION_REFERENCE_LAST).contains(&o) {
            // the echo of the reaction inputs
            return Ok(f64::from(u8::from(
                o - vr::REACTION_REFERENCE == i - vr::BEAM_FORCE_X,
            )));
        }
        if !(vr::MOUNT_AX..=vr::MOUNT_ALPHA).contains(&o)
            || !(vr::BEAM_FORCE_X..=vr::BEAM_INERTIA).contains(&i)
        {
            return Ok(0.0);
        }
        let row = (o - vr::MOUNT_X) as usize;
        let k = (i - vr::BEAM_FORCE_X) as usize;
        if i <= vr::BEAM_MOMENT_Z {
            return Ok(self.mobility()[row - 6][k]);
        }
        let kept = self.inputs[0][k];
        let mut at = |x: f64| {
            self.inputs[0][k] = x;
            let a = self.mount()[row];
            self.inputs[0][k] = kept;
            a
        };
        let d = 1e-6 * kept.abs().max(1.0);
        Ok((at(kept + d) - at(kept - d)) / (2.0 * d))
    }

    fn set_input_derivative(&mut self, index: usize, order: u32, value: f64) -> Result<(), String> {
        let r = self.vars[index].vr;
        match (r, order) {
            (vr::BEAM_FORCE_X..=vr::BEAM_INERTIA, 1 | 2) => {
                self.inputs[order as usize][(r - vr::BEAM_FORCE_X) as usize] = value;
                Ok(())
            }
            _ => Err(format!(
                "value reference {r} has no input derivative of order {order}"
            )),
        }
    }
}
