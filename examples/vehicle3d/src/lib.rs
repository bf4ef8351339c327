//! The vehicle side of the spatial mounted-beam co-simulation example: a car with heave, pitch
//! and roll on four wheels as an FMI 2.0 co-simulation FMU on the generic `fmi2` layer, the
//! spatial counterpart of the pitch-plane car `hybeam-vehicle` (`examples/vehicle`).
//!
//! Axes (ISO 8855 vehicle axes, SI): world x forward, y left, z up, gravity along −z. The body
//! rotation is R = R_y(θ) R_x(φ) (body frame → world): pitch θ about y, **positive nose down**
//! (ISO), then roll φ about the pitched x axis, positive left side up / right side down. The
//! pitch-plane car's pitch (nose up positive) is −θ. Resource `vehicle3d.toml`.
//!
//! Model: a sprung body (mass m, pitch inertia I_y, roll inertia I_x about its centre of mass)
//! on four suspensions (spring k, damper c per wheel; front pair at x = a, rear pair at x = −b,
//! left at y = +w/2, right at y = −w/2), each on a wheel of mass m_w with a linear tire spring
//! k_t that never leaves the road. The car drives at constant speed V (the drive absorbs every
//! longitudinal force, and nothing holds y or yaw: no lateral loads reach them) over a
//! one-period cosine bump h(x) under its left wheels (`[road] sides = "left"`) or across the
//! road (`"both"`: the pitch-plane car's road). States z (body heave), θ, φ, z_i (wheel heaves,
//! i = fl, fr, rl, rr), all from the configuration with every spring at free length (so gravity
//! sags them), their rates, and the energy ledger. Small-angle suspension geometry and body
//! inertia, as in the planar car (corner i at body (x_i, y_i) moves by z − x_i θ + y_i φ):
//!
//! ```text
//! P_i = k_i (z_i − z + x_i θ − y_i φ) + c_i (ż_i − ż + x_i θ̇ − y_i φ̇)   suspension on body
//! m z̈   = Σ P_i − m g + Q_z                         Q: generalized forces of the beam
//! I_y θ̈ = −Σ x_i P_i + Q_θ
//! I_x φ̈ =  Σ y_i P_i + Q_φ
//! m_w z̈_i = −P_i + k_t (h(V t + x_i) − z_i) − m_w g   (h = 0 under the right wheels if "left")
//! ```
//!
//! The mount point (body-frame offset s̄ = [forward, left, up] from the centre of mass) and the
//! mount frame (= the body frame) move exactly: position (V t, 0, h_cg + z) + r, r = R s̄;
//! angular velocity ω = θ̇ e_y + φ̇ u with u = R_y(θ) e_x (world axes); angular acceleration
//! α = θ̈ e_y + φ̈ u + θ̇ φ̇ (e_y × u); velocity (V, 0, ż) + ω × r; acceleration
//! (0, 0, z̈) + α × r + ω × (ω × r). The beam acts through its reaction (inputs
//! `beam.root.force.{x,y,z}`, `beam.root.moment.{x,y,z}`: the force F and moment M of the
//! support ON THE BEAM about the mount point, world axes, as the spatial beam FMU outputs
//! them); the car takes −F at the mount point and −M: by virtual work
//! Q_z = −F_z, Q_θ = −e_y·(r × F + M), Q_φ = −u·(r × F + M) (F_x's moment included; its
//! force goes to the drive). Interface mass (spatial.md §5.3): with the inputs
//! `beam.root.mass`, `beam.root.center_of_mass.{x,y,z}`, `beam.root.inertia.{xx,…,yz}` (the
//! beam FMU's rigid inertia at the mount, mount frame, tensor about the mount point) the body
//! carries the beam as a rigid payload, accelerated with it in one 3×3 mass matrix (the
//! payload's reaction F = m (a + α × c + ω × (ω × c) − g), M = I α + ω × I ω + m c × (a − g),
//! exact, `model/inertia.rs` of the engine); the reaction inputs are then the part the payload
//! does not account for (the beam FMU's `root.force_elastic.*`, `root.moment_elastic.*`).
//! Integrated with RK4 at a fixed internal step; the inputs are held over a communication step
//! or follow the host's input derivatives (orders 1, 2). The energy ledger (road work, beam
//! work, damper dissipation; and the drive's work on the beam, `energy.drive_work` =
//! ∫ F_drive V dt with F_drive the longitudinal force it adds for the beam: the reaction's x
//! component F_x as the car was given it, plus, with a payload, the payload's inertia force
//! m_p a_c,x) is integrated with the state, so E − E₀ = W_road + W_beam − D
//! closes to the integrator's accuracy (W_beam includes the payload's inertial and gravity
//! forces). Not modelled: tire lift-off, longitudinal, lateral and yaw dynamics, the body's
//! gyroscopic terms (its kinetic energy is ½ m ż² + ½ I_y θ̇² + ½ I_x φ̇², small-angle).

use serde::Deserialize;

use hybeam_vehicle::{solve, Experiment, SceneModel};

use fmi2::hash::fnv1a64;
use fmi2::{Capabilities, Causality, CoSimModel, ModelInfo, StepError, Variability, Variable};

// the FMI 2.0 C entry points, only where the cdylib is built as an FMU binary (`--features
// export`, run.sh): two cars' exports in one test binary (the spatial car's tests compare it with
// the pitch-plane car) would be duplicate symbols
#[cfg(feature = "export")]
fmi2::export_fmi2!(Vehicle3d);

