//! The inputs the harness sets before each step: a sine tip force and, for a mounted FMU, a
//! vertical heave of the mount with consistent position, velocity and acceleration.

use std::f64::consts::TAU;

use crate::fmu::{Causality, ModelDescription};

/// A sine `amplitude · sin(2π · frequency · t)` and its first two time derivatives.
#[derive(Debug, Clone, Copy)]
pub struct Sine {
    /// Amplitude (the unit of the quantity: N for the force, m for the heave).
    pub amplitude: f64,
    /// Frequency [Hz].
    pub frequency: f64,
}

impl Sine {
    /// `[value, d/dt value, d²/dt² value]` at `t` [s].
    #[inline]
    pub fn at(&self, t: f64) -> [f64; 3] {
        let w = TAU * self.frequency;
        let (s, c) = (w * t).sin_cos();
        [
            self.amplitude * s,
            self.amplitude * w * c,
            -self.amplitude * w * w * s,
        ]
    }
}

/// What one input is set to at each step.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Role {
    /// Held at this value (its start value).
    Constant(f64),
    /// The tip force sine.
    Force,
    /// The heave path: its derivative `order` (0 position, 1 velocity, 2 acceleration) added
    /// to `base` (the start value).
    Heave { order: usize, base: f64 },
}

/// The inputs set each step: value references, what each follows, and the values buffer.
#[derive(Debug, Clone)]
pub struct InputPlan {
    /// Value references passed to fmi2SetReal, in this order.
    pub vrs: Vec<u32>,
    /// Names, for the report.
    pub names: Vec<String>,
    roles: Vec<Role>,
    /// The values of the last [`InputPlan::fill`] (pre-allocated).
    pub values: Vec<f64>,
    force: Sine,
    heave: Sine,
    /// The vertical axis of the mount (`y` planar, `z` spatial), if the FMU is mounted.
    pub vertical: Option<char>,
}

/// The variable that carries the tip force: `tip.force.z` in space, else `tip.force.y`.
pub fn force_variable(md: &ModelDescription) -> Option<&'static str> {
    ["tip.force.z", "tip.force.y"].into_iter().find(|n| {
        md.variable(n)
            .is_some_and(|v| v.causality == Causality::Input)
    })
}

impl InputPlan {
    /// The plan for `md`: the tip force (`force`), and for a mounted FMU (inputs
    /// `root.position.*`) the heave `heave` along the vertical axis (z when the FMU has
    /// `root.position.z`, else y: the shipped spatial scenes have gravity along -z, the
    /// planar ones along -y) on position, velocity and acceleration, every other `root.*` input
    /// (the other axes, orientation or angle, angular velocity and acceleration) held at its start
    /// value; the partner inputs `root.mobility.*` and `root.reaction_reference.*` are not set.
    pub fn new(md: &ModelDescription, force: Sine, heave: Sine) -> Result<Self, String> {
        let force_name = force_variable(md)
            .ok_or("the FMU has no input tip.force.z or tip.force.y: not a hybeam beam FMU")?;
        let mut plan = InputPlan {
            vrs: Vec::new(),
            names: Vec::new(),
            roles: Vec::new(),
            values: Vec::new(),
            force,
            heave,
            vertical: None,
        };
        let force_vr = md.variable(force_name).map(|v| v.vr).unwrap_or_default();
        plan.push(force_name, force_vr, Role::Force);
        let mounted = md
            .variables
            .iter()
            .any(|v| v.causality == Causality::Input && v.name.starts_with("root.position."));
        if mounted {
            let axis = if md.variable("root.position.z").is_some() {
                'z'
            } else {
                'y'
            };
            plan.vertical = Some(axis);
            let heaved = [
                format!("root.position.{axis}"),
                format!("root.velocity.{axis}"),
                format!("root.acceleration.{axis}"),
            ];
            for v in md.variables.iter().filter(|v| {
                v.causality == Causality::Input
                    && v.name.starts_with("root.")
                    && !v.name.starts_with("root.mobility.")
                    && !v.name.starts_with("root.reaction_reference.")
            }) {
                let start = v.start.ok_or_else(|| {
                    format!(
                        "input {} has no start value in modelDescription.xml",
                        v.name
                    )
                })?;
                let role = match heaved.iter().position(|h| *h == v.name) {
                    Some(order) => Role::Heave { order, base: start },
                    None => Role::Constant(start),
                };
                plan.push(&v.name, v.vr, role);
            }
            for h in &heaved[..2] {
                if !plan.names.contains(h) {
                    return Err(format!(
                        "a mounted FMU (it has root.position.* inputs) without the input {h}"
                    ));
                }
            }
        }
        plan.values = vec![0.0; plan.vrs.len()];
        Ok(plan)
    }

