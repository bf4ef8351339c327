//! [`Scene::validate`]: every value of a scene checked; an error names the field, its value and
//! what is allowed (or what to change).

use super::*;
use crate::integrator::{Method, Mode, MIN_ERROR_TOLERANCE};

fn check_positive(field: &str, v: f64, what: &str) -> Result<(), SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SceneError(format!(
            "{field} = {v}: must be a finite number > 0 ({what})"
        )))
    }
}

fn check_nonnegative(field: &str, v: f64, what: &str) -> Result<(), SceneError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(SceneError(format!(
            "{field} = {v}: must be a finite number >= 0 ({what})"
        )))
    }
}

/// A section dimension `field` [m]: a number > 0, or a taper `[at_start, at_end]` of two
/// numbers > 0.
fn check_dim(field: &str, d: &Dim) -> Result<(), SceneError> {
    match d {
        Dim::Uniform(v) => check_positive(field, *v, "metres"),
        Dim::Taper(v) => {
            if v.len() != 2 {
                return Err(SceneError(format!(
                    "{field} = {}: a taper is a list of two numbers [at_start, at_end] in metres \
                     (a uniform section: one number)",
                    show_dim(d)
                )));
            }
            if v.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
                return Err(SceneError(format!(
                    "{field} = {}: both ends of a taper must be finite numbers > 0 (metres)",
                    show_dim(d)
                )));
            }
            Ok(())
        }
    }
}

/// A dimension as the scene writes it.
fn show_dim(d: &Dim) -> String {
    match d {
        Dim::Uniform(v) => format!("{v}"),
        Dim::Taper(v) => format!("{v:?}"),
    }
}

fn check_finite(field: &str, v: f64) -> Result<(), SceneError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(SceneError(format!(
            "{field} = {v}: must be a finite number"
        )))
    }
}

/// Largest number of modes and elements accepted per segment.
pub const MAX_MODES: usize = 12;
/// Largest number of ANCF elements accepted per segment.
pub const MAX_ELEMENTS: usize = 4096;
/// Highest polynomial degree of an ANCF element (a segment's `degree`).
pub const MAX_DEGREE: usize = 7;