/// A 3-vector [m, m/s, N, …].
pub type V3 = [f64; 3];

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(k: f64, a: V3) -> V3 {
    [k * a[0], k * a[1], k * a[2]]
}

fn mat_vec(m: &[V3; 3], v: V3) -> V3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

/// Number of inputs (value references 1..=INPUTS).
const INPUTS: usize = 16;

/// Work cap of one communication step (internal steps).
const MAX_STEPS: f64 = 1e6;

/// The resource (`vehicle3d.toml`).
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

/// Sprung body.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Mass [kg].
    pub mass: f64,
    /// Pitch inertia about the centre of mass, body y [kg m²].
    pub pitch_inertia: f64,
    /// Roll inertia about the centre of mass, body x [kg m²].
    pub roll_inertia: f64,
    /// Centre of mass above the road with unloaded springs [m].
    pub cg_height: f64,
    /// Centre of mass to front axle [m].
    pub front: f64,
    /// Centre of mass to rear axle [m].
    pub rear: f64,
    /// Track width, left to right wheel (the centre of mass midway) [m].
    pub track: f64,
}

/// Suspensions, per wheel.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Suspension {
    /// Each front wheel [N/m].
    pub front_stiffness: f64,
    /// Each rear wheel [N/m].
    pub rear_stiffness: f64,
    /// Each front wheel [N s/m].
    pub front_damping: f64,
    /// Each rear wheel [N s/m].
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

/// Which wheels the bump lies under.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Sides {
    /// Under the left wheels only (the right ones run on a flat road).
    Left,
    /// Across the road (the pitch-plane car's road).
    #[default]
    Both,
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
    /// Which wheels cross the bump (default "both").
    #[serde(default)]
    pub sides: Sides,
}

/// Roof mount point.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mount {
    /// Body-frame offset s̄ from the centre of mass (forward, left, up) [m].
    pub position: V3,
}

/// Gravity and step.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Solver {
    /// [m/s²], along −z.
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

/// A rigid payload at the mount (interface mass), the beam FMU's `root.mass`,
/// `root.center_of_mass.{x,y,z}`, `root.inertia.{xx,yy,zz,xy,xz,yz}`: mass [kg], centre of
/// mass from the mount point in the mount frame [m], inertia tensor about the mount point in
/// the mount frame [kg m²] (tensor entries: I_xy = −∫xy dm). All zero: none.
pub type Payload = [f64; 10];

/// State layout: z, θ, φ, z_fl, z_fr, z_rl, z_rr, their rates, then the energy ledger (road,
/// beam, dissipated, drive).
pub const N: usize = 18;
/// Positions (z, θ, φ, four wheel heaves).
const NQ: usize = 7;
const W_ROAD: usize = 14;
const W_BEAM: usize = 15;
const DISSIPATED: usize = 16;
const W_DRIVE: usize = 17;

/// The body's exact kinematics at a state: the rotation, the mount arm and the maps from the
/// body's (z̈, θ̈, φ̈) to the mount's acceleration and angular acceleration (world axes).
#[derive(Debug, Clone, Copy)]
pub struct Kinematics {
    /// R = R_y(θ) R_x(φ), rows (body frame → world).
    pub rot: [V3; 3],
    /// Mount arm r = R s̄ from the centre of mass [m].
    pub r: V3,
    /// Angular velocity ω = θ̇ e_y + φ̇ u [rad/s].
    pub omega: V3,
    /// ∂(mount point velocity)/∂(ż, θ̇, φ̇): e_z, e_y × r, u × r.
    pub jac: [V3; 3],
    /// ∂ω/∂(ż, θ̇, φ̇): 0, e_y, u = R_y(θ) e_x.
    pub ang: [V3; 3],
    /// Mount acceleration at zero body acceleration: α₀ × r + ω × (ω × r) [m/s²].
    pub bias_a: V3,
    /// Angular acceleration at zero body acceleration: θ̇ φ̇ (e_y × u) [rad/s²].
    pub bias_alpha: V3,
}

impl Kinematics {
    /// Mount acceleration and angular acceleration (world) at body accelerations `qdd`.
    pub fn accelerations(&self, qdd: V3) -> (V3, V3) {
        let mut a = self.bias_a;
        let mut al = self.bias_alpha;
        for k in 0..3 {
            a = add(a, scale(qdd[k], self.jac[k]));
            al = add(al, scale(qdd[k], self.ang[k]));
        }
        (a, al)
    }

    /// Generalized forces (heave, pitch, roll) on the car of a reaction `f`, `m` of the support
    /// on a body at the mount (about the mount point, world axes): the car feels −f, −m.
    pub fn generalized(&self, f: V3, m: V3) -> V3 {
        std::array::from_fn(|k| -(dot(self.jac[k], f) + dot(self.ang[k], m)))
    }
}

/// Euler parameters (scalar first, frame → world) of R = R_y(θ) R_x(φ): the product of the
/// quaternions (cos θ/2, 0, sin θ/2, 0) and (cos φ/2, sin φ/2, 0, 0).
pub fn euler_parameters(theta: f64, phi: f64) -> [f64; 4] {
    let (st, ct) = (0.5 * theta).sin_cos();
    let (sp, cp) = (0.5 * phi).sin_cos();
    [ct * cp, ct * sp, st * cp, -st * sp]
}

/// R = R_y(θ) R_x(φ) (body frame → world), rows.
pub fn rotation(theta: f64, phi: f64) -> [V3; 3] {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    [
        [ct, st * sp, st * cp],
        [0.0, cp, -sp],
        [-st, ct * sp, ct * cp],
    ]
}

