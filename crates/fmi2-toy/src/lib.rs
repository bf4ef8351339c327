//! The FMI 2.0 layer's example model (as Reference-FMUs ships `Dahlquist` or `BouncingBall`
//! beside its `fmi2Functions.c`): a 2D point mass on a spring-damper anchored at the origin,
//! `m ẍ = −k x − c ẋ + m g + F`, integrated with semi-implicit Euler at a fixed internal step.
//! A step fails (state untouched, a recoverable fmi2Discard) when `|F| > max_force` or when it
//! needs more than a million substeps. It offers the optional FMI calls: input derivatives of
//! F (orders 1, 2: F(τ) = F + F′τ + ½F″τ² over the next step), output derivatives (orders 1, 2,
//! of the continuous model), and the directional derivative of its acceleration outputs,
//! which depend directly on F (∂a/∂F = 1/m). Built from the resource `toy.toml`; the whole model is a
//! [`CoSimModel`] plus one line, `fmi2::export_fmi2!(Toy)`. `benches/fmi_overhead.rs` measures
//! the layer's cost per fmi2DoStep with it.

use serde::Deserialize;

use fmi2::hash::fnv1a64;
use fmi2::{Capabilities, Causality, CoSimModel, ModelInfo, StepError, Variability, Variable};

/// Work cap of one communication step (substeps).
const MAX_SUBSTEPS: f64 = 1e6;

