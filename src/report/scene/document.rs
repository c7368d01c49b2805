//! Builds the glTF document ([`gltf_json::Root`]) and its binary buffer.
//!
//! Every object is a plain `gltf_json` struct literal; meshes, materials, nodes and
//! animations carry their `name` (the crate enables `gltf-json`'s `names` feature). The JSON
//! goes through [`serde_json::Value`] before it is written: keys sorted, numbers as `f64`.

use super::SceneError;
use super::check::finite32;
use super::glb;
use super::mesh::TriangleMesh;
use gltf_json::accessor::{ComponentType, GenericComponentType, Type};
use gltf_json::animation::{Channel, Sampler};
use gltf_json::buffer::{Target, View};
use gltf_json::extensions;
use gltf_json::extensions::mesh::Mapping;
use gltf_json::extensions::root::KhrMaterialsVariants;
use gltf_json::extensions::scene::khr_materials_variants;
use gltf_json::material::{PbrBaseColorFactor, PbrMetallicRoughness, StrengthFactor};
use gltf_json::mesh::{Mode, Primitive, Semantic};
use gltf_json::validation::{Checked, USize64};
use gltf_json::{Accessor, Animation, Buffer, Index, Material, Mesh, Node, Root, Scene, Value};
use std::collections::BTreeMap;

/// The document under construction: JSON objects and the binary chunk.
pub(super) struct Builder {
    root: Root,
    bin: Vec<u8>,
}

impl Builder {
    /// An empty document with the asset header.
    pub fn new() -> Builder {
        let mut root = Root::default();
        root.asset.generator = Some(format!("cable-dict {}", env!("CARGO_PKG_VERSION")));
        Builder {
            root,
            bin: Vec::new(),
        }
    }