/// A symmetric tensor [xx, yy, zz, xy, xz, yz] as rows.
fn tensor(i: &[f64]) -> [V3; 3] {
    [[i[0], i[3], i[4]], [i[3], i[1], i[5]], [i[4], i[5], i[2]]]
}

/// R T Rᵀ.
fn rotate_tensor(r: &[V3; 3], t: &[V3; 3]) -> [V3; 3] {
    let rt: [V3; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| dot(r[i], [t[0][j], t[1][j], t[2][j]])));
    std::array::from_fn(|i| std::array::from_fn(|j| dot(rt[i], r[j])))
}

impl Car {
    /// Road height h(x) [m] and slope dh/dx (the pitch-plane car's bump, copied: the example
    /// crates are separate).
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

    /// Corner `i` (0 fl, 1 fr, 2 rl, 3 rr): body position (x_i, y_i) [m], spring [N/m] and
    /// damper [N s/m].
    pub fn corner(&self, i: usize) -> (f64, f64, f64, f64) {
        let (b, s) = (&self.body, &self.suspension);
        let y = if i.is_multiple_of(2) { 0.5 } else { -0.5 } * b.track;
        if i < 2 {
            (b.front, y, s.front_stiffness, s.front_damping)
        } else {
            (-b.rear, y, s.rear_stiffness, s.rear_damping)
        }
    }

    /// Road height and slope under corner `i` at time `t`.
    fn road_at(&self, i: usize, t: f64) -> (f64, f64) {
        if self.road.sides == Sides::Left && i % 2 == 1 {
            return (0.0, 0.0);
        }
        self.road(self.road.speed * t + self.corner(i).0)
    }

    /// The body's exact kinematics at state `s`.
    pub fn kinematics(&self, s: &[f64; N]) -> Kinematics {
        let (theta, phi) = (s[1], s[2]);
        let (td, pd) = (s[NQ + 1], s[NQ + 2]);
        let rot = rotation(theta, phi);
        let r = mat_vec(&rot, self.mount.position);
        let ey = [0.0, 1.0, 0.0];
        let u = [theta.cos(), 0.0, -theta.sin()];
        let omega = add(scale(td, ey), scale(pd, u));
        let bias_alpha = scale(td * pd, cross(ey, u));
        Kinematics {
            rot,
            r,
            omega,
            jac: [[0.0, 0.0, 1.0], cross(ey, r), cross(u, r)],
            ang: [[0.0; 3], ey, u],
            bias_a: add(cross(bias_alpha, r), cross(omega, cross(omega, r))),
            bias_alpha,
        }
    }

    /// Suspension forces on the body P_i [N] (upward) and damper deflection rates [m/s].
    fn suspension(&self, s: &[f64; N]) -> ([f64; 4], [f64; 4]) {
        let mut p = [0.0; 4];
        let mut dv = [0.0; 4];
        for i in 0..4 {
            let (x, y, k, c) = self.corner(i);
            let d = s[3 + i] - s[0] + x * s[1] - y * s[2];
            dv[i] = s[NQ + 3 + i] - s[NQ] + x * s[NQ + 1] - y * s[NQ + 2];
            p[i] = k * d + c * dv[i];
        }
        (p, dv)
    }

    /// Tire loads k_t (h_i − z_i) [N], road on wheel, upward (fl, fr, rl, rr) at `t`.
    pub fn tire_loads(&self, t: f64, s: &[f64; N]) -> [f64; 4] {
        std::array::from_fn(|i| self.wheels.tire_stiffness * (self.road_at(i, t).0 - s[3 + i]))
    }

    /// Whether `p` carries anything.
    fn has_payload(p: &Payload) -> bool {
        p[0] != 0.0 || p[4..].iter().any(|x| *x != 0.0)
    }

    /// The reaction (support on the payload, world axes, moment about the mount point) of the
    /// rigid payload `p` moving with the mount at acceleration `a`, angular acceleration `al`.
    fn payload_reaction(&self, k: &Kinematics, p: &Payload, a: V3, al: V3) -> (V3, V3) {
        let m = p[0];
        let c = mat_vec(&k.rot, [p[1], p[2], p[3]]);
        let iw = rotate_tensor(&k.rot, &tensor(&p[4..]));
        let ag = add(a, [0.0, 0.0, self.solver.gravity]);
        let w = k.omega;
        let f = scale(m, add(ag, add(cross(al, c), cross(w, cross(w, c)))));
        let mo = add(
            add(mat_vec(&iw, al), cross(w, mat_vec(&iw, w))),
            scale(m, cross(c, ag)),
        );
        (f, mo)
    }

    /// The body's mass matrix in (z, θ, φ) with the payload `p`, and the payload's generalized
    /// force at zero body acceleration (the reaction is affine in the accelerations: columns
    /// exact by unit accelerations).
    fn mass_matrix(&self, k: &Kinematics, p: &Payload) -> ([V3; 3], V3) {
        let b = &self.body;
        let mut mm = [
            [b.mass, 0.0, 0.0],
            [0.0, b.pitch_inertia, 0.0],
            [0.0, 0.0, b.roll_inertia],
        ];
        if !Self::has_payload(p) {
            return (mm, [0.0; 3]);
        }
        let q0 = {
            let (f, m) = self.payload_reaction(k, p, k.bias_a, k.bias_alpha);
            k.generalized(f, m)
        };
        for col in 0..3 {
            let mut e = [0.0; 3];
            e[col] = 1.0;
            let (a, al) = k.accelerations(e);
            let (f, m) = self.payload_reaction(k, p, a, al);
            let q = k.generalized(f, m);
            for row in 0..3 {
                mm[row][col] += q0[row] - q[row];
            }
        }
        (mm, q0)
    }