    fn push(&mut self, name: &str, vr: u32, role: Role) {
        self.vrs.push(vr);
        self.names.push(name.to_string());
        self.roles.push(role);
    }

    /// Writes the inputs at time `t` [s] into [`InputPlan::values`] (no allocation).
    #[inline]
    pub fn fill(&mut self, t: f64) {
        let f = self.force.at(t)[0];
        let h = self.heave.at(t);
        for (value, role) in self.values.iter_mut().zip(&self.roles) {
            *value = match *role {
                Role::Constant(c) => c,
                Role::Force => f,
                Role::Heave { order, base } => base + h[order],
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmu::parse;

    /// Central differences of the path's position and velocity match its velocity and
    /// acceleration to the differences' truncation error (h² / 6 of the next derivative).
    #[test]
    fn the_heave_path_is_consistent() {
        let s = Sine {
            amplitude: 0.02,
            frequency: 1.5,
        };
        let h = 1e-5;
        let w = TAU * s.frequency;
        let bound = s.amplitude * w.powi(4) * h * h; // ≥ h²/6 · max |x'''|, |x''''|
        for k in 0..200 {
            let t = 0.0123 * k as f64;
            let (m, c, p) = (s.at(t - h), s.at(t), s.at(t + h));
            let dx = (p[0] - m[0]) / (2.0 * h);
            let dv = (p[1] - m[1]) / (2.0 * h);
            assert!(
                (dx - c[1]).abs() < bound + 1e-9,
                "t = {t}: {dx} vs {}",
                c[1]
            );
            assert!(
                (dv - c[2]).abs() < bound + 1e-8,
                "t = {t}: {dv} vs {}",
                c[2]
            );
            // and the second difference of the position is the acceleration
            let ddx = (p[0] - 2.0 * c[0] + m[0]) / (h * h);
            assert!((ddx - c[2]).abs() < 1e-3 * s.amplitude * w * w, "t = {t}");
        }
        // at rest at t = 0 relative to the start: position 0, acceleration 0
        assert_eq!(s.at(0.0)[0], 0.0);
        assert_eq!(s.at(0.0)[2], 0.0);
    }

    const MOUNTED_3D: &str = r#"<fmiModelDescription guid="{g}">
  <CoSimulation modelIdentifier="boom_3d"/>
  <ModelVariables>
    <ScalarVariable name="tip.force.y" valueReference="2" causality="input"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="tip.force.z" valueReference="3" causality="input"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="root.position.x" valueReference="40" causality="input"><Real start="0.3"/></ScalarVariable>
    <ScalarVariable name="root.position.z" valueReference="42" causality="input"><Real start="1.4"/></ScalarVariable>
    <ScalarVariable name="root.orientation.e0" valueReference="44" causality="input"><Real start="0.99"/></ScalarVariable>
    <ScalarVariable name="root.velocity.z" valueReference="50" causality="input"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="root.acceleration.z" valueReference="57" causality="input"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="root.mobility.ax_fx" valueReference="200" causality="input"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="tip.position.z" valueReference="12" causality="output"><Real/></ScalarVariable>
  </ModelVariables>
</fmiModelDescription>"#;

    #[test]
    fn a_mounted_spatial_fmu_heaves_along_z() {
        let md = parse(MOUNTED_3D).unwrap();
        let force = Sine {
            amplitude: 10.0,
            frequency: 2.0,
        };
        let heave = Sine {
            amplitude: 0.01,
            frequency: 1.0,
        };
        let mut plan = InputPlan::new(&md, force, heave).unwrap();
        assert_eq!(plan.vertical, Some('z'));
        assert_eq!(plan.vrs, vec![3, 40, 42, 44, 50, 57]);
        let t = 0.1;
        plan.fill(t);
        let h = heave.at(t);
        assert_eq!(plan.values[0], force.at(t)[0]);
        assert_eq!(plan.values[1], 0.3);
        assert_eq!(plan.values[2], 1.4 + h[0]);
        assert_eq!(plan.values[3], 0.99);
        assert_eq!(plan.values[4], h[1]);
        assert_eq!(plan.values[5], h[2]);
    }

    #[test]
    fn a_clamped_planar_fmu_gets_the_force_only() {
        let md = parse(
            r#"<fmiModelDescription guid="{g}"><CoSimulation modelIdentifier="case1"/><ModelVariables>
    <ScalarVariable name="tip.force.y" valueReference="2" causality="input"><Real start="0"/></ScalarVariable>
  </ModelVariables></fmiModelDescription>"#,
        )
        .unwrap();
        let plan = InputPlan::new(
            &md,
            Sine {
                amplitude: 1.0,
                frequency: 2.0,
            },
            Sine {
                amplitude: 0.0,
                frequency: 1.0,
            },
        )
        .unwrap();
        assert_eq!((plan.vrs.clone(), plan.vertical), (vec![2], None));
    }
}
