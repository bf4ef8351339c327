//! The data of the stations a model holds ([`super::stations`] computes with it): the cuts and
//! where each coordinate's rigid group is.

use super::section_stress::StressSection;
use crate::scene::Segment;

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
/// the root section's sample (element, ξ); and, with `outputs.stress`, the segments and where
/// each element starts along its segment [m] and each segment along the beam [m].
#[derive(Debug, Clone, Default)]
pub(crate) struct GroupMap {
    pub(crate) free: Vec<Option<(u32, u8)>>,
    pub(crate) held: Vec<Option<(u32, u8)>>,
    pub(crate) root: (usize, f64),
    pub(crate) stress: Option<(Vec<Segment>, Vec<f64>, Vec<f64>)>,
}