    /// The body's accelerations (z̈, θ̈, φ̈) at `s` with the beam reaction `f`, `m` and the
    /// payload `p`, the beam's generalized force on the body (reaction and payload), and the
    /// longitudinal force the drive adds for the beam (F_x plus the payload's x inertia force
    /// m_p a_c,x: the x component of its reaction, gravity having none).
    fn body_accelerations(
        &self,
        k: &Kinematics,
        s: &[f64; N],
        f: V3,
        m: V3,
        p: &Payload,
    ) -> (V3, V3, f64) {
        let b = &self.body;
        let (ps, _) = self.suspension(s);
        let mut qs = [-b.mass * self.solver.gravity, 0.0, 0.0];
        for (i, pi) in ps.iter().enumerate() {
            let (x, y, _, _) = self.corner(i);
            qs[0] += pi;
            qs[1] -= x * pi;
            qs[2] += y * pi;
        }
        let qr = k.generalized(f, m);
        if !Self::has_payload(p) {
            let qdd = [
                (qs[0] + qr[0]) / b.mass,
                (qs[1] + qr[1]) / b.pitch_inertia,
                (qs[2] + qr[2]) / b.roll_inertia,
            ];
            return (qdd, qr, f[0]);
        }
        let (mm, q0) = self.mass_matrix(k, p);
        let qdd = solve(mm, std::array::from_fn(|i| qs[i] + qr[i] + q0[i]));
        let (a, al) = k.accelerations(qdd);
        let (fp, mp) = self.payload_reaction(k, p, a, al);
        (qdd, add(qr, k.generalized(fp, mp)), f[0] + fp[0])
    }

    /// ds/dt at time `t` with the beam reaction `f`, `m` (support on beam, world axes, moment
    /// about the mount point) and the rigid payload `p` at the mount ([`Payload`]).
    pub fn rate(&self, t: f64, s: &[f64; N], f: V3, m: V3, p: &Payload) -> [f64; N] {
        let (w, g, v) = (&self.wheels, self.solver.gravity, self.road.speed);
        let k = self.kinematics(s);
        let (ps, dv) = self.suspension(s);
        let (qdd, qb, drive) = self.body_accelerations(&k, s, f, m, p);
        let mut d = [0.0; N];
        d[..NQ].copy_from_slice(&s[NQ..2 * NQ]);
        d[NQ..NQ + 3].copy_from_slice(&qdd);
        for i in 0..4 {
            let (h, slope) = self.road_at(i, t);
            let tire = w.tire_stiffness * (h - s[3 + i]);
            d[NQ + 3 + i] = (-ps[i] + tire) / w.mass - g;
            d[W_ROAD] += tire * slope * v;
            d[DISSIPATED] += self.corner(i).3 * dv[i] * dv[i];
        }
        d[W_BEAM] = (0..3).map(|j| qb[j] * s[NQ + j]).sum();
        d[W_DRIVE] = drive * v;
        d
    }

    /// Mechanical energy of the car [J]: kinetic, springs and tires, gravity (heights from the
    /// free-length configuration).
    pub fn energy(&self, t: f64, s: &[f64; N]) -> f64 {
        let (b, w, g) = (&self.body, &self.wheels, self.solver.gravity);
        let mut e = 0.5 * b.mass * s[NQ] * s[NQ]
            + 0.5 * b.pitch_inertia * s[NQ + 1] * s[NQ + 1]
            + 0.5 * b.roll_inertia * s[NQ + 2] * s[NQ + 2]
            + g * b.mass * s[0];
        for i in 0..4 {
            let (x, y, k, _) = self.corner(i);
            let d = s[3 + i] - s[0] + x * s[1] - y * s[2];
            let tire = self.road_at(i, t).0 - s[3 + i];
            e += 0.5 * w.mass * s[NQ + 3 + i] * s[NQ + 3 + i]
                + 0.5 * k * d * d
                + 0.5 * w.tire_stiffness * tire * tire
                + g * w.mass * s[3 + i];
        }
        e
    }