fmi2::export_fmi2!(Toy);

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Scene {
    model: SceneModel,
    experiment: SceneExperiment,
    parameters: Params,
    initial: Initial,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneModel {
    name: String,
    #[serde(default)]
    description: String,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneExperiment {
    start_time: f64,
    stop_time: f64,
    step_size: f64,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    mass: f64,
    stiffness: f64,
    damping: f64,
    gravity: [f64; 2],
    max_force: f64,
    internal_step: f64,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
struct Initial {
    position: [f64; 2],
    velocity: [f64; 2],
}

/// Value references of the toy (stable).
mod vr {
    pub const MASS: u32 = 0;
    pub const STIFFNESS: u32 = 1;
    pub const DAMPING: u32 = 2;
    pub const GRAVITY_X: u32 = 3;
    pub const GRAVITY_Y: u32 = 4;
    pub const MAX_FORCE: u32 = 5;
    pub const FORCE_X: u32 = 10;
    pub const FORCE_Y: u32 = 11;
    pub const POS_X: u32 = 20;
    pub const POS_Y: u32 = 21;
    pub const VEL_X: u32 = 22;
    pub const VEL_Y: u32 = 23;
    pub const KINETIC: u32 = 24;
    pub const ACC_X: u32 = 25;
    pub const ACC_Y: u32 = 26;
}

const STATE_MAGIC: &[u8; 8] = b"HYBTOY02";
/// Magic, scene hash, [`Toy::state_f64s`].
const STATE_LEN: usize = 8 + 8 + 19 * 8;

/// The toy model.
#[derive(Debug, Clone)]
pub struct Toy {
    scene_hash: u64,
    info: ModelInfo,
    vars: Vec<Variable>,
    scene_params: Params,
    initial: Initial,
    p: Params,
    force: [f64; 2],
    /// d/dt and d²/dt² of the force over the next step (fmi2SetRealInputDerivatives).
    force_rate: [[f64; 2]; 2],
    x: [f64; 2],
    v: [f64; 2],
}

fn check_params(p: &Params) -> Result<(), String> {
    let checks = [
        ("mass", p.mass, p.mass > 0.0, "> 0"),
        ("stiffness", p.stiffness, p.stiffness >= 0.0, ">= 0"),
        ("damping", p.damping, p.damping >= 0.0, ">= 0"),
        ("max_force", p.max_force, p.max_force > 0.0, "> 0"),
        (
            "internal_step",
            p.internal_step,
            p.internal_step > 0.0,
            "> 0",
        ),
        ("gravity.x", p.gravity[0], true, "finite"),
        ("gravity.y", p.gravity[1], true, "finite"),
    ];
    for (name, value, ok, rule) in checks {
        if !(ok && value.is_finite()) {
            return Err(format!(
                "parameters.{name} = {value}: must be finite and {rule}"
            ));
        }
    }
    Ok(())
}

fn variables(p: &Params) -> Vec<Variable> {
    use Causality::*;
    use Variability::*;
    let v = |name: &str, vr, causality, variability, start, unit, description: &str| Variable {
        name: name.into(),
        vr,
        causality,
        variability,
        start,
        unit: Some(unit),
        description: description.into(),
        depends_on: Vec::new(),
    };
    let acc = |name: &str, vr, input, description: &str| Variable {
        depends_on: vec![input],
        ..v(name, vr, Output, Continuous, None, "m/s2", description)
    };
    vec![
        v(
            "mass",
            vr::MASS,
            Parameter,
            Fixed,
            Some(p.mass),
            "kg",
            "Point mass",
        ),
        v(
            "stiffness",
            vr::STIFFNESS,
            Parameter,
            Fixed,
            Some(p.stiffness),
            "N/m",
            "Spring stiffness",
        ),
        v(
            "damping",
            vr::DAMPING,
            Parameter,
            Tunable,
            Some(p.damping),
            "N.s/m",
            "Damping coefficient",
        ),
        v(
            "gravity.x",
            vr::GRAVITY_X,
            Parameter,
            Tunable,
            Some(p.gravity[0]),
            "m/s2",
            "Gravity, x",
        ),
        v(
            "gravity.y",
            vr::GRAVITY_Y,
            Parameter,
            Tunable,
            Some(p.gravity[1]),
            "m/s2",
            "Gravity, y",
        ),
        v(
            "max_force",
            vr::MAX_FORCE,
            Parameter,
            Fixed,
            Some(p.max_force),
            "N",
            "A step with a larger |tip.force| fails",
        ),
        v(
            "tip.force.x",
            vr::FORCE_X,
            Input,
            Continuous,
            Some(0.0),
            "N",
            "Force on the mass, x",
        ),
        v(
            "tip.force.y",
            vr::FORCE_Y,
            Input,
            Continuous,
            Some(0.0),
            "N",
            "Force on the mass, y",
        ),
        v(
            "tip.position.x",
            vr::POS_X,
            Output,
            Continuous,
            None,
            "m",
            "Position of the mass, x",
        ),
        v(
            "tip.position.y",
            vr::POS_Y,
            Output,
            Continuous,
            None,
            "m",
            "Position of the mass, y",
        ),
        v(
            "tip.velocity.x",
            vr::VEL_X,
            Output,
            Continuous,
            None,
            "m/s",
            "Velocity of the mass, x",
        ),
        v(
            "tip.velocity.y",
            vr::VEL_Y,
            Output,
            Continuous,
            None,
            "m/s",
            "Velocity of the mass, y",
        ),
        v(
            "energy.kinetic",
            vr::KINETIC,
            Output,
            Continuous,
            None,
            "J",
            "Kinetic energy",
        ),
        acc(
            "tip.acceleration.x",
            vr::ACC_X,
            vr::FORCE_X,
            "Acceleration of the mass, x (depends directly on tip.force.x)",
        ),
        acc(
            "tip.acceleration.y",
            vr::ACC_Y,
            vr::FORCE_Y,
            "Acceleration of the mass, y (depends directly on tip.force.y)",
        ),
    ]
}

impl Toy {
    /// Acceleration of the continuous model, component `i` [m/s²], with force `f`.
    fn acceleration(&self, i: usize, x: f64, v: f64, f: f64) -> f64 {
        let p = &self.p;
        (f - p.stiffness * x - p.damping * v) / p.mass + p.gravity[i]
    }

    /// Force component `i` at `tau` seconds into the current step [N].
    fn force_at(&self, i: usize, tau: f64) -> f64 {
        self.force[i] + self.force_rate[0][i] * tau + 0.5 * self.force_rate[1][i] * tau * tau
    }

    fn state_f64s(&self) -> [f64; 19] {
        let p = &self.p;
        [
            p.mass,
            p.stiffness,
            p.damping,
            p.gravity[0],
            p.gravity[1],
            p.max_force,
            p.internal_step,
            self.force[0],
            self.force[1],
            self.x[0],
            self.x[1],
            self.v[0],
            self.v[1],
            0.0,
            0.0,
            self.force_rate[0][0],
            self.force_rate[0][1],
            self.force_rate[1][0],
            self.force_rate[1][1],
        ]
    }
}

impl CoSimModel for Toy {
    const RESOURCE: &'static str = "toy.toml";
    const GUID_NAMESPACE: &'static str = "fmi2.toy";
    const BUILD_ID: &'static str = concat!("toy/", env!("CARGO_PKG_VERSION"));
    const GENERATION_TOOL: &'static str = "fmi2 toy";
    const STATE_MAGIC: [u8; 8] = *b"TOYFMI2S";

    fn from_resource(scene_toml: &str) -> Result<Self, String> {
        let scene: Scene = toml::from_str(scene_toml).map_err(|e| e.to_string())?;
        check_params(&scene.parameters)?;
        let e = &scene.experiment;
        if !(e.start_time.is_finite() && e.stop_time > e.start_time && e.step_size > 0.0) {
            return Err("experiment: need stop_time > start_time and step_size > 0".into());
        }
        let init = scene.initial;
        if init
            .position
            .iter()
            .chain(&init.velocity)
            .any(|x| !x.is_finite())
        {
            return Err("initial: position and velocity must be finite".into());
        }
        Ok(Self {
            scene_hash: fnv1a64(scene_toml.as_bytes()),
            info: ModelInfo {
                model_name: scene.model.name,
                description: scene.model.description,
                start_time: e.start_time,
                stop_time: e.stop_time,
                step_size: e.step_size,
                capabilities: Capabilities {
                    input_derivative_order: 2,
                    output_derivative_order: 2,
                    directional_derivative: true,
                },
            },
            vars: variables(&scene.parameters),
            scene_params: scene.parameters,
            initial: init,
            p: scene.parameters,
            force: [0.0; 2],
            force_rate: [[0.0; 2]; 2],
            x: init.position,
            v: init.velocity,
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
        let p = &self.p;
        Ok(match r {
            vr::MASS => p.mass,
            vr::STIFFNESS => p.stiffness,
            vr::DAMPING => p.damping,
            vr::GRAVITY_X => p.gravity[0],
            vr::GRAVITY_Y => p.gravity[1],
            vr::MAX_FORCE => p.max_force,
            vr::FORCE_X => self.force[0],
            vr::FORCE_Y => self.force[1],
            vr::POS_X => self.x[0],
            vr::POS_Y => self.x[1],
            vr::VEL_X => self.v[0],
            vr::VEL_Y => self.v[1],
            vr::KINETIC => 0.5 * p.mass * (self.v[0] * self.v[0] + self.v[1] * self.v[1]),
            vr::ACC_X | vr::ACC_Y => {
                let i = (r - vr::ACC_X) as usize;
                self.acceleration(i, self.x[i], self.v[i], self.force[i])
            }
            _ => return Err(format!("value reference {r} is not a variable of the toy")),
        })
    }

    fn set_real(&mut self, index: usize, value: f64) -> Result<(), String> {
        let r = self.vars[index].vr;
        let mut p = self.p;
        match r {
            vr::MASS => p.mass = value,
            vr::STIFFNESS => p.stiffness = value,
            vr::DAMPING => p.damping = value,
            vr::GRAVITY_X => p.gravity[0] = value,
            vr::GRAVITY_Y => p.gravity[1] = value,
            vr::MAX_FORCE => p.max_force = value,
            vr::FORCE_X | vr::FORCE_Y => {
                if !value.is_finite() {
                    return Err(format!("tip force {value} is not finite"));
                }
                let i = (r - vr::FORCE_X) as usize;
                self.force[i] = value;
                // a new value starts a new input polynomial
                self.force_rate[0][i] = 0.0;
                self.force_rate[1][i] = 0.0;
                return Ok(());
            }
            _ => return Err(format!("value reference {r} cannot be set")),
        }
        check_params(&p)?;
        self.p = p;
        Ok(())
    }

    fn initialize(&mut self, _start_time: f64) -> Result<(), String> {
        check_params(&self.p)?;
        self.x = self.initial.position;
        self.v = self.initial.velocity;
        Ok(())
    }

    fn do_step(&mut self, _t: f64, h: f64) -> Result<(), StepError> {
        let p = &self.p;
        let f = self.force;
        let f_abs = f[0].hypot(f[1]);
        if f_abs > p.max_force {
            return Err(StepError::Discard(format!(
                "|tip.force| = {f_abs} N exceeds max_force = {} N",
                p.max_force
            )));
        }
        let n = (h / p.internal_step - 1e-9).ceil().max(1.0);
        if n > MAX_SUBSTEPS {
            return Err(StepError::Discard(format!(
                "h = {h} s needs {n:e} substeps of internal_step = {} s, more than {MAX_SUBSTEPS:e}: split the communication step",
                p.internal_step
            )));
        }
        let dt = h / n;
        let (mut x, mut v) = (self.x, self.v);
        for k in 0..n as u64 {
            let tau = k as f64 * dt;
            for i in 0..2 {
                let a = self.acceleration(i, x[i], v[i], self.force_at(i, tau));
                v[i] += dt * a;
                x[i] += dt * v[i];
            }
        }
        if x.iter().chain(&v).any(|z| !z.is_finite()) {
            return Err(StepError::Discard("the state became non-finite".into()));
        }
        self.x = x;
        self.v = v;
        // the input derivatives held for this step only
        self.force_rate = [[0.0; 2]; 2];
        Ok(())
    }

    fn reset(&mut self) -> Result<(), String> {
        self.p = self.scene_params;
        self.force = [0.0; 2];
        self.force_rate = [[0.0; 2]; 2];
        self.x = self.initial.position;
        self.v = self.initial.velocity;
        Ok(())
    }

    fn save_state(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(STATE_LEN);
        b.extend_from_slice(STATE_MAGIC);
        b.extend_from_slice(&self.scene_hash.to_le_bytes());
        for x in self.state_f64s() {
            b.extend_from_slice(&x.to_le_bytes());
        }
        b
    }

    fn load_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        if bytes.len() != STATE_LEN || &bytes[..8] != STATE_MAGIC {
            return Err(format!(
                "not a toy state of format 2 ({} bytes)",
                bytes.len()
            ));
        }
        let word = |i: usize| {
            let mut w = [0u8; 8];
            w.copy_from_slice(&bytes[8 + 8 * i..16 + 8 * i]);
            w
        };
        if u64::from_le_bytes(word(0)) != self.scene_hash {
            return Err("the state belongs to another scene".into());
        }
        let f: Vec<f64> = (1..20).map(|i| f64::from_le_bytes(word(i))).collect();
        let p = Params {
            mass: f[0],
            stiffness: f[1],
            damping: f[2],
            gravity: [f[3], f[4]],
            max_force: f[5],
            internal_step: f[6],
        };
        check_params(&p)?;
        if f[7..13].iter().chain(&f[15..19]).any(|x| !x.is_finite()) {
            return Err("the state holds non-finite values".into());
        }
        self.p = p;
        self.force = [f[7], f[8]];
        self.x = [f[9], f[10]];
        self.v = [f[11], f[12]];
        self.force_rate = [[f[15], f[16]], [f[17], f[18]]];
        Ok(())
    }

    fn set_input_derivative(&mut self, index: usize, order: u32, value: f64) -> Result<(), String> {
        let r = self.vars[index].vr;
        match (r, order) {
            (vr::FORCE_X | vr::FORCE_Y, 1 | 2) => {
                self.force_rate[order as usize - 1][(r - vr::FORCE_X) as usize] = value;
                Ok(())
            }
            _ => Err(format!(
                "value reference {r} has no input derivative of order {order}"
            )),
        }
    }

    /// Time derivatives of the continuous model at the current time (x′ = v, v′ = a,
    /// a′ = (F′ − k v − c a)/m, a″ = (F″ − k a − c a′)/m).
    fn get_output_derivative(&self, index: usize, order: u32) -> Result<f64, String> {
        let r = self.vars[index].vr;
        let p = &self.p;
        let i = match r {
            vr::POS_X | vr::VEL_X | vr::ACC_X => 0,
            vr::POS_Y | vr::VEL_Y | vr::ACC_Y => 1,
            _ => return Err(format!("value reference {r} has no output derivative")),
        };
        let a = self.acceleration(i, self.x[i], self.v[i], self.force[i]);
        let a1 = (self.force_rate[0][i] - p.stiffness * self.v[i] - p.damping * a) / p.mass;
        let a2 = (self.force_rate[1][i] - p.stiffness * a - p.damping * a1) / p.mass;
        // derivatives of x: [v, a, a′, a″]; velocity starts one later, acceleration two
        let chain = [self.v[i], a, a1, a2];
        let shift = match r {
            vr::POS_X | vr::POS_Y => 0,
            vr::VEL_X | vr::VEL_Y => 1,
            _ => 2,
        };
        chain
            .get(shift + order as usize - 1)
            .copied()
            .ok_or_else(|| format!("order {order} of value reference {r} is not available"))
    }

    /// ∂a_i/∂F_i = 1/m (the only direct dependencies).
    fn partial_derivative(&mut self, output: usize, input: usize) -> Result<f64, String> {
        let (o, i) = (self.vars[output].vr, self.vars[input].vr);
        match (o, i) {
            (vr::ACC_X, vr::FORCE_X) | (vr::ACC_Y, vr::FORCE_Y) => Ok(1.0 / self.p.mass),
            _ => Err(format!("no direct dependency of {o} on {i}")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = include_str!("../toy.toml");

    /// The index of value reference `r` (the FMI layer's resolution).
    fn at(m: &Toy, r: u32) -> usize {
        m.vars.iter().position(|v| v.vr == r).unwrap()
    }

    #[test]
    fn failed_step_keeps_state_and_state_round_trips() {
        let mut m = Toy::from_resource(SCENE).unwrap();
        m.initialize(0.0).unwrap();
        m.set_real(at(&m, vr::FORCE_X), 5.0).unwrap();
        m.do_step(0.0, 0.01).unwrap();
        let saved = m.save_state();
        m.set_real(at(&m, vr::FORCE_Y), 1e6).unwrap();
        assert!(m
            .do_step(0.01, 0.01)
            .unwrap_err()
            .message()
            .contains("max_force"));
        // the parameters (before the force, which was set, and the state) are unchanged
        assert_eq!(m.save_state()[..STATE_LEN - 96], saved[..STATE_LEN - 96]);
        let mut n = Toy::from_resource(SCENE).unwrap();
        n.load_state(&saved).unwrap();
        m.load_state(&saved).unwrap();
        m.do_step(0.01, 0.01).unwrap();
        n.do_step(0.01, 0.01).unwrap();
        assert_eq!(
            m.get_real(at(&m, vr::POS_X)).unwrap().to_bits(),
            n.get_real(at(&n, vr::POS_X)).unwrap().to_bits()
        );
        assert!(n.load_state(b"junk").is_err());
    }

    #[test]
    fn bad_scene_and_parameter_are_named() {
        let e = Toy::from_resource(&SCENE.replace("mass = 1.0", "mass = -1.0")).unwrap_err();
        assert!(e.contains("parameters.mass"), "{e}");
        assert!(Toy::from_resource("nonsense").is_err());
        let mut m = Toy::from_resource(SCENE).unwrap();
        assert!(m
            .set_real(at(&m, vr::DAMPING), -1.0)
            .unwrap_err()
            .contains("damping"));
        assert_eq!(m.get_real(at(&m, vr::DAMPING)).unwrap(), 0.5);
    }
}
