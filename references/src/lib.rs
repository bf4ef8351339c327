//! Reference numbers of `docs/references.md`, as constants for the physics tests
//! (`tests/statics.rs`) and the report, so each table is written once in code. The markdown page
//! is the citable source (it says how each number was made); this crate's test reads it and fails
//! if a constant here and its row there differ.
//!
//! Conventions: a cantilever clamped horizontally at the origin, loaded downwards; `v` is the
//! tip's downward deflection and `u` its horizontal shortening, both divided by the length L.

/// One row of a static cantilever table: tip deflection under a dimensionless load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deflection {
    /// Dimensionless load: α = PL²/EI (§4a) or γ = qL³/EI (§4b) [-].
    pub load: f64,
    /// Downward tip deflection v/L [-].
    pub v: f64,
    /// Horizontal tip shortening u/L [-].
    pub u: f64,
}

const fn row(load: f64, v: f64, u: f64) -> Deflection {
    Deflection { load, v, u }
}

/// §4a: tip-loaded cantilever, inextensible elastica, α = PL²/EI (P the tip force).
pub const ELASTICA: [Deflection; 4] = [
    row(1.0, 0.30172, 0.05643),
    row(2.0, 0.49346, 0.16064),
    row(5.0, 0.71379, 0.38763),
    row(10.0, 0.81061, 0.55500),
];

/// §4b: cantilever under its own weight, inextensible elastica, γ = qL³/EI (q the weight per
/// length).
pub const SELF_WEIGHT: [Deflection; 4] = [
    row(1.0, 0.12347, 0.00875),
    row(2.0, 0.23851, 0.03311),
    row(5.0, 0.49591, 0.15334),
    row(10.0, 0.70020, 0.34365),
];

/// §4c: one of the paper's beams (steel assumed, E = 210 GPa, ρ = 7850 kg/m³), clamped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperBeam {
    /// The beam as §4c names it.
    pub name: &'static str,
    /// Lowest four bending frequencies f₁…f₄ [Hz] (Euler–Bernoulli).
    pub frequencies: [f64; 4],
    /// Static tip sag under self-weight, g = 9.81 m/s² [m] (positive downwards).
    pub sag: f64,
}

/// §4c: the beam of Cases 1 and 2, d = 2 mm, L = 40 cm.
pub const CASE1_BEAM: PaperBeam = PaperBeam {
    name: "d = 2 mm, L = 40 cm (Cases 1, 2)",
    frequencies: [9.045, 56.68, 158.71, 311.01],
    sag: 4.69e-3,
};

/// §4c: the stepped beam of Case 3, d = 2 mm × 20 cm + d = 1 mm × 40 cm.
pub const CASE3_BEAM: PaperBeam = PaperBeam {
    name: "d = 2 mm × 20 cm + d = 1 mm × 40 cm (Case 3, stepped)",
    frequencies: [4.064, 20.47, 41.27, 83.48],
    sag: 24.35e-3,
};

#[cfg(test)]
mod tests {
    use super::*;

    const PAGE: &str = include_str!("../../docs/references.md");

    /// The lines of the page's section whose heading starts with `heading`, up to the next
    /// heading.
    fn section(heading: &str) -> Vec<&'static str> {
        let mut lines = PAGE.lines().skip_while(|l| !l.starts_with(heading));
        let first = lines
            .next()
            .unwrap_or_else(|| panic!("no section {heading}"));
        std::iter::once(first)
            .chain(lines.take_while(|l| !l.starts_with('#')))
            .collect()
    }

    /// Markdown table rows of a section as trimmed cells.
    fn rows(heading: &str) -> Vec<Vec<&'static str>> {
        section(heading)
            .into_iter()
            .filter(|l| l.starts_with('|'))
            .map(|l| l.trim_matches('|').split('|').map(str::trim).collect())
            .collect()
    }

    fn num(cell: &str) -> f64 {
        cell.parse()
            .unwrap_or_else(|_| panic!("{cell:?} is not a number"))
    }

    #[test]
    fn elastica_is_the_table_of_4a() {
        let table = rows("### 4a.");
        let found: Vec<Deflection> = table
            .iter()
            .filter(|r| r[0].parse::<f64>().is_ok())
            .map(|r| row(num(r[0]), num(r[1]), num(r[2])))
            .collect();
        assert_eq!(found, ELASTICA);
    }

    #[test]
    fn self_weight_is_the_table_of_4b() {
        // transposed: rows γ, v/L, u/L with one column per load
        let table = rows("### 4b.");
        let line = |name: &str| -> Vec<f64> {
            let r = table.iter().find(|r| r[0] == name).expect(name);
            r[1..].iter().map(|c| num(c)).collect()
        };
        let (g, v, u) = (line("γ"), line("v/L"), line("u/L"));
        let found: Vec<Deflection> = (0..g.len()).map(|k| row(g[k], v[k], u[k])).collect();
        assert_eq!(found, SELF_WEIGHT);
    }

    #[test]
    fn paper_beams_are_the_table_of_4c() {
        let table = rows("### 4c.");
        for beam in [CASE1_BEAM, CASE3_BEAM] {
            let r = table.iter().find(|r| r[0] == beam.name).expect(beam.name);
            let f: Vec<f64> = r[1].split(',').map(|c| num(c.trim())).collect();
            assert_eq!(f, beam.frequencies, "{}", beam.name);
            let sag = num(r[3].strip_suffix(" mm").expect("sag in mm")) * 1e-3;
            assert!((sag - beam.sag).abs() < 1e-15, "{}: {sag} m", beam.name);
        }
    }
}