    /// The static equilibrium at `t` (velocities zero) under gravity, the beam reaction `f`,
    /// `m` and the payload `p`: Newton on the accelerations over the seven positions (linear
    /// but for the rotation of the mount arm), Jacobian by unit differences. The positions are
    /// stepped in a left/right basis (heave, pitch, axle mean heaves; then roll, axle half
    /// differences), so a mirror-symmetric car and load stays exactly symmetric (roll 0).
    pub fn static_state(&self, t: f64, f: V3, m: V3, p: &Payload) -> [f64; N] {
        // basis of position changes (columns) and the matching residual combinations (rows)
        const BASIS: [[f64; NQ]; NQ] = [
            [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0],
            [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0],
        ];
        let residual = |s: &[f64; N]| -> [f64; NQ] {
            let r = self.rate(t, s, f, m, p);
            std::array::from_fn(|row| (0..NQ).map(|k| BASIS[row][k] * r[NQ + k]).sum())
        };
        let mut s = [0.0; N];
        for _ in 0..12 {
            let res = residual(&s);
            if res.iter().all(|x| x.abs() < 1e-13) {
                break;
            }
            let mut jac = [[0.0; NQ]; NQ];
            for c in 0..NQ {
                let h = 1e-6;
                let sp =
                    std::array::from_fn(|k| if k < NQ { s[k] + h * BASIS[c][k] } else { s[k] });
                let rp = residual(&sp);
                for (row, j) in jac.iter_mut().enumerate() {
                    j[c] = (rp[row] - res[row]) / h;
                }
            }
            let dx = solve(jac, res.map(|x| -x));
            for k in 0..NQ {
                s[k] += (0..NQ).map(|c| dx[c] * BASIS[c][k]).sum::<f64>();
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
        input: impl Fn(f64) -> (V3, V3, Payload),
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
    /// Inputs 1–6: the beam's reaction (support on beam, world axes, moment about the mount
    /// point): force x, y, z (1, 2, 3), moment x, y, z (4, 5, 6).
    pub const BEAM_FORCE_X: u32 = 1;
    /// .
    pub const BEAM_FORCE_Y: u32 = 2;
    /// .
    pub const BEAM_FORCE_Z: u32 = 3;
    /// .
    pub const BEAM_MOMENT_X: u32 = 4;
    /// .
    pub const BEAM_MOMENT_Y: u32 = 5;
    /// .
    pub const BEAM_MOMENT_Z: u32 = 6;
    /// Inputs 7–16: the beam's rigid inertia at the mount (the payload, interface mass, mount
    /// frame): mass (7), centre of mass x, y, z (8–10), inertia xx, yy, zz, xy, xz, yz (11–16).
    pub const BEAM_MASS: u32 = 7;
    /// .
    pub const BEAM_COM_X: u32 = 8;
    /// .
    pub const BEAM_INERTIA_XX: u32 = 11;
    /// .
    pub const BEAM_INERTIA_YZ: u32 = 16;
    /// Outputs 20–38 (world axes): mount position x, y, z (20–22), Euler parameters e0–e3
    /// (23–26), velocity (27–29), angular velocity (30–32), acceleration (33–35), angular
    /// acceleration (36–38).
    pub const MOUNT_X: u32 = 20;
    /// .
    pub const MOUNT_E0: u32 = 23;
    /// .
    pub const MOUNT_VX: u32 = 27;
    /// .
    pub const MOUNT_WX: u32 = 30;
    /// .
    pub const MOUNT_AX: u32 = 33;
    /// .
    pub const MOUNT_ALPHA_X: u32 = 36;
    /// .
    pub const MOUNT_ALPHA_Z: u32 = 38;
    /// Body heave z [m].
    pub const HEAVE: u32 = 40;
    /// Body pitch θ [rad] (nose down positive).
    pub const PITCH: u32 = 41;
    /// Body roll φ [rad] (left side up positive).
    pub const ROLL: u32 = 42;
    /// Energy ledger [J].
    pub const ENERGY: u32 = 43;
    /// .
    pub const W_ROAD: u32 = 44;
    /// .
    pub const W_BEAM: u32 = 45;
    /// .
    pub const DISSIPATED: u32 = 46;
    /// `energy.drive_work`
    pub const W_DRIVE: u32 = 47;
    /// Outputs: the mobility at the mount, `mount.mobility.<a>_<r>` at 50 + 6·i + j (i: ax,
    /// ay, az, alphax, alphay, alphaz; j: fx, fy, fz, mx, my, mz).
    pub const MOBILITY: u32 = 50;
    /// The last of them.
    pub const MOBILITY_LAST: u32 = 85;
    /// Outputs: the reaction inputs echoed, `mount.reaction_reference.<r>` (90–95).
    pub const REACTION_REFERENCE: u32 = 90;
    /// The last of them.
    pub const REACTION_REFERENCE_LAST: u32 = 95;
}

/// The car as an FMU model.
#[derive(Debug, Clone)]
pub struct Vehicle3d {
    scene_hash: u64,
    info: ModelInfo,
    vars: Vec<Variable>,
    /// Constant data.
    pub car: Car,
    t: f64,
    s: [f64; N],
    /// Inputs (beam reaction force, moment, then the payload, [`Payload`]; indexed by value
    /// reference − 1) and their first two time derivatives over the next step.
    inputs: [[f64; INPUTS]; 3],
    /// Not yet initialized, with `static_start`: the state follows the inputs' static
    /// equilibrium.
    settling: bool,
}

const XYZ: [&str; 3] = ["x", "y", "z"];
const TENSOR: [&str; 6] = ["xx", "yy", "zz", "xy", "xz", "yz"];

fn variables() -> Vec<Variable> {
    use Causality::*;
    let v = |name: String, vr, causality, unit: &'static str, description: String| Variable {
        name,
        vr,
        causality,
        variability: Variability::Continuous,
        start: (causality == Input).then_some(0.0),
        unit: Some(unit),
        description,
        depends_on: Vec::new(),
    };
    let beam: Vec<u32> = (1..=INPUTS as u32).collect();
    let mut out = Vec::new();
    for (k, a) in XYZ.iter().enumerate() {
        out.push(v(format!("beam.root.force.{a}"), vr::BEAM_FORCE_X + k as u32, Input, "N",
            format!("Force of the mount on the beam, world {a} (the beam FMU's root.force.{a}); the car feels its negative at the mount point")));
    }
    for (k, a) in XYZ.iter().enumerate() {
        out.push(v(format!("beam.root.moment.{a}"), vr::BEAM_MOMENT_X + k as u32, Input, "N.m",
            format!("Moment of the mount on the beam about the mount point, world {a} (root.moment.{a}); the car feels its negative")));
    }
    out.push(v("beam.root.mass".into(), vr::BEAM_MASS, Input, "kg",
        "Interface mass: the beam's mass (root.mass), carried by the body as a rigid payload at the mount; then beam.root.force/moment must be the reaction beyond the payload's (root.force_elastic, root.moment_elastic). 0: no payload".into()));
    for (k, a) in XYZ.iter().enumerate() {
        out.push(v(format!("beam.root.center_of_mass.{a}"), vr::BEAM_COM_X + k as u32, Input, "m",
            format!("Payload centre of mass from the mount point, mount frame {a} (root.center_of_mass.{a})")));
    }
    for (k, a) in TENSOR.iter().enumerate() {
        out.push(v(format!("beam.root.inertia.{a}"), vr::BEAM_INERTIA_XX + k as u32, Input, "kg.m2",
            format!("Payload inertia tensor about the mount point, mount frame {a} (root.inertia.{a}; off-diagonal entries are tensor entries, −∫{a} dm)")));
    }
    for (k, a) in XYZ.iter().enumerate() {
        out.push(v(
            format!("mount.position.{a}"),
            vr::MOUNT_X + k as u32,
            Output,
            "m",
            format!("Roof mount point, world {a}"),
        ));
    }
    for k in 0..4 {
        // dimensionless, no unit (like the beam FMU's root.orientation.*)
        out.push(Variable { unit: None, ..v(format!("mount.orientation.e{k}"), vr::MOUNT_E0 + k as u32, Output, "",
            format!("Euler parameter e{k} (scalar first) of the mount frame = body frame -> world, R = R_y(pitch) R_x(roll)")) });
    }
    for (k, a) in XYZ.iter().enumerate() {
        out.push(v(
            format!("mount.velocity.{a}"),
            vr::MOUNT_VX + k as u32,
            Output,
            "m/s",
            format!("Mount point velocity, world {a}"),
        ));
    }
    for (k, a) in XYZ.iter().enumerate() {
        out.push(v(
            format!("mount.angular_velocity.{a}"),
            vr::MOUNT_WX + k as u32,
            Output,
            "rad/s",
            format!("Angular velocity of the mount frame, world {a}"),
        ));
    }
    // accelerations depend at once on the forces applied now
    for (k, a) in XYZ.iter().enumerate() {
        out.push(Variable {
            depends_on: beam.clone(),
            ..v(
                format!("mount.acceleration.{a}"),
                vr::MOUNT_AX + k as u32,
                Output,
                "m/s2",
                format!("Mount point acceleration, world {a}"),
            )
        });
    }
    for (k, a) in XYZ.iter().enumerate() {
        out.push(Variable {
            depends_on: beam.clone(),
            ..v(
                format!("mount.angular_acceleration.{a}"),
                vr::MOUNT_ALPHA_X + k as u32,
                Output,
                "rad/s2",
                format!("Angular acceleration of the mount frame, world {a}"),
            )
        });
    }
    out.extend([
        v("body.heave".into(), vr::HEAVE, Output, "m", "Body centre-of-mass heave from the free-length configuration, up".into()),
        v("body.pitch".into(), vr::PITCH, Output, "rad", "Body pitch about y, nose down positive (ISO 8855; the pitch-plane car's pitch is its negative)".into()),
        v("body.roll".into(), vr::ROLL, Output, "rad", "Body roll about x, left side up positive".into()),
        v("energy.total".into(), vr::ENERGY, Output, "J", "Kinetic + spring + tire + gravity energy of the car".into()),
        v("energy.road_work".into(), vr::W_ROAD, Output, "J", "Work done by the road on the tires since the start".into()),
        v("energy.beam_work".into(), vr::W_BEAM, Output, "J", "Work done by the beam on the car (heave, pitch, roll) since the start".into()),
        v("energy.dissipated".into(), vr::DISSIPATED, Output, "J", "Energy dissipated in the dampers since the start".into()),
        v("energy.drive_work".into(), vr::W_DRIVE, Output, "J", "Work done by the drive, which holds the forward speed, against the beam's longitudinal reaction (and the payload's inertia) since the start: energy the drive puts into the beam".into()),
    ]);
    out.extend(hybeam_vehicle::partner_outputs(
        &["ax", "ay", "az", "alphax", "alphay", "alphaz"],
        &["fx", "fy", "fz", "mx", "my", "mz"],
        3,
        (vr::MOBILITY, vr::REACTION_REFERENCE),
        (vr::BEAM_FORCE_X..=vr::BEAM_MOMENT_Z).collect(),
    ));
    out
}

impl Vehicle3d {
    /// Inputs at `tau` into the current step: beam reaction (force, moment), payload.
    fn input_at(&self, tau: f64) -> (V3, V3, Payload) {
        let [u, d1, d2] = &self.inputs;
        let at = |k: usize| u[k] + d1[k] * tau + 0.5 * d2[k] * tau * tau;
        (
            std::array::from_fn(at),
            std::array::from_fn(|k| at(3 + k)),
            std::array::from_fn(|k| at(6 + k)),
        )
    }

    /// The state (see the module doc for the layout) and the time.
    pub fn state(&self) -> (f64, [f64; N]) {
        (self.t, self.s)
    }

    /// Mount kinematics now (world axes): position (3), Euler parameters (4), velocity (3),
    /// angular velocity (3), acceleration (3), angular acceleration (3).
    pub fn mount(&self) -> [f64; 19] {
        let (c, s) = (&self.car, &self.s);
        let (f, m, p) = self.input_at(0.0);
        let k = c.kinematics(s);
        let (qdd, _, _) = c.body_accelerations(&k, s, f, m, &p);
        let (a, al) = k.accelerations(qdd);
        let pos = add([c.road.speed * self.t, 0.0, c.body.cg_height + s[0]], k.r);
        let vel = add([c.road.speed, 0.0, s[NQ]], cross(k.omega, k.r));
        let e = euler_parameters(s[1], s[2]);
        let mut out = [0.0; 19];
        out[..3].copy_from_slice(&pos);
        out[3..7].copy_from_slice(&e);
        out[7..10].copy_from_slice(&vel);
        out[10..13].copy_from_slice(&k.omega);
        out[13..16].copy_from_slice(&a);
        out[16..].copy_from_slice(&al);
        out
    }

    /// The car's mobility at the mount now: ∂(a, α)/∂(F, M) (rows a x, y, z, α x, y, z;
    /// columns the reaction inputs F x, y, z, M x, y, z), exact: −[J; Ω] M⁻¹ [J; Ω]ᵀ with the
    /// body's (and payload's) mass matrix M.
    pub fn mobility(&self) -> [[f64; 6]; 6] {
        let k = self.car.kinematics(&self.s);
        let (mm, _) = self.car.mass_matrix(&k, &self.input_at(0.0).2);
        let mut out = [[0.0; 6]; 6];
        for col in 0..6 {
            let mut f = [0.0; 3];
            let mut m = [0.0; 3];
            if col < 3 {
                f[col] = 1.0;
            } else {
                m[col - 3] = 1.0;
            }
            let dq = solve(mm, k.generalized(f, m));
            let mut da = [0.0; 3];
            let mut dal = [0.0; 3];
            for j in 0..3 {
                da = add(da, scale(dq[j], k.jac[j]));
                dal = add(dal, scale(dq[j], k.ang[j]));
            }
            for row in 0..3 {
                out[row][col] = da[row];
                out[3 + row][col] = dal[row];
            }
        }
        out
    }

    /// The payload input now, checked for a rigid body (inertia about the centre of mass
    /// positive semi-definite).
    fn check_payload(&self) -> Result<(), String> {
        let p = self.input_at(0.0).2;
        let (m, c) = (p[0], [p[1], p[2], p[3]]);
        let io = tensor(&p[4..]);
        // about the centre of mass: I_o − m (|c|² 1 − c cᵀ)
        let ic: [V3; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                io[i][j] - m * (if i == j { dot(c, c) } else { 0.0 } - c[i] * c[j])
            })
        });
        // principal minors of orders 1, 2, 3 >= 0, to rounding relative to the trace
        let tr = (io[0][0] + io[1][1] + io[2][2]).abs();
        let minors = [
            (ic[0][0], 1),
            (ic[1][1], 1),
            (ic[2][2], 1),
            (ic[0][0] * ic[1][1] - ic[0][1] * ic[0][1], 2),
            (ic[0][0] * ic[2][2] - ic[0][2] * ic[0][2], 2),
            (ic[1][1] * ic[2][2] - ic[1][2] * ic[1][2], 2),
            (dot(ic[0], cross(ic[1], ic[2])), 3),
        ];
        if minors.iter().any(|&(x, n)| x < -1e-12 * tr.powi(n)) {
            return Err(format!(
                "payload inertia about its centre of mass {ic:?} kg m2 (beam.root.inertia.* minus m (|c|² 1 − c cᵀ)) is not positive semi-definite: not a rigid body"
            ));
        }
        Ok(())
    }
}

