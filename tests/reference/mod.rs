//! Independent reference solutions used by the validation tests.
//!
//! Nothing in here uses the `cable_dict` crate: the references are written from the continuum
//! equations so that they can judge the crate's discrete solver.

#![allow(dead_code)]

pub mod elastica;
pub mod mesh_solid;
pub mod vibration;
