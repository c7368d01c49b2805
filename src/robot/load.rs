//! Turning a URDF document into a validated [`Robot`].

use super::collision::colliders_of_link;
use super::locate::{MAX_XML_DEPTH, first_problem, first_xacro_use, too_deep};
use super::mesh::{MeshFile, MeshSource};
use super::{Joint, JointDrive, JointKind, JointLimits, Link, Robot, RobotError};
use crate::pose::pose_from_xyz_rpy;
use nalgebra::{Unit, Vector3};
use std::collections::HashMap;
use std::path::Path;

/// A file named `*.xacro` is read like any other: refused at its first use of xacro, loaded
/// when it has none (it is then a URDF; xacro would output the same robot).
pub(super) fn from_file(path: &Path) -> Result<Robot, RobotError> {
    let text =
        crate::input::read_text(path, crate::input::URDF).map_err(|e| RobotError::file(path, e))?;
    from_str(&text, path, None)
}

/// The robot of URDF `text`; meshes from `embedded` when given, else from files next to
/// `source`.
pub(super) fn from_str(
    text: &str,
    source: &Path,
    embedded: Option<&[MeshFile]>,
) -> Result<Robot, RobotError> {
    if let Some((line, use_of_xacro)) = first_xacro_use(text) {
        return Err(RobotError::at_line(
            source,
            line,
            format!("{use_of_xacro}; {}", xacro_advice(source)),
        ));
    }
    if let Some(line) = too_deep(text) {
        return Err(RobotError::at_line(
            source,
            line,
            format!("elements nested more than {MAX_XML_DEPTH} deep: not a URDF robot description"),
        ));
    }
    let urdf = urdf_rs::read_from_string(text).map_err(|e| match first_problem(text) {
        Some((line, problem)) => RobotError::at_line(source, line, problem),
        None => RobotError::file(source, format!("not a valid URDF document: {e}")),
    })?;
    let meshes = match embedded {
        Some(files) => MeshSource::Embedded(files),
        None => MeshSource::Files(folder_of(source)),
    };
    Builder {
        text,
        source,
        meshes,
    }
    .build(&urdf)
}

/// The folder `path` is in: "." for a bare file name (whose parent is the empty path, which
/// cannot be canonicalized to find the folders above it).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder,
        _ => Path::new("."),
    }
}

/// What to do with a xacro file: how to expand it without ROS, with PyPI's xacro or, for
/// `$(find pkg)`, the repository's script (both named after `source`), and where `$(find pkg)`
/// and `package://` resolution is documented.
fn xacro_advice(source: &Path) -> String {
    let name = source
        .file_name()
        .map_or_else(|| "robot.urdf.xacro".into(), |n| n.to_string_lossy());
    let expanded = expanded_name(&name);
    let (name, expanded) = (shell_word(&name), shell_word(&expanded));
    format!(
        "this is a xacro file, not a URDF: expand it with PyPI's xacro, no ROS needed \
         (`pip install xacro`, then `xacro {name} > {expanded}`, adding `name:=value` for each \
         argument it needs), and point the setup's `robot` (or the command) at {expanded}; if \
         it or a file it includes uses `$(find pkg)`, which PyPI's xacro resolves only with ROS, \
         run `scripts/expand-xacro.sh {name} {expanded}` (cable-dict's repository) instead; how \
         `$(find pkg)` and `package://` paths resolve: docs/robots.md, \"Xacro packages\""
    )
}

/// The name to expand the xacro file `name` into: `robot.urdf.xacro` and `robot.xacro` into
/// `robot.urdf`; any other name (a `.urdf` that uses xacro) into `….expanded.urdf`, never
/// itself, which the shell would empty before xacro reads it.
fn expanded_name(name: &str) -> String {
    let lower = name.to_ascii_lowercase();
    let stem_len = |suffix: &str| {
        (lower.len() > suffix.len() && lower.ends_with(suffix)).then(|| name.len() - suffix.len())
    };
    if let Some(len) = stem_len(".urdf.xacro").or_else(|| stem_len(".xacro")) {
        format!("{}.urdf", &name[..len])
    } else if let Some(len) = stem_len(".urdf") {
        format!("{}.expanded.urdf", &name[..len])
    } else {
        format!("{name}.expanded.urdf")
    }
}