impl Scene {
    /// Checks every value; the error names the field, its value and what is allowed.
    pub fn validate(&self) -> Result<(), SceneError> {
        if self.name.trim().is_empty() {
            return Err(SceneError("name = \"\": give the scene a name".into()));
        }
        let sp = self.space;
        let (axes, moment_axes) = match sp {
            SpaceKind::Planar => ("[x, y]", "[z] (the z component)"),
            SpaceKind::Spatial => ("[x, y, z]", "[x, y, z]"),
        };
        for (field, v, n, how) in [
            ("gravity", &self.gravity, sp.dim(), axes),
            ("tip.force", &self.tip.force, sp.dim(), axes),
            ("tip.moment", &self.tip.moment, sp.moment_dim(), moment_axes),
        ] {
            if !v.is_empty() && v.len() != n {
                return Err(SceneError(format!(
                    "{field} = {v:?}: a {sp:?} scene takes {n} components {how} (or leave it out for zero)"
                ).replace("Planar", "planar").replace("Spatial", "spatial")));
            }
            for (i, x) in v.iter().enumerate() {
                check_finite(&format!("{field}[{i}]"), *x)?;
            }
        }
        check_finite("initial.angle", self.initial.angle)?;
        match sp {
            SpaceKind::Planar => {
                if self.root == Root::Ball {
                    return Err(SceneError(
                        "root = \"ball\": a planar scene has clamped or pinned roots (a ball root needs space = \"spatial\")".into(),
                    ));
                }
                if self.initial.orientation.is_some() {
                    return Err(SceneError(
                        "initial.orientation: a planar scene gives the root direction as initial.angle [rad]; remove orientation or set space = \"spatial\"".into(),
                    ));
                }
                if !self.torsion {
                    return Err(SceneError(
                        "torsion = false: torsion is a switch of spatial scenes; remove it or set space = \"spatial\"".into(),
                    ));
                }
                if self.torsion_element != TorsionElement::Director {
                    return Err(SceneError(
                        "torsion_element = \"angle\": the twist element is a choice of spatial scenes; remove it or set space = \"spatial\"".into(),
                    ));
                }
            }
            SpaceKind::Spatial => {
                if self.torsion_element == TorsionElement::Angle {
                    if !self.torsion {
                        return Err(SceneError(
                            "torsion_element = \"angle\" with torsion = false: the cable carries no twist; set torsion = true or remove torsion_element".into(),
                        ));
                    }
                    if self.root == Root::Mounted {
                        return Err(SceneError(
                            "torsion_element = \"angle\" with root = \"mounted\": the twist angles are taken from the beam's initial axis, which a mount turns; use torsion_element = \"director\" on a mounted root".into(),
                        ));
                    }
                }
                if self.root == Root::Pinned {
                    return Err(SceneError(
                        "root = \"pinned\": a spatial scene has clamped or ball roots (a ball root holds the position and leaves the orientation free)".into(),
                    ));
                }
                if self.initial.angle != 0.0 {
                    return Err(SceneError(format!(
                        "initial.angle = {}: a spatial scene gives the root frame as initial.orientation = [e0, e1, e2, e3]",
                        self.initial.angle
                    )));
                }
                if let Some(e) = self.initial.orientation {
                    let n = e.iter().map(|x| x * x).sum::<f64>().sqrt();
                    if !(n.is_finite() && n > 1e-6) {
                        return Err(SceneError(format!(
                            "initial.orientation = {e:?}: Euler parameters must be finite and not all zero (identity: [1, 0, 0, 0])"
                        )));
                    }
                }
            }
        }
        self.validate_mount()?;
        let s = &self.solver;
        if !(s.rho_inf.is_finite() && (0.0..1.0).contains(&s.rho_inf)) {
            return Err(SceneError(format!(
                "solver.rho_inf = {}: must be in [0, 1) (index-3 constraints need numerical damping; 0.9 is the default)",
                s.rho_inf
            )));
        }
        if !(s.max_step.is_finite() && s.max_step >= MIN_STEP) {
            return Err(SceneError(format!(
                "solver.max_step = {}: must be a finite number of seconds >= {MIN_STEP:e} (the smallest internal step: a shorter one resolves nothing of a beam and only multiplies the work)",
                s.max_step
            )));
        }
        if let Some(t) = s
            .tolerance
            .filter(|t| !(t.is_finite() && *t >= MIN_TOLERANCE && *t < 1e-2))
        {
            return Err(SceneError(format!(
                "solver.tolerance = {t}: must be in [{MIN_TOLERANCE:e}, 0.01) (relative Newton tolerance; 1e-11 is the default)"
            )));
        }
        if let Some(e) = s.error_tolerance {
            if !(e.is_finite() && (MIN_ERROR_TOLERANCE..1.0).contains(&e)) {
                return Err(SceneError(format!(
                    "solver.error_tolerance = {e}: must be in [{MIN_ERROR_TOLERANCE:e}, 1) (the local error per internal step relative to each coordinate's scale, e.g. 1e-6; leave it out for equal steps of solver.max_step)"
                )));
            }
            if s.method != Method::Esdirk4 {
                return Err(SceneError(format!(
                    "solver.error_tolerance = {e}: the error control needs the embedded solution of solver.method = \"esdirk4\"; generalized-alpha has none: set solver.method = \"esdirk4\" or remove solver.error_tolerance (generalized-alpha takes equal steps of solver.max_step)"
                )));
            }
            if s.mode == Mode::Realtime {
                return Err(SceneError(format!(
                    "solver.error_tolerance = {e}: the real-time mode (solver.mode = \"realtime\") takes a fixed work per step, internal steps of solver.max_step: remove solver.error_tolerance or set solver.mode = \"normal\""
                )));
            }
        }
        if s.max_internal_steps == 0 {
            return Err(SceneError(
                "solver.max_internal_steps = 0: must be >= 1 (internal steps allowed in one communication step; 20000 is the default)".into(),
            ));
        }
        if !(s.max_axial_strain.is_finite()
            && s.max_axial_strain > 0.0
            && s.max_axial_strain <= 1.0)
        {
            return Err(SceneError(format!(
                "solver.max_axial_strain = {}: must be in (0, 1] (the largest axial strain a state may reach before the step is refused; 0.05 is the default, a rubber hose or soft polymer rod may raise it)",
                s.max_axial_strain
            )));
        }
        if s.realtime_iterations == 0 || s.realtime_iterations > 20 {
            return Err(SceneError(format!(
                "solver.realtime_iterations = {}: must be in 1..=20 (the Newton iterations of every implicit solve in the real-time mode; 3 is the default)",
                s.realtime_iterations
            )));
        }
        if s.realtime_refresh == 0 || s.realtime_refresh > 1000 {
            return Err(SceneError(format!(
                "solver.realtime_refresh = {}: must be in 1..=1000 (the Newton matrix is refreshed every this many implicit solves in the real-time mode; 1, the default, refreshes it every solve)",
                s.realtime_refresh
            )));
        }
        if !(s.realtime_bound.is_finite() && (1.0..=1e12).contains(&s.realtime_bound)) {
            return Err(SceneError(format!(
                "solver.realtime_bound = {}: must be in [1, 1e12] (the largest last Newton increment, in units of solver.tolerance, a real-time step is accepted with; 1e3 is the default)",
                s.realtime_bound
            )));
        }
        if s.max_iterations == 0 || s.max_iterations > 100 {
            return Err(SceneError(format!(
                "solver.max_iterations = {}: must be in 1..=100",
                s.max_iterations
            )));
        }
        check_positive("simulation.t_end", self.simulation.t_end, "seconds")?;
        check_positive(
            "simulation.output_step",
            self.simulation.output_step,
            "seconds",
        )?;
        if self.segments.is_empty() {
            return Err(SceneError(
                "segments: the list is empty: add at least one [[segments]] table with kind = \"modal\" or \"ancf\"".into(),
            ));
        }
        for (i, seg) in self.segments.iter().enumerate() {
            let p = format!("segments[{i}]");
            if seg.name.trim().is_empty()
                || !seg
                    .name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_')
            {
                return Err(SceneError(format!(
                    "{p}.name = {:?}: must be non-empty and use only letters, digits and '_' (it prefixes FMU variable names)",
                    seg.name
                )));
            }
            if self.segments[..i].iter().any(|o| o.name == seg.name) {
                return Err(SceneError(format!(
                    "{p}.name = {:?}: segment names must be unique",
                    seg.name
                )));
            }
            check_positive(&format!("{p}.length"), seg.length, "metres")?;
            check_positive(&format!("{p}.youngs_modulus"), seg.youngs_modulus, "Pa")?;
            check_positive(&format!("{p}.density"), seg.density, "kg/m3")?;
            check_nonnegative(&format!("{p}.damping_time"), seg.damping_time, "seconds")?;
            if !(seg.poisson_ratio.is_finite()
                && seg.poisson_ratio > -1.0
                && seg.poisson_ratio <= 0.5)
            {
                return Err(SceneError(format!(
                    "{p}.poisson_ratio = {}: must be in (-1, 0.5] (steel: 0.3, the default)",
                    seg.poisson_ratio
                )));
            }
            if seg.section != Section::Tube && seg.inner_diameter.is_some() {
                return Err(SceneError(format!(
                    "{p}.inner_diameter: only a section = \"tube\" has an inner diameter"
                )));
            }
            match seg.section {
                Section::Round | Section::Tube => {
                    let d = seg.diameter.as_ref().ok_or_else(|| {
                        SceneError(format!(
                            "{p}.diameter is missing: a round section or a tube needs diameter = <metres> (outer)"
                        ))
                    })?;
                    check_dim(&format!("{p}.diameter"), d)?;
                    if seg.section == Section::Tube {
                        let di = seg.inner_diameter.as_ref().ok_or_else(|| {
                            SceneError(format!(
                                "{p}.inner_diameter is missing: a tube needs inner_diameter = <metres>, below diameter"
                            ))
                        })?;
                        if let Dim::Taper(_) = di {
                            check_dim(&format!("{p}.inner_diameter"), di)?;
                        }
                        for (t, end) in [(0.0, "start"), (1.0, "end")] {
                            let (o, i) = (d.at(t), di.at(t));
                            if !(i.is_finite() && i >= 0.0 && i < o) {
                                return Err(SceneError(if d.is_taper() || di.is_taper() {
                                    format!(
                                        "{p}.inner_diameter = {}: at the segment's {end} it is {i}, must be in [0, diameter = {o}) metres (give a smaller inner diameter or a larger diameter there)",
                                        show_dim(di)
                                    )
                                } else {
                                    format!("{p}.inner_diameter = {i}: must be in [0, diameter = {o}) metres")
                                }));
                            }
                        }
                    }
                }
                Section::Rectangle => {
                    for (f, v) in [("width", &seg.width), ("height", &seg.height)] {
                        let v = v.as_ref().ok_or_else(|| {
                            SceneError(format!(
                                "{p}.{f} is missing: a rectangle section needs width and height in metres"
                            ))
                        })?;
                        check_dim(&format!("{p}.{f}"), v)?;
                    }
                }
            }
            for (f, v) in [
                ("diameter", &seg.diameter),
                ("width", &seg.width),
                ("height", &seg.height),
            ] {
                let used = match seg.section {
                    Section::Round | Section::Tube => f == "diameter",
                    Section::Rectangle => f != "diameter",
                };
                if !used && v.is_some() {
                    // ignored before tapers existed; a taper there must not pass unnoticed
                    if let Some(d @ Dim::Taper(_)) = v {
                        return Err(SceneError(format!(
                            "{p}.{f} = {}: a section = \"{}\" has no {f}; remove it",
                            show_dim(d),
                            format!("{:?}", seg.section).to_lowercase()
                        )));
                    }
                }
            }
            match seg.kind {
                SegmentKind::Modal => {
                    let n = seg.modes.ok_or_else(|| {
                        SceneError(format!(
                            "{p}.modes is missing: a modal segment needs modes = 1..={MAX_MODES}"
                        ))
                    })?;
                    if n == 0 || n > MAX_MODES {
                        return Err(SceneError(format!(
                            "{p}.modes = {n}: must be in 1..={MAX_MODES}"
                        )));
                    }
                    if seg.elements.is_some() {
                        return Err(SceneError(format!(
                            "{p}.elements: a modal segment has no elements; use modes, or kind = \"ancf\""
                        )));
                    }
                    if !(seg.damping_ratio.is_finite() && (0.0..=1.0).contains(&seg.damping_ratio))
                    {
                        return Err(SceneError(format!(
                            "{p}.damping_ratio = {}: must be in [0, 1]",
                            seg.damping_ratio
                        )));
                    }
                }
                SegmentKind::Ancf => {
                    let n = seg.elements.ok_or_else(|| {
                        SceneError(format!(
                            "{p}.elements is missing: an ancf segment needs elements = 1..={MAX_ELEMENTS}"
                        ))
                    })?;
                    if n == 0 || n > MAX_ELEMENTS {
                        return Err(SceneError(format!(
                            "{p}.elements = {n}: must be in 1..={MAX_ELEMENTS}"
                        )));
                    }
                    if seg.modes.is_some() || seg.interface_modes {
                        return Err(SceneError(format!(
                            "{p}.modes: an ancf segment has no modes; use elements, or kind = \"modal\""
                        )));
                    }
                    if seg.linear {
                        return Err(SceneError(format!(
                            "{p}.linear = true: only a modal segment has a linear variant (an ancf segment is nonlinear by construction); remove the key, or use kind = \"modal\""
                        )));
                    }
                    if seg.damping_ratio != 0.0 {
                        return Err(SceneError(format!(
                            "{p}.damping_ratio = {}: only modal segments take a damping ratio; use damping_time (Kelvin-Voigt, seconds) on an ancf segment",
                            seg.damping_ratio
                        )));
                    }
                }
            }
            if let Some(q) = &seg.line_load {
                let f = format!("segments.{}.line_load", seg.name);
                if q.len() != sp.dim() {
                    return Err(SceneError(format!(
                        "{f} = {q:?}: a {sp:?} scene takes {} components {axes} [N/m, world axes] (or leave it out for none)",
                        sp.dim()
                    ).replace("Planar", "planar").replace("Spatial", "spatial")));
                }
                // the static start under a mount is solved in the mount frame, where the
                // world-axes line load would need turning
                let turned = self.mount_start().is_some_and(|m| {
                    m.angle != 0.0 || m.orientation.is_some_and(|o| o != [1.0, 0.0, 0.0, 0.0])
                });
                if turned && self.initial.state == InitialState::Static {
                    return Err(SceneError(format!(
                        "{f} = {q:?}: a line load with a turned mount (mount.angle or mount.orientation) and initial.state = \"static\" is not modelled yet; start straight (initial.state = \"straight\"), leave the mount unturned at the start, or remove the line load"
                    )));
                }
                for x in q {
                    if !x.is_finite() {
                        return Err(SceneError(format!(
                            "{f} = {q:?}: every component must be a finite number [N/m]; give finite values (or leave it out for none)"
                        )));
                    }
                }
            }
            self.validate_curvature(i, seg)?;
        }
        let lines = self.line_load_segments();
        if lines.len() > MAX_LINE_LOADS {
            let names: Vec<&str> = lines
                .iter()
                .map(|&i| self.segments[i].name.as_str())
                .collect();
            return Err(SceneError(format!(
                "segments.*.line_load: {} segments ({}) set a line load, at most {MAX_LINE_LOADS} may; merge segments or remove the line load of those that carry none",
                lines.len(),
                names.join(", ")
            )));
        }
        self.validate_masses()?;
        self.validate_degrees()?;
        self.validate_stations()
    }

