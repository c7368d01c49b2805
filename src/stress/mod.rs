//! Stress metrics of a cable shape at one robot pose: how tightly it bends, how far it is
//! stretched, how close it comes to the robot and to itself.
//!
//! A shape is the polyline of the discrete cable's nodes from one guide to the next.

mod bend;
pub mod contact;
mod self_contact;
mod stretch;
mod twist;

pub use bend::{
    BendRadius, CurvatureRange, bend_profile, curvature_vectors_per_m, curvatures_per_m,
    min_bend_radius,
};
pub use contact::{
    ClampZone, Clearance, ContactError, GuideEnd, Obstacles, min_clearance, min_clearance_to_links,
};
pub use self_contact::{
    FirstSelfContact, SelfContact, self_contact, self_contact_gap_m, self_contact_within,
};
pub use stretch::stretch;
pub use twist::twist_per_length_deg_per_m;
