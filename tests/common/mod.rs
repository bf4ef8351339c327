//! Scene builders shared by the physics tests.
#![allow(dead_code)]

use hybeam::scene::Scene;

/// Steel.
pub const E_STEEL: f64 = 2.1e11;
/// Steel density [kg/m³].
pub const RHO_STEEL: f64 = 7850.0;

/// A scene from a header (top-level fields and tables) and segment tables.
pub fn scene(header: &str, segments: &[String]) -> Scene {
    let mut text = format!("name = \"test\"\n{header}\n");
    for s in segments {
        text.push_str("[[segments]]\n");
        text.push_str(s);
        text.push('\n');
    }
    Scene::from_toml(&text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// An ANCF segment table.
pub fn ancf(name: &str, length: f64, section: &str, elements: usize, extra: &str) -> String {
    format!(
        "name = \"{name}\"\nkind = \"ancf\"\nlength = {length:e}\n{section}\nyoungs_modulus = {E_STEEL:e}\ndensity = {RHO_STEEL:e}\nelements = {elements}\n{extra}\n"
    )
}

/// A modal segment table.
pub fn modal(
    name: &str,
    length: f64,
    section: &str,
    modes: usize,
    interface: bool,
    extra: &str,
) -> String {
    format!(
        "name = \"{name}\"\nkind = \"modal\"\nlength = {length:e}\n{section}\nyoungs_modulus = {E_STEEL:e}\ndensity = {RHO_STEEL:e}\nmodes = {modes}\ninterface_modes = {interface}\n{extra}\n"
    )
}

/// Round section of diameter d.
pub fn round(d: f64) -> String {
    format!("section = \"round\"\ndiameter = {d:e}")
}

/// Square section of side b.
pub fn square(b: f64) -> String {
    format!("section = \"rectangle\"\nwidth = {b:e}\nheight = {b:e}")
}

/// Reads the tip y column of a run, sampled every `dt` up to `t_end`.
pub fn tip_history(scene: Scene, t_end: f64, dt: f64) -> Vec<[f64; 2]> {
    let mut sim = hybeam::simulator::Simulator::new(scene).expect("scene builds");
    let mut out = vec![sim.outputs().tip_position];
    let n = (t_end / dt).round() as usize;
    for k in 1..=n {
        sim.advance(k as f64 * dt).expect("step succeeds");
        out.push(sim.outputs().tip_position);
    }
    out
}