    /// The segments' `degree`: 3 (the cubic element) anywhere; 4..=[`MAX_DEGREE`] on a
    /// uniform, straight ANCF segment of a planar scene or a 3D cable (`torsion = false`),
    /// without masses that have an offset or a rotary inertia. An error names the field, its
    /// value and the fix.
    fn validate_degrees(&self) -> Result<(), SceneError> {
        for (i, seg) in self.segments.iter().enumerate() {
            let d = seg.degree;
            if d == 3 {
                continue;
            }
            let f = format!("segments[{i}].degree = {d}");
            if !(3..=MAX_DEGREE).contains(&d) {
                return Err(SceneError(format!(
                    "{f}: must be in 3..={MAX_DEGREE} (3, the default: the cubic ANCF cable element; 4..={MAX_DEGREE}: hierarchic bubbles inside each element)"
                )));
            }
            let refuse = |why: &str| Err(SceneError(format!("{f}: {why}")));
            if seg.kind == SegmentKind::Modal {
                return refuse("a modal segment has no element degree (its shapes are its modes); remove degree, or make the segment kind = \"ancf\"");
            }
            if self.space == SpaceKind::Spatial && self.torsion {
                return refuse("with torsion = true the director and angle elements are cubic only; set torsion = false (the 3D cable takes degree 4..) or degree = 3");
            }
            if seg.is_tapered() {
                return refuse("a tapered segment takes the cubic element only; set degree = 3 or give the segment uniform dimensions");
            }
            if seg.curvature().is_some() {
                return refuse("an initially curved segment takes the cubic element only; set degree = 3 or remove initial_curvature");
            }
            for (k, m) in self.masses.iter().enumerate() {
                if m.segment == seg.name && !m.is_point() {
                    let field = if m
                        .inertia
                        .as_ref()
                        .is_some_and(|v| v.iter().any(|x| *x != 0.0))
                    {
                        "inertia"
                    } else {
                        "offset"
                    };
                    return Err(SceneError(format!(
                        "masses[{k}].{field}: segment {:?} has elements of degree {d}, which carry point masses only (no offset, no rotary inertia); set segments[{i}].degree = 3 or remove `{field}`",
                        seg.name
                    )));
                }
            }
        }
        Ok(())
    }