/// `word` as one POSIX shell word: as it is when it holds only characters that need no
/// quoting, else in single quotes.
fn shell_word(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "._-+,:=@%/".contains(c);
    if !word.is_empty() && word.chars().all(plain) {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

/// 1-based line of the first `<tag … name="name"` in `text`, for error locations.
fn element_line(text: &str, tag: &str, name: &str) -> Option<usize> {
    let opening = format!("<{tag}");
    let mut from = 0;
    while let Some(found) = text[from..].find(&opening) {
        let start = from + found;
        let end = text[start..].find('>').map_or(text.len(), |e| start + e);
        let attributes = &text[start + opening.len()..end];
        let named = [format!("name=\"{name}\""), format!("name='{name}'")]
            .iter()
            .any(|pattern| attributes.contains(pattern.as_str()));
        if named {
            return Some(text[..start].matches('\n').count() + 1);
        }
        from = end;
    }
    None
}

struct Builder<'a> {
    text: &'a str,
    source: &'a Path,
    meshes: MeshSource<'a>,
}

impl Builder<'_> {
    fn error(&self, tag: &str, name: &str, problem: impl Into<String>) -> RobotError {
        RobotError::element(
            self.source,
            element_line(self.text, tag, name),
            format!("<{tag} name=\"{name}\">"),
            problem,
        )
    }

    fn build(&self, urdf: &urdf_rs::Robot) -> Result<Robot, RobotError> {
        let link_index = self.index_links(urdf)?;
        let parent_joint = self.parent_joints(urdf, &link_index)?;
        let link_order = self.topological_links(urdf, &link_index, &parent_joint)?;
        let mut new_link_of = vec![0; urdf.links.len()];
        for (new, &old) in link_order.iter().enumerate() {
            new_link_of[old] = new;
        }
        // Joints follow their child links, so parents come before children.
        let joint_order: Vec<usize> = link_order[1..]
            .iter()
            .map(|old_link| parent_joint[old_link])
            .collect();
        let actuated = actuated_in_document_order(urdf, &joint_order);
        let joints = joint_order
            .iter()
            .map(|&j| self.joint(urdf, j, &link_index, &new_link_of, &actuated))
            .collect::<Result<Vec<_>, _>>()?;
        let (links, mesh_files) = self.links(urdf, &link_order, &joints)?;
        if actuated.is_empty() {
            return Err(RobotError::file(
                self.source,
                "the robot has no movable joint (revolute, continuous or prismatic)",
            ));
        }
        Ok(Robot {
            name: urdf.name.clone(),
            source: self.source.to_path_buf(),
            links,
            joints,
            actuated: actuated.iter().map(|(_, new)| *new).collect(),
            mesh_files,
        })
    }

    fn index_links(&self, urdf: &urdf_rs::Robot) -> Result<HashMap<String, usize>, RobotError> {
        if urdf.links.is_empty() {
            return Err(RobotError::file(self.source, "the URDF has no <link>"));
        }
        let mut index = HashMap::new();
        for (i, link) in urdf.links.iter().enumerate() {
            if index.insert(link.name.clone(), i).is_some() {
                return Err(self.error("link", &link.name, "a second link has this name"));
            }
        }
        let mut joint_names = HashMap::new();
        for joint in &urdf.joints {
            if joint_names.insert(joint.name.as_str(), ()).is_some() {
                return Err(self.error("joint", &joint.name, "a second joint has this name"));
            }
        }
        Ok(index)
    }

    /// For each link (by URDF index) that is a joint's child, that joint's URDF index.
    fn parent_joints(
        &self,
        urdf: &urdf_rs::Robot,
        link_index: &HashMap<String, usize>,
    ) -> Result<HashMap<usize, usize>, RobotError> {
        let mut parent_joint = HashMap::new();
        for (j, joint) in urdf.joints.iter().enumerate() {
            for (role, link) in [("parent", &joint.parent.link), ("child", &joint.child.link)] {
                if !link_index.contains_key(link) {
                    let problem = format!("its {role} link '{link}' is not defined");
                    return Err(self.error("joint", &joint.name, problem));
                }
            }
            if let Some(previous) = parent_joint.insert(link_index[&joint.child.link], j) {
                let problem = format!(
                    "link '{}' is already the child of joint '{}'; a link has one parent",
                    joint.child.link, urdf.joints[previous].name
                );
                return Err(self.error("joint", &joint.name, problem));
            }
        }
        Ok(parent_joint)
    }

    /// URDF link indices in depth-first order from the single root, children in document order.
    fn topological_links(
        &self,
        urdf: &urdf_rs::Robot,
        link_index: &HashMap<String, usize>,
        parent_joint: &HashMap<usize, usize>,
    ) -> Result<Vec<usize>, RobotError> {
        let roots: Vec<usize> = (0..urdf.links.len())
            .filter(|l| !parent_joint.contains_key(l))
            .collect();
        let root = match roots.as_slice() {
            [root] => *root,
            [] => {
                return Err(RobotError::file(
                    self.source,
                    "every link has a parent joint, so the joints form a cycle; \
                     a robot needs one root link",
                ));
            }
            several => {
                let names: Vec<&str> = several
                    .iter()
                    .map(|&l| urdf.links[l].name.as_str())
                    .collect();
                return Err(RobotError::file(
                    self.source,
                    format!(
                        "links {} have no parent joint; a robot must be one tree with one root",
                        names.join(", ")
                    ),
                ));
            }
        };
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); urdf.links.len()];
        for joint in &urdf.joints {
            children[link_index[&joint.parent.link]].push(link_index[&joint.child.link]);
        }
        let mut order = Vec::with_capacity(urdf.links.len());
        let mut stack = vec![root];
        while let Some(link) = stack.pop() {
            order.push(link);
            stack.extend(children[link].iter().rev());
        }
        if order.len() < urdf.links.len() {
            let lost = (0..urdf.links.len())
                .find(|l| !order.contains(l))
                .unwrap_or(0);
            let name = &urdf.links[lost].name;
            return Err(self.error(
                "link",
                name,
                "is part of a cycle of joints, unreachable from the root",
            ));
        }
        Ok(order)
    }

    fn joint(
        &self,
        urdf: &urdf_rs::Robot,
        j: usize,
        link_index: &HashMap<String, usize>,
        new_link_of: &[usize],
        actuated: &[(usize, usize)],
    ) -> Result<Joint, RobotError> {
        let joint = &urdf.joints[j];
        let fail = |problem: String| self.error("joint", &joint.name, problem);
        let kind = joint_kind(&joint.joint_type).ok_or_else(|| {
            fail(format!(
                "joint type {:?} is not supported (use revolute, continuous, prismatic or fixed)",
                joint.joint_type
            ))
        })?;
        let xyz = joint.origin.xyz.0;
        let rpy = joint.origin.rpy.0;
        if xyz.iter().chain(rpy.iter()).any(|v| !v.is_finite()) {
            return Err(fail("<origin> has a non-finite value".into()));
        }
        let axis = self.axis(joint, kind)?;
        Ok(Joint {
            name: joint.name.clone(),
            kind,
            parent_link: new_link_of[link_index[&joint.parent.link]],
            child_link: new_link_of[link_index[&joint.child.link]],
            origin: pose_from_xyz_rpy(xyz, rpy),
            axis,
            limits: self.limits(joint, kind)?,
            drive: self.drive(urdf, j, kind, actuated)?,
        })
    }

    fn axis(
        &self,
        joint: &urdf_rs::Joint,
        kind: JointKind,
    ) -> Result<Unit<Vector3<f64>>, RobotError> {
        let axis = Vector3::from(joint.axis.xyz.0);
        if kind == JointKind::Fixed {
            return Ok(Vector3::x_axis());
        }
        Unit::try_new(axis, 1e-12)
            .filter(|a| a.iter().all(|v| v.is_finite()))
            .ok_or_else(|| {
                self.error(
                    "joint",
                    &joint.name,
                    format!("<axis xyz> {axis:?} is not a usable direction"),
                )
            })
    }

    fn limits(
        &self,
        joint: &urdf_rs::Joint,
        kind: JointKind,
    ) -> Result<Option<JointLimits>, RobotError> {
        if !matches!(kind, JointKind::Revolute | JointKind::Prismatic) {
            return Ok(None);
        }
        let limit = &joint.limit;
        let fail = |problem: String| self.error("joint", &joint.name, problem);
        if limit.lower.is_nan() || limit.upper.is_nan() {
            return Err(fail("<limit> lower/upper is not a number".into()));
        }
        if limit.lower >= limit.upper {
            return Err(fail(format!(
                "<limit> range is empty (lower {} ≥ upper {}); is the <limit> element missing?",
                limit.lower, limit.upper
            )));
        }
        let velocity =
            (limit.velocity.is_finite() && limit.velocity > 0.0).then_some(limit.velocity);
        Ok(Some(JointLimits {
            lower: limit.lower,
            upper: limit.upper,
            velocity,
        }))
    }

    fn drive(
        &self,
        urdf: &urdf_rs::Robot,
        j: usize,
        kind: JointKind,
        actuated: &[(usize, usize)],
    ) -> Result<JointDrive, RobotError> {
        let joint = &urdf.joints[j];
        if kind == JointKind::Fixed {
            return Ok(JointDrive::None);
        }
        let vector_index = |urdf_joint: usize| actuated.iter().position(|&(u, _)| u == urdf_joint);
        let Some(mimic) = &joint.mimic else {
            return Ok(JointDrive::Actuated {
                index: vector_index(j).unwrap_or_default(),
            });
        };
        let target = urdf.joints.iter().position(|o| o.name == mimic.joint);
        let Some(index) = target.and_then(vector_index) else {
            let problem = format!(
                "<mimic joint=\"{}\"> must name an actuated joint (not fixed, not itself a mimic)",
                mimic.joint
            );
            return Err(self.error("joint", &joint.name, problem));
        };
        let multiplier = mimic.multiplier.unwrap_or(1.0);
        let offset = mimic.offset.unwrap_or(0.0);
        if !multiplier.is_finite() || !offset.is_finite() {
            return Err(self.error(
                "joint",
                &joint.name,
                "<mimic> multiplier/offset is not finite",
            ));
        }
        Ok(JointDrive::Mimic {
            index,
            multiplier,
            offset,
        })
    }

    fn links(
        &self,
        urdf: &urdf_rs::Robot,
        link_order: &[usize],
        joints: &[Joint],
    ) -> Result<(Vec<Link>, Vec<MeshFile>), RobotError> {
        let mut files = Vec::new();
        let links = link_order
            .iter()
            .enumerate()
            .map(|(new, &old)| {
                let urdf_link = &urdf.links[old];
                let colliders = colliders_of_link(urdf_link, self.meshes, &mut files)
                    .map_err(|problem| self.error("link", &urdf_link.name, problem))?;
                Ok(Link {
                    name: urdf_link.name.clone(),
                    parent_joint: joints.iter().position(|j| j.child_link == new),
                    colliders,
                })
            })
            .collect::<Result<Vec<_>, RobotError>>()?;
        Ok((links, files))
    }
}

