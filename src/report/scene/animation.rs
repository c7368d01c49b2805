//! The animation of the main copy: link nodes follow the frames' link poses, cable pieces the
//! frames' cable nodes, all with plain TRS channels and linear interpolation.

use super::document::Builder;
use super::graph::{LineNodes, Trs, f32x3, quaternion_xyzw};
use super::{PoseScene, SceneAnimation};
use gltf_json::accessor::Type;
use gltf_json::animation::{Channel, Interpolation, Property, Sampler, Target};
use gltf_json::validation::Checked;
use gltf_json::{Accessor, Index, Node};
use nalgebra::{UnitQuaternion, Vector3};

/// The animated values, one track per node property, one element per keyframe.
#[derive(Default)]
struct Tracks {
    tracks: Vec<(Index<Node>, Property, Vec<f32>, Type)>,
}

impl Tracks {
    fn translations(&mut self, node: Index<Node>, values: impl Iterator<Item = Vector3<f64>>) {
        let flat: Vec<f32> = values.flat_map(|v| f32x3(&v)).collect();
        self.tracks
            .push((node, Property::Translation, flat, Type::Vec3));
    }

    fn rotations(&mut self, node: Index<Node>, values: impl Iterator<Item = UnitQuaternion<f64>>) {
        self.tracks
            .push((node, Property::Rotation, continuous(values), Type::Vec4));
    }

    fn scales(&mut self, node: Index<Node>, values: impl Iterator<Item = Vector3<f64>>) {
        let flat: Vec<f32> = values.flat_map(|v| f32x3(&v)).collect();
        self.tracks.push((node, Property::Scale, flat, Type::Vec3));
    }

    /// Writes the outputs (one buffer view) and returns one linear sampler and channel per
    /// track, all sampling at `input`.
    fn finish(self, builder: &mut Builder, input: Index<Accessor>) -> (Vec<Channel>, Vec<Sampler>) {
        let parts: Vec<(&[f32], Type)> = self
            .tracks
            .iter()
            .map(|(_, _, values, type_)| (values.as_slice(), *type_))
            .collect();
        let outputs = builder.float_block(&parts);
        let mut channels = Vec::with_capacity(outputs.len());
        let mut samplers = Vec::with_capacity(outputs.len());
        for ((node, property, _, _), output) in self.tracks.into_iter().zip(outputs) {
            let sampler = Index::push(&mut samplers, linear_sampler(input, output));
            channels.push(channel(sampler, node, property));
        }
        (channels, samplers)
    }
}

fn linear_sampler(input: Index<Accessor>, output: Index<Accessor>) -> Sampler {
    Sampler {
        extensions: None,
        extras: Default::default(),
        input,
        interpolation: Checked::Valid(Interpolation::Linear),
        output,
    }
}

fn channel(sampler: Index<Sampler>, node: Index<Node>, property: Property) -> Channel {
    Channel {
        sampler,
        target: Target {
            extensions: None,
            extras: Default::default(),
            node,
            path: Checked::Valid(property),
        },
        extensions: None,
        extras: Default::default(),
    }
}

/// Quaternions as (x, y, z, w), each sign chosen to be nearest the previous one, so that
/// interpolation takes the short way.
fn continuous(rotations: impl Iterator<Item = UnitQuaternion<f64>>) -> Vec<f32> {
    let mut previous: Option<UnitQuaternion<f64>> = None;
    let mut flat = Vec::new();
    for q in rotations {
        let q = match previous {
            Some(p) if p.coords.dot(&q.coords) < 0.0 => {
                UnitQuaternion::new_unchecked(-q.into_inner())
            }
            _ => q,
        };
        flat.extend(quaternion_xyzw(&q));
        previous = Some(q);
    }
    flat
}

/// Adds the animation: translation and rotation of every link node; translation, rotation
/// and scale of every cable sub-segment; translation of every cable joint sphere.
///
/// The animation must have been checked: every frame has all links and the same cable lines
/// with the same node counts as the main scene that built `lines`.
pub(super) fn add_animation(
    builder: &mut Builder,
    animation: &SceneAnimation,
    links: &[Index<Node>],
    lines: &[LineNodes],
) {
    let mut tracks = Tracks::default();
    let frames = &animation.frames;
    for (l, &node) in links.iter().enumerate() {
        let poses = || frames.iter().filter_map(move |f| f.link_poses.get(l));
        tracks.translations(node, poses().map(|p| p.translation.vector));
        tracks.rotations(node, poses().map(|p| p.rotation));
    }
    for (i, line) in lines.iter().enumerate() {
        for (k, &node) in line.segments.iter().enumerate() {
            let trs = || frames.iter().filter_map(move |f| segment_trs(f, i, k));
            tracks.translations(node, trs().map(|t| t.translation));
            tracks.rotations(node, trs().map(|t| t.rotation));
            tracks.scales(node, trs().map(|t| t.scale));
        }
        for (k, &node) in line.joints.iter().enumerate() {
            let points = frames.iter().filter_map(|f| f.cable.get(i)?.nodes_m.get(k));
            tracks.translations(node, points.map(|p| p.coords));
        }
    }
    let times: Vec<f32> = animation.times_s.iter().map(|&t| t as f32).collect();
    let input = builder.floats(&times, Type::Scalar, true, None);
    let (channels, samplers) = tracks.finish(builder, input);
    builder.animation(&animation.name, channels, samplers);
}

/// The transform of sub-segment `k` of cable line `i` in a frame.
fn segment_trs(frame: &PoseScene, i: usize, k: usize) -> Option<Trs> {
    let nodes = &frame.cable.get(i)?.nodes_m;
    Some(Trs::segment(nodes.get(k)?, nodes.get(k + 1)?))
}
