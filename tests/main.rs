//! The integration tests, one binary: each module is one subject (a file in this folder);
//! `common` holds the helpers they share (the package root, the binary runner, the bundled
//! setup), `reference` the independent reference solutions, `svg_pictures` the checks on the
//! report's SVG pictures.
//!
//! One binary links the library once instead of once per file; run one subject with
//! `cargo test --release --test main solve::`.

mod common;
mod reference;
mod svg_pictures;

mod attachment;
mod bodies;
mod cable_spec;
mod calibrate;
mod cell;
mod certified_answers;
mod chain;
mod cli;
mod connected_geometry;
mod contact;
mod datasheet_limits;
mod design_space;
mod diagnosis;
mod dictionary;
mod dictionary_files;
mod dynamics;
mod elastica_reference;
mod guide_kinds;
mod hostile_inputs;
mod hostile_names;
mod lazy_search;
mod life;
mod mesh_reference;
mod motion;
mod motion_consistency;
mod motion_test;
mod mounting;
mod optional_clamps;
mod ranges;
mod real_cables;
mod real_meshes;
mod report;
mod report_plots;
mod report_scene;
mod rigid_chain;
mod robot_info_meshes;
mod robot_model;
mod self_contact;
mod setup;
mod shipped_dictionaries;
mod signatures;
mod sites;
mod solve;
mod statics;
mod sweep;
mod unsolved;
mod urdf_real;
mod viper_dh;
mod whole_arm;
mod xacro;
