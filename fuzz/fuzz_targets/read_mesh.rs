//! Fuzzes the STL mesh reader (binary and ASCII STL, the split into shells, the colliders
//! built from them) through a robot whose one link's collision is the mesh: any bytes must
//! give a robot or an error, never a panic or a hang.
#![no_main]

const URDF: &str = r#"<robot name="fuzz">
  <link name="base"/>
  <link name="arm"><collision><geometry><mesh filename="arm.stl"/></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"#;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let mesh = cable_dict::robot::MeshFile {
        uri: "arm.stl".into(),
        bytes: data.to_vec(),
    };
    let _ = cable_dict::robot::Robot::from_urdf_str_with_meshes(
        URDF,
        std::path::Path::new("fuzz.urdf"),
        &[mesh],
    );
});
