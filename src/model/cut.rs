//! The data of the stations a model holds ([`super::stations`] computes with it): the cuts and
//! where each coordinate's rigid group is.

use super::section_stress::StressSection;

/// A station of a model: the elements before its cut, where its point and frame are sampled,
/// its section.
#[derive(Debug, Clone)]
pub(crate) struct Cut {
    /// Indices of the elements of the inboard part.
    pub(crate) inboard: Vec<usize>,
    /// (element, ξ) whose sample is the cut's point and section frame.
    pub(crate) at: (usize, f64),
    /// A cut inside an element: (element, ξ) — the loads at the element's start node
    /// (`inboard` are the elements before it) carried across the part [0, ξ] by the element's
    /// [`super::component::Element::partial_load`].
    pub(crate) partial: Option<(usize, f64)>,
    pub(crate) section: StressSection,
}

/// Where each coordinate's rigid group is: (group index, component), for free and held ones;
/// the root section's sample (element, ξ); and, with `outputs.stress`, each element's stress
/// points (indexed as the elements; empty for an element of no segment).
#[derive(Debug, Clone, Default)]
pub(crate) struct GroupMap {
    pub(crate) free: Vec<Option<(u32, u8)>>,
    pub(crate) held: Vec<Option<(u32, u8)>>,
    pub(crate) root: (usize, f64),
    pub(crate) stress: Option<Vec<Vec<StressPoint>>>,
}

/// A point where the beam's stress is sampled, its section computed once: arc length from the
/// root [m], the stiffnesses that turn the local strains into loads, the section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StressPoint {
    /// Arc length from the beam's root [m].
    pub at: f64,
    /// EA [N], GJ [N m²], EI_y, EI_z [N m²].
    pub stiffness: [f64; 4],
    /// The section for [`StressSection::stress`].
    pub section: StressSection,
}

impl StressPoint {
    /// The point at the fraction `t` of segment `seg`'s length, `at` from the beam's root.
    pub fn of(seg: &crate::scene::Segment, t: f64, at: f64) -> Self {
        let props = seg.section_props_at(t);
        let (e, g) = (seg.youngs_modulus, seg.shear_modulus());
        Self {
            at,
            stiffness: [
                e * props.area,
                g * props.torsion,
                e * props.i_y,
                e * props.i_z,
            ],
            section: StressSection::of(seg, t),
        }
    }

    /// The largest von Mises stress [Pa] from the local strains of the sample `p`: N = EAε,
    /// T = GJτ, M_y = EI_y κ_y, M_z = EI_z κ_z (no transverse shear: a strain field does not
    /// give it).
    pub fn stress(&self, p: &super::sample::ShapePoint) -> f64 {
        let [ea, gj, eiy, eiz] = self.stiffness;
        let force = [ea * p.axial_strain, 0.0, 0.0];
        let moment = [gj * p.twist, eiy * p.curvature[0], eiz * p.curvature[1]];
        self.section.stress(force, moment)
    }
}

/// The stations' working memory, kept between outputs: each element's residual (flat, at
/// `offset[e]`), whether it is computed at this output, the samples of a cut.
#[derive(Debug, Clone, Default)]
pub(crate) struct StationWork {
    pub(crate) residual: Vec<f64>,
    pub(crate) offset: Vec<usize>,
    pub(crate) done: Vec<bool>,
    pub(crate) samples: Vec<super::sample::ShapePoint>,
}