    /// Appends `bytes` to the binary chunk (4-byte aligned) as a new buffer view.
    fn view(&mut self, bytes: &[u8], target: Option<Target>) -> Index<View> {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        let view = View {
            buffer: Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(self.bin.len())),
            byte_stride: None,
            name: None,
            target: target.map(Checked::Valid),
            extensions: None,
            extras: Default::default(),
        };
        self.bin.extend_from_slice(bytes);
        Index::push(&mut self.root.buffer_views, view)
    }

    /// Float data (`type_` components per element, flattened) as a view and an accessor,
    /// with per-component bounds when `bounded`.
    pub fn floats(
        &mut self,
        values: &[f32],
        type_: Type,
        bounded: bool,
        target: Option<Target>,
    ) -> Index<Accessor> {
        let width = type_.multiplicity();
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, target);
        let mut accessor = self.accessor(view, values.len() / width, ComponentType::F32, type_);
        if bounded {
            let (min, max) = bounds(values, width);
            accessor.min = Some(Value::from(min));
            accessor.max = Some(Value::from(max));
        }
        Index::push(&mut self.root.accessors, accessor)
    }

    /// Several float arrays (`type_` components per element, flattened) packed into one
    /// buffer view without target (animation data), one accessor each.
    pub fn float_block(&mut self, parts: &[(&[f32], Type)]) -> Vec<Index<Accessor>> {
        let bytes: Vec<u8> = parts
            .iter()
            .flat_map(|(values, _)| values.iter().flat_map(|v| v.to_le_bytes()))
            .collect();
        let view = self.view(&bytes, None);
        let mut offset = 0;
        let mut accessors = Vec::with_capacity(parts.len());
        for (values, type_) in parts {
            let count = values.len() / type_.multiplicity();
            let mut accessor = self.accessor(view, count, ComponentType::F32, *type_);
            accessor.byte_offset = (offset > 0).then(|| USize64::from(offset));
            offset += 4 * values.len();
            accessors.push(Index::push(&mut self.root.accessors, accessor));
        }
        accessors
    }

    /// Triangle indices, as `u16` when the vertices allow it.
    fn indices(&mut self, indices: &[u32], vertices: usize) -> Index<Accessor> {
        let target = Some(Target::ElementArrayBuffer);
        let (view, component) = if vertices <= usize::from(u16::MAX) {
            let bytes: Vec<u8> = indices
                .iter()
                .flat_map(|&i| (i as u16).to_le_bytes())
                .collect();
            (self.view(&bytes, target), ComponentType::U16)
        } else {
            let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
            (self.view(&bytes, target), ComponentType::U32)
        };
        let accessor = self.accessor(view, indices.len(), component, Type::Scalar);
        Index::push(&mut self.root.accessors, accessor)
    }

    /// An accessor of `count` elements at the start of `view`, without bounds.
    fn accessor(
        &self,
        view: Index<View>,
        count: usize,
        component: ComponentType,
        type_: Type,
    ) -> Accessor {
        Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Checked::Valid(GenericComponentType(component)),
            extensions: None,
            extras: Default::default(),
            type_: Checked::Valid(type_),
            min: None,
            max: None,
            name: None,
            normalized: false,
            sparse: None,
        }
    }

    /// A dielectric (metallic 0) material of `rgba` colour.
    pub fn material(&mut self, name: &str, rgba: [f32; 4], roughness: f32) -> Index<Material> {
        let material = Material {
            pbr_metallic_roughness: PbrMetallicRoughness {
                base_color_factor: PbrBaseColorFactor(rgba),
                metallic_factor: StrengthFactor(0.0),
                roughness_factor: StrengthFactor(roughness),
                ..Default::default()
            },
            name: Some(name.to_owned()),
            ..Default::default()
        };
        Index::push(&mut self.root.materials, material)
    }

    /// A one-primitive triangle mesh; refused when a vertex is not finite as `f32`.
    pub fn mesh(
        &mut self,
        name: &str,
        mesh: &TriangleMesh,
        material: Index<Material>,
    ) -> Result<Index<Mesh>, SceneError> {
        self.mesh_in_variants(name, mesh, material, &[])
    }

    /// Declares the material variants `names` (glTF's `KHR_materials_variants`), numbered
    /// in their order.
    pub fn variants(&mut self, names: &[&str]) {
        let variants = names
            .iter()
            .map(|name| khr_materials_variants::Variant {
                name: (*name).to_owned(),
            })
            .collect();
        let extensions = self.root.extensions.get_or_insert_with(Default::default);
        extensions.khr_materials_variants = Some(KhrMaterialsVariants { variants });
        let used = "KHR_materials_variants".to_owned();
        if !self.root.extensions_used.contains(&used) {
            self.root.extensions_used.push(used);
        }
    }

    /// [`Builder::mesh`] with the material of each variant given (`(material, variant)`,
    /// variants as numbered by [`Builder::variants`]); `material` where none is given.
    pub fn mesh_in_variants(
        &mut self,
        name: &str,
        mesh: &TriangleMesh,
        material: Index<Material>,
        variants: &[(Index<Material>, u32)],
    ) -> Result<Index<Mesh>, SceneError> {
        let positions = to_f32(mesh.positions.iter().flat_map(|p| p.iter()).copied(), name)?;
        let normals = to_f32(
            mesh.normals.iter().flat_map(|n| {
                let u = n.normalize();
                [u.x, u.y, u.z]
            }),
            name,
        )?;
        let array = Some(Target::ArrayBuffer);
        let mut attributes = BTreeMap::new();
        let position_accessor = self.floats(&positions, Type::Vec3, true, array);
        attributes.insert(Checked::Valid(Semantic::Positions), position_accessor);
        let normal_accessor = self.floats(&normals, Type::Vec3, false, array);
        attributes.insert(Checked::Valid(Semantic::Normals), normal_accessor);
        let indices = self.indices(&mesh.indices, mesh.positions.len());
        let mappings: Vec<Mapping> = (variants.iter())
            .map(|(material, variant)| Mapping {
                material: material.value() as u32,
                variants: vec![*variant],
            })
            .collect();
        let primitive = Primitive {
            attributes,
            extensions: (!mappings.is_empty()).then_some(extensions::mesh::Primitive {
                khr_materials_variants: Some(extensions::mesh::KhrMaterialsVariants { mappings }),
            }),
            extras: Default::default(),
            indices: Some(indices),
            material: Some(material),
            mode: Checked::Valid(Mode::Triangles),
            targets: None,
        };
        let gltf_mesh = Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.to_owned()),
            primitives: vec![primitive],
            weights: None,
        };
        Ok(Index::push(&mut self.root.meshes, gltf_mesh))
    }

    /// Appends a node called `name`.
    pub fn node(&mut self, name: impl Into<String>, node: Node) -> Index<Node> {
        let node = Node {
            name: Some(name.into()),
            ..node
        };
        Index::push(&mut self.root.nodes, node)
    }

    /// Makes `child` the last child of `parent`.
    pub fn add_child(&mut self, parent: Index<Node>, child: Index<Node>) {
        if let Some(node) = self.root.nodes.get_mut(parent.value()) {
            node.children.get_or_insert_with(Vec::new).push(child);
        }
    }

    /// Appends an animation of the given channels and samplers.
    pub fn animation(&mut self, name: &str, channels: Vec<Channel>, samplers: Vec<Sampler>) {
        self.root.animations.push(Animation {
            extensions: None,
            extras: Default::default(),
            channels,
            name: Some(name.to_owned()),
            samplers,
        });
    }

    /// The `.glb` bytes of the document whose one scene shows `roots`.
    pub fn finish(mut self, roots: Vec<Index<Node>>) -> Result<Vec<u8>, SceneError> {
        let scene = Scene {
            extensions: None,
            extras: Default::default(),
            name: None,
            nodes: roots,
        };
        self.root.scene = Some(Index::push(&mut self.root.scenes, scene));
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        if !self.bin.is_empty() {
            self.root.buffers.push(Buffer {
                byte_length: USize64::from(self.bin.len()),
                name: None,
                uri: None,
                extensions: None,
                extras: Default::default(),
            });
        }
        let json = serde_json::to_value(&self.root)?;
        glb::pack(&serde_json::to_vec(&json)?, &self.bin)
    }
}

/// Per-component minimum and maximum of `width`-component elements.
fn bounds(values: &[f32], width: usize) -> (Vec<f32>, Vec<f32>) {
    let mut min = vec![f32::INFINITY; width];
    let mut max = vec![f32::NEG_INFINITY; width];
    for element in values.chunks_exact(width) {
        for (c, &v) in element.iter().enumerate() {
            min[c] = min[c].min(v);
            max[c] = max[c].max(v);
        }
    }
    (min, max)
}

/// Values as `f32`, refused when one is not finite (as `f32`).
fn to_f32(values: impl Iterator<Item = f64>, mesh: &str) -> Result<Vec<f32>, SceneError> {
    values
        .map(|v| {
            if finite32(v) {
                Ok(v as f32)
            } else {
                Err(SceneError::NonFinite {
                    scene: "robot".to_owned(),
                    what: format!("a vertex or normal of mesh '{mesh}'"),
                })
            }
        })
        .collect()
}
