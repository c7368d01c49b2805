//! The result of [`solve`](super::solve), by job: the data ([`data`]), its assembly from the
//! stages' results, the margins re-solved for the answer, the result JSON and the printed
//! summary.

mod assemble;
mod data;
mod json;
mod margins;
mod text;
mod workshop_text;

pub use assemble::{guide_names, named_path, pose_summary};
pub use data::*;