impl Vehicle3d {
    /// The car's OSP-IS port groups (`<modelName>_OspModelDescription.xml`: file name and
    /// text): the mirror of the spatial beam FMU's mount groups (its outputs where the beam
    /// has inputs), with the same names and order: position, orientation, the linear port
    /// (the beam's reaction `beam.root.force.*` as Force, the mount velocity), the angular
    /// port, the accelerations.
    pub fn osp_model_description(&self) -> Result<(String, String), String> {
        let text = fmi2::osp::model_description(&Self::osp_groups(), &self.vars)?;
        Ok((
            format!("{}_OspModelDescription.xml", self.info.model_name),
            text,
        ))
    }

    /// The groups of [`Vehicle3d::osp_model_description`].
    pub fn osp_groups() -> Vec<fmi2::osp::VariableGroup> {
        use fmi2::osp::VariableGroup as G;
        let names =
            |stem: &str| -> Vec<String> { XYZ.iter().map(|a| format!("{stem}.{a}")).collect() };
        let of = |kind, name: &str, stem: &str| {
            let n = names(stem);
            G::of(
                kind,
                name,
                &n.iter().map(String::as_str).collect::<Vec<_>>(),
            )
        };
        vec![
            of("LinearDisplacement", "mount.position", "mount.position"),
            G::of(
                "Generic",
                "mount.orientation",
                &[
                    "mount.orientation.e0",
                    "mount.orientation.e1",
                    "mount.orientation.e2",
                    "mount.orientation.e3",
                ],
            ),
            G::nest(
                "LinearMechanicalPort",
                "mount.linear",
                vec![
                    of("Force", "mount.force", "beam.root.force"),
                    of("LinearVelocity", "mount.velocity", "mount.velocity"),
                ],
            ),
            G::nest(
                "AngularMechanicalPort",
                "mount.angular",
                vec![
                    of("Torque", "mount.moment", "beam.root.moment"),
                    of(
                        "AngularVelocity",
                        "mount.angular_velocity",
                        "mount.angular_velocity",
                    ),
                ],
            ),
            of("Generic", "mount.acceleration", "mount.acceleration"),
            of(
                "Generic",
                "mount.angular_acceleration",
                "mount.angular_acceleration",
            ),
        ]
    }
}

