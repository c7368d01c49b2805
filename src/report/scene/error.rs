//! Why a scene cannot be written.

/// A [`SceneSpec`](super::SceneSpec) that cannot become a `.glb` file.
///
/// Frame and keyframe numbers are 0-based; `scene` names the part of the spec at fault
/// (`main`, `animation frame 3`, `snapshot 'critical pose 1'`).
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The cable radius is not a positive finite length.
    #[error("the cable radius {0} m must be finite and > 0")]
    CableRadius(f64),
    /// A pose scene has not one link pose per robot link.
    #[error("{scene}: {got} link poses for a robot with {expected} links")]
    LinkPoseCount {
        /// The pose scene at fault.
        scene: String,
        /// Link poses given.
        got: usize,
        /// Links of the robot.
        expected: usize,
    },
    /// A cable line cannot be drawn with fewer than two nodes.
    #[error("{scene}: cable line '{line}' has {nodes} node(s); at least 2 are needed")]
    TooFewNodes {
        /// The pose scene at fault.
        scene: String,
        /// The cable line's name.
        line: String,
        /// Its node count.
        nodes: usize,
    },
    /// A coordinate, pose, time or mesh vertex is NaN, infinite or too large for `f32`.
    #[error("{scene}: {what} is not finite (or too large for glTF's 32-bit floats)")]
    NonFinite {
        /// The part of the spec at fault.
        scene: String,
        /// The offending value.
        what: String,
    },
    /// Damage per cycle given for a cable line the main scene does not have, not one value
    /// per node of it, or a value that is negative or not finite.
    #[error("damage per cycle of cable line '{line}': {why}")]
    Damage {
        /// The cable line's name.
        line: String,
        /// What is wrong.
        why: String,
    },
    /// A guide refers to a link the robot does not have.
    #[error("guide '{guide}' is on link {link}, but the robot has {links} links")]
    GuideLink {
        /// The guide's name.
        guide: String,
        /// The link index it gives.
        link: usize,
        /// Links of the robot.
        links: usize,
    },
    /// An animation has not one frame per keyframe time.
    #[error("animation '{animation}': {times} keyframe times but {frames} frames")]
    KeyframeCount {
        /// The animation's name.
        animation: String,
        /// Keyframe times given.
        times: usize,
        /// Frames given.
        frames: usize,
    },
    /// An animation without keyframes.
    #[error("animation '{animation}' has no keyframes")]
    NoKeyframes {
        /// The animation's name.
        animation: String,
    },
    /// The first keyframe is not at time 0.
    #[error("animation '{animation}': the first keyframe is at {time} s; it must be at 0 s")]
    FirstKeyframe {
        /// The animation's name.
        animation: String,
        /// Its first keyframe time.
        time: f64,
    },
    /// Keyframe times that do not strictly increase (also after rounding to `f32`).
    #[error(
        "animation '{animation}': keyframe {index} at {time} s does not come after the one \
         before it at {previous} s (times must strictly increase, also as 32-bit floats)"
    )]
    TimesNotIncreasing {
        /// The animation's name.
        animation: String,
        /// Index of the offending keyframe.
        index: usize,
        /// Time of the keyframe before it.
        previous: f64,
        /// Its time.
        time: f64,
    },
    /// An animation frame with another number of cable lines than the main scene.
    #[error("animation frame {frame}: {got} cable lines, but the main scene has {expected}")]
    FrameLineCount {
        /// Index of the frame.
        frame: usize,
        /// Its cable line count.
        got: usize,
        /// The main scene's cable line count.
        expected: usize,
    },
    /// An animation frame whose cable line has another node count than in the main scene.
    #[error(
        "animation frame {frame}: cable line {index} ('{line}') has {got} nodes, \
         but {expected} in the main scene"
    )]
    FrameNodeCount {
        /// Index of the frame.
        frame: usize,
        /// Index of the cable line.
        index: usize,
        /// The cable line's name in the main scene.
        line: String,
        /// Its node count in the frame.
        got: usize,
        /// Its node count in the main scene.
        expected: usize,
    },
    /// A collision mesh triangle refers to a vertex the mesh does not have.
    #[error(
        "link '{link}', collider {collider}: triangle {triangle} refers to vertex {vertex}, \
         but the mesh has {vertices} vertices"
    )]
    MeshIndex {
        /// The link's name.
        link: String,
        /// Index of the collider in the link.
        collider: usize,
        /// Index of the triangle.
        triangle: usize,
        /// The vertex index it gives.
        vertex: u32,
        /// Vertices of the mesh.
        vertices: usize,
    },
    /// More data than a `.glb` file (32-bit lengths) can hold.
    #[error("the scene needs {bytes} bytes, more than a .glb file can hold (4 GiB)")]
    TooLarge {
        /// Bytes needed.
        bytes: u64,
    },
    /// The glTF JSON could not be written.
    #[error("cannot write the glTF JSON: {0}")]
    Json(#[from] serde_json::Error),
}
