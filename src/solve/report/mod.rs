//! The result of [`solve`](super::solve), one job per file: the data (`data`), its assembly
//! from the stages' results (`assemble`), the margins re-solved for the answer (`margins`),
//! the result JSON (`json`). Its wordings (the printed summaries, the rows of the report)
//! are in [`crate::report::text`].

mod assemble;
mod data;
mod json;
mod margins;

pub(in crate::solve) use assemble::Stages;
pub(in crate::solve) use assemble::{binding, life, motion_verdicts};
pub use assemble::{dropped_per_segment, guide_names, named_path, pose_summary};
pub use data::*;