    /// The segment named `segment` of an item `p` (`masses[i]`, `stations[i]`) of kind `what`
    /// named `name`, after checking the name (letters, digits, `_`; not among `earlier`).
    fn named_item<'a>(
        &self,
        p: &str,
        what: &str,
        name: &str,
        mut earlier: impl Iterator<Item = &'a str>,
        segment: &str,
    ) -> Result<&Segment, SceneError> {
        if name.trim().is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(SceneError(format!(
                "{p}.name = {name:?}: must be non-empty and use only letters, digits and '_' (it prefixes FMU variable names)"
            )));
        }
        if earlier.any(|o| o == name) {
            return Err(SceneError(format!(
                "{p}.name = {name:?}: {what} names must be unique; rename one of them"
            )));
        }
        self.segments
            .iter()
            .find(|s| s.name == segment)
            .ok_or_else(|| {
                let names: Vec<&str> = self.segments.iter().map(|s| s.name.as_str()).collect();
                SceneError(format!(
                    "{p}.segment = {segment:?}: no segment has this name; use one of {names:?}"
                ))
            })
    }

    /// The `[[stations]]` tables: names, segments, positions (at a segment end or an ANCF node).
    fn validate_stations(&self) -> Result<(), SceneError> {
        if self.stations.len() > MAX_STATIONS {
            return Err(SceneError(format!(
                "stations: {} stations, at most {MAX_STATIONS}; remove some",
                self.stations.len()
            )));
        }
        for (i, st) in self.stations.iter().enumerate() {
            let p = format!("stations[{i}]");
            let earlier = self.stations[..i].iter().map(|o| o.name.as_str());
            let seg = self.named_item(&p, "station", &st.name, earlier, &st.segment)?;
            if self.space == SpaceKind::Spatial
                && self.torsion
                && self.torsion_element == TorsionElement::Angle
            {
                return Err(SceneError(format!(
                    "{p}: stations are not computed with torsion_element = \"angle\" (its nodal twist angles do not turn with a rigid rotation of the part beyond the cut); use the director element (torsion_element = \"director\") or remove the station"
                )));
            }
            let at = st.at;
            let tol = 1e-9 * seg.length;
            let along = at.is_finite() && at >= -tol && at <= seg.length + tol;
            if !along {
                return Err(SceneError(format!(
                    "{p}.at = {at}: not a cut of segment {:?}, which is {} m long; give the arc length from its start, 0 to {} m",
                    seg.name, seg.length, seg.length
                )));
            }
            // anywhere along it: the element holding the cut (ANCF element, modal body; planar
            // and spatial) integrates its part before the cut itself (`Element::partial_load`)
        }
        Ok(())
    }

    /// A segment's `initial_curvature`: the scene's number of components, finite, on an ANCF
    /// segment with the exact strain measures and an element family that takes it (the
    /// director element in spatial scenes), and a radius 1/|κ| no shorter than the section's
    /// depth in the bending direction.
    fn validate_curvature(&self, i: usize, seg: &Segment) -> Result<(), SceneError> {
        let Some(c) = &seg.initial_curvature else {
            return Ok(());
        };
        let f = format!("segments[{i}].initial_curvature");
        let v = c.values();
        let shown = match c {
            Curvature::Number(k) => format!("{k}"),
            Curvature::List(v) => format!("{v:?}"),
        };
        let (want, how) = match self.space {
            SpaceKind::Planar => (
                1,
                "a planar scene takes one number κ [1/m] (positive: counter-clockwise)",
            ),
            SpaceKind::Spatial => (
                2,
                "a spatial scene takes [κ_y, κ_z] [1/m] about the section axes",
            ),
        };
        if v.len() != want
            || (self.space == SpaceKind::Spatial && matches!(c, Curvature::Number(_)))
        {
            return Err(SceneError(format!(
                "{f} = {shown}: {how}; give {} (or leave it out for a straight segment)",
                if want == 1 { "a number" } else { "two numbers" }
            )));
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(SceneError(format!(
                "{f} = {shown}: every component must be a finite number [1/m]"
            )));
        }
        let Some([ky, kz]) = seg.curvature() else {
            return Ok(()); // all zero: straight
        };
        if seg.kind == SegmentKind::Modal {
            return Err(SceneError(format!(
                "{f} = {shown}: a modal segment is straight (its modes are a straight beam's); make the segment ANCF (kind = \"ancf\", elements = N) or remove initial_curvature"
            )));
        }
        if seg.strain != StrainModel::Exact {
            return Err(SceneError(format!(
                "{f} = {shown} with strain = \"paper\": the paper's bending measure |r″| has no stress-free arc; remove `strain` (the exact measures) or remove initial_curvature"
            )));
        }
        if self.space == SpaceKind::Spatial {
            if !self.torsion {
                return Err(SceneError(format!(
                    "{f} = {shown} with torsion = false: the 3D cable's bending measure has no section frame to hold a curved reference; use torsion = true (the director element) or remove initial_curvature"
                )));
            }
            if self.torsion_element != TorsionElement::Director {
                return Err(SceneError(format!(
                    "{f} = {shown} with torsion_element = \"angle\": the angle element's twist is taken from the straight beam's axis; use torsion_element = \"director\" or remove initial_curvature"
                )));
            }
        }
        // depth of the section in the bending direction (the curvature normal (κ_z, −κ_y) in
        // section axes y, z): a rectangle's extent along it, a round section's diameter (the
        // larger end's on a taper)
        let k = (ky * ky + kz * kz).sqrt();
        let largest = |d: &Option<Dim>| d.as_ref().map_or(0.0, |d| d.at(0.0).max(d.at(1.0)));
        let depth = match seg.section {
            Section::Round | Section::Tube => largest(&seg.diameter),
            Section::Rectangle => {
                let (b, h) = (largest(&seg.width), largest(&seg.height));
                (h * kz.abs() + b * ky.abs()) / k
            }
        };
        if 1.0 / k < depth {
            return Err(SceneError(format!(
                "{f} = {shown}: the radius of curvature 1/|κ| = {} m is shorter than the section's depth {depth} m in the bending direction; use |κ| <= {} 1/m (a thinner section or a gentler arc)",
                1.0 / k,
                1.0 / depth
            )));
        }
        Ok(())
    }

    /// The `[[masses]]` tables: names, segments, positions, masses, inertia and offset lengths.
    fn validate_masses(&self) -> Result<(), SceneError> {
        let sp = self.space;
        let (space, n_in, n_off, in_how, off_how) = match sp {
            SpaceKind::Planar => ("planar", 1, 2, "[Izz]", "[x, y]"),
            SpaceKind::Spatial => ("spatial", 3, 3, "[Ixx, Iyy, Izz]", "[x, y, z]"),
        };
        for (i, m) in self.masses.iter().enumerate() {
            let p = format!("masses[{i}]");
            let earlier = self.masses[..i].iter().map(|o| o.name.as_str());
            let seg = self.named_item(&p, "mass", &m.name, earlier, &m.segment)?;
            if !(m.at.is_finite() && m.at >= 0.0 && m.at <= seg.length) {
                return Err(SceneError(format!(
                    "{p}.at = {}: must be in [0, {}] (the arc length from the start of segment {:?}, whose length is {} m); move the mass onto that segment or name the segment it sits on",
                    m.at, seg.length, seg.name, seg.length
                )));
            }
            check_positive(&format!("{p}.mass"), m.mass, "kg")?;
            if let Some(v) = &m.inertia {
                if v.len() != n_in {
                    return Err(SceneError(format!(
                        "{p}.inertia = {v:?}: a {space} scene takes {n_in} components {in_how} [kg m2] (or leave it out for a point mass)"
                    )));
                }
                for (k, x) in v.iter().enumerate() {
                    check_nonnegative(&format!("{p}.inertia[{k}]"), *x, "kg m2")?;
                }
            }
            if let Some(v) = &m.offset {
                if v.len() != n_off {
                    return Err(SceneError(format!(
                        "{p}.offset = {v:?}: a {space} scene takes {n_off} components {off_how} [m] (or leave it out for a mass on the centreline)"
                    )));
                }
                for (k, x) in v.iter().enumerate() {
                    check_finite(&format!("{p}.offset[{k}]"), *x)?;
                }
            }
        }
        Ok(())
    }

    fn validate_mount(&self) -> Result<(), SceneError> {
        let sp = self.space;
        let Some(m) = &self.mount else {
            return Ok(());
        };
        if self.root != Root::Mounted {
            return Err(SceneError(format!(
                "[mount]: only a root = \"mounted\" scene has a mount (root = {:?}); remove the table or set root = \"mounted\"",
                self.root
            ).replace("Clamped", "\"clamped\"").replace("Pinned", "\"pinned\"").replace("Ball", "\"ball\"")));
        }
        let (n, nm) = (sp.dim(), sp.moment_dim());
        for (field, v, k) in [
            ("mount.position", &m.position, n),
            ("mount.velocity", &m.velocity, n),
            ("mount.acceleration", &m.acceleration, n),
            ("mount.angular_velocity", &m.angular_velocity, nm),
            ("mount.angular_acceleration", &m.angular_acceleration, nm),
        ] {
            if !v.is_empty() && v.len() != k {
                let space = if sp == SpaceKind::Planar {
                    "planar"
                } else {
                    "spatial"
                };
                return Err(SceneError(format!(
                    "{field} = {v:?}: a {space} scene takes {k} components here (or leave it out for zero)"
                )));
            }
            for (i, x) in v.iter().enumerate() {
                check_finite(&format!("{field}[{i}]"), *x)?;
            }
        }
        check_finite("mount.angle", m.angle)?;
        match sp {
            SpaceKind::Planar => {
                if m.orientation.is_some() {
                    return Err(SceneError(
                        "mount.orientation: a planar scene gives the mount frame as mount.angle [rad]; remove orientation or set space = \"spatial\"".into(),
                    ));
                }
            }
            SpaceKind::Spatial => {
                if m.angle != 0.0 {
                    return Err(SceneError(format!(
                        "mount.angle = {}: a spatial scene gives the mount frame as mount.orientation = [e0, e1, e2, e3]",
                        m.angle
                    )));
                }
                if let Some(e) = m.orientation {
                    let norm = e.iter().map(|x| x * x).sum::<f64>().sqrt();
                    if !(norm.is_finite() && norm > 1e-6) {
                        return Err(SceneError(format!(
                            "mount.orientation = {e:?}: Euler parameters must be finite and not all zero (identity: [1, 0, 0, 0])"
                        )));
                    }
                }
            }
        }
        if self.initial.state == InitialState::Static && self.mount_turns().1 {
            return Err(SceneError(
                "initial.state = \"static\" with mount.angular_acceleration nonzero: a spin that changes has no static state in the mount frame; use initial.state = \"straight\", or start at a constant spin".into(),
            ));
        }
        Ok(())
    }
}