fn joint_kind(kind: &urdf_rs::JointType) -> Option<JointKind> {
    match kind {
        urdf_rs::JointType::Revolute => Some(JointKind::Revolute),
        urdf_rs::JointType::Continuous => Some(JointKind::Continuous),
        urdf_rs::JointType::Prismatic => Some(JointKind::Prismatic),
        urdf_rs::JointType::Fixed => Some(JointKind::Fixed),
        _ => None,
    }
}

/// `(URDF joint index, topological joint index)` of each actuated joint, in document order.
fn actuated_in_document_order(urdf: &urdf_rs::Robot, joint_order: &[usize]) -> Vec<(usize, usize)> {
    urdf.joints
        .iter()
        .enumerate()
        .filter(|(_, j)| j.mimic.is_none())
        .filter(|(_, j)| joint_kind(&j.joint_type).is_some_and(|k| k != JointKind::Fixed))
        .filter_map(|(u, _)| joint_order.iter().position(|&o| o == u).map(|new| (u, new)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::element_line;

    #[test]
    fn element_line_finds_the_named_element() {
        let text = "<robot>\n <link name=\"a\"/>\n <joint name='j' type=\"fixed\">\n</robot>";
        assert_eq!(element_line(text, "link", "a"), Some(2));
        assert_eq!(element_line(text, "joint", "j"), Some(3));
        assert_eq!(element_line(text, "joint", "a"), None);
    }
}