impl CoSimModel for Vehicle3d {
    const RESOURCE: &'static str = "vehicle3d.toml";
    const GUID_NAMESPACE: &'static str = "hybeam-vehicle3d";
    const BUILD_ID: &'static str = concat!("hybeam-vehicle3d/", env!("CARGO_PKG_VERSION"));
    const GENERATION_TOOL: &'static str = "hybeam fmi2 layer";
    const STATE_MAGIC: [u8; 8] = *b"HYBCAR3D";

    fn from_resource(text: &str) -> Result<Self, String> {
        let scene: Scene = toml::from_str(text).map_err(|e| format!("vehicle3d.toml: {e}"))?;
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
            ("body.roll_inertia", car.body.roll_inertia),
            ("body.front", car.body.front),
            ("body.rear", car.body.rear),
            ("body.track", car.body.track),
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
        let finite = [
            ("body.cg_height", car.body.cg_height),
            ("suspension.front_stiffness", car.suspension.front_stiffness),
            ("suspension.rear_stiffness", car.suspension.rear_stiffness),
            ("suspension.front_damping", car.suspension.front_damping),
            ("suspension.rear_damping", car.suspension.rear_damping),
            ("road.speed", car.road.speed),
            ("road.bump_start", car.road.bump_start),
            ("road.bump_height", car.road.bump_height),
            ("mount.position[0]", car.mount.position[0]),
            ("mount.position[1]", car.mount.position[1]),
            ("mount.position[2]", car.mount.position[2]),
            ("solver.gravity", car.solver.gravity),
        ];
        for (name, v) in finite {
            if !v.is_finite() {
                return Err(format!("{name} = {v}: must be a finite number"));
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
                car.static_state(0.0, [0.0; 3], [0.0; 3], &[0.0; 10])
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
        Ok(match r {
            1..=16 => self.inputs[0][(r - 1) as usize],
            vr::MOUNT_X..=vr::MOUNT_ALPHA_Z => self.mount()[(r - vr::MOUNT_X) as usize],
            vr::HEAVE => self.s[0],
            vr::PITCH => self.s[1],
            vr::ROLL => self.s[2],
            vr::ENERGY => self.car.energy(self.t, &self.s),
            vr::W_ROAD => self.s[W_ROAD],
            vr::W_BEAM => self.s[W_BEAM],
            vr::DISSIPATED => self.s[DISSIPATED],
            vr::W_DRIVE => self.s[W_DRIVE],
            vr::MOBILITY..=vr::MOBILITY_LAST => {
                let k = (r - vr::MOBILITY) as usize;
                self.mobility()[k / 6][k % 6]
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
            vr::BEAM_MASS | 11..=13 if value < 0.0 => Err(format!(
                "{} = {value}: a payload's mass and moments of inertia must be >= 0",
                self.vars[index].name
            )),
            1..=16 if value.is_finite() => {
                let k = (r - 1) as usize;
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
            _ => Err(format!(
                "{} (value reference {r}) cannot be set to {value}",
                self.vars[index].name
            )),
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
        self.check_payload().map_err(StepError::Discard)?;
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
            self.car.static_state(0.0, [0.0; 3], [0.0; 3], &[0.0; 10])
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
            return Err(format!(
                "not a state of this car ({} bytes, expected {})",
                bytes.len(),
                8 * (2 + N + 3 * INPUTS)
            ));
        }
        let word = |i: usize| {
            let mut w = [0u8; 8];
            w.copy_from_slice(&bytes[8 * i..8 * i + 8]);
            u64::from_le_bytes(w)
        };
        if word(0) != self.scene_hash {
            return Err("the state belongs to another vehicle3d.toml".into());
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
    /// mobility ([`Vehicle3d::mobility`], exact); the payload enters nonlinearly, its partials
    /// are central differences (relative step 1e-6).
    fn partial_derivative(&mut self, output: usize, input: usize) -> Result<f64, String> {
        let (o, i) = (self.vars[output].vr, self.vars[input].vr);
        if (vr::REACTION_REFERENCE..=vr::REACTION_REFERENCE_LAST).contains(&o) {
            // the echo of the reaction inputs
            return Ok(f64::from(u8::from(o - vr::REACTION_REFERENCE + 1 == i)));
        }
        if !(vr::MOUNT_AX..=vr::MOUNT_ALPHA_Z).contains(&o) || !(1..=16).contains(&i) {
            return Ok(0.0);
        }
        let row = (o - vr::MOUNT_AX) as usize;
        let k = (i - 1) as usize;
        if k < 6 {
            return Ok(self.mobility()[row][k]);
        }
        let kept = self.inputs[0][k];
        let mut at = |x: f64| {
            self.inputs[0][k] = x;
            let a = self.mount()[13 + row];
            self.inputs[0][k] = kept;
            a
        };
        let d = 1e-6 * kept.abs().max(1.0);
        Ok((at(kept + d) - at(kept - d)) / (2.0 * d))
    }

    fn set_input_derivative(&mut self, index: usize, order: u32, value: f64) -> Result<(), String> {
        let r = self.vars[index].vr;
        match (r, order) {
            (1..=16, 1 | 2) => {
                self.inputs[order as usize][(r - 1) as usize] = value;
                Ok(())
            }
            _ => Err(format!(
                "{} (value reference {r}) has no input derivative of order {order}",
                self.vars[index].name
            )),
        }
    }
}
