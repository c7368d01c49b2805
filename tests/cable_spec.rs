//! Cable files: the bundled specs carry the paper's values (Table 3, restated in DESIGN §3.3)
//! and every bad value is refused naming the file, the line and the field.

use cable_dict::cable::CableSpec;
use std::path::Path;

fn bundled(name: &str) -> CableSpec {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cables")
        .join(name);
    CableSpec::from_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn bundled_cables_carry_the_papers_values() {
    // (file, diameter m, kg/m, kb, kt, min bend radius m)
    let table = [
        ("smc_le_cp_3_paper.toml", 0.008, 0.260, 5.1e-2, 1.5, 0.048),
        ("gev_c6hf_paper.toml", 0.006, 0.662, 6.7e-2, 2.1, 0.060),
    ];
    for (file, diameter, mass, kb, kt, radius) in table {
        let cable = bundled(file);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        assert!(close(cable.diameter_m, diameter), "{file}");
        assert!(close(cable.mass_per_length_kg_m, mass), "{file}");
        assert!(close(cable.bending_stiffness_nm_per_rad, kb), "{file}");
        assert!(close(cable.torsion_stiffness_nm_per_rad, kt), "{file}");
        assert!(close(cable.min_bend_radius_m, radius), "{file}");
        assert!(close(cable.sub_segment_pitch_m, 0.010), "{file}");
        // Continuum stiffness of the discrete model: EI = kb · l_ss.
        assert!(close(cable.bending_rigidity_nm2(), kb * 0.010), "{file}");
        assert!(close(cable.torsional_rigidity_nm2(), kt * 0.010), "{file}");
    }
}

const GOOD: &str = r#"name = "test cable"
diameter_mm = 8.0
mass_per_length_kg_m = 0.26
bending_stiffness_nm_per_rad = 0.051
torsion_stiffness_nm_per_rad = 1.5
min_bend_radius_mm = 48.0
sub_segment_pitch_mm = 10.0
axial_stiffness_n = 1.0e4
"#;

fn refusal(text: &str) -> String {
    CableSpec::from_toml_str(text, Path::new("c.toml"))
        .expect_err("must be refused")
        .to_string()
}

#[test]
fn non_positive_and_non_finite_values_are_refused_with_field_and_line() {
    let cases = [
        ("diameter_mm = 8.0", "diameter_mm = 0.0", 2, "diameter_mm"),
        (
            "mass_per_length_kg_m = 0.26",
            "mass_per_length_kg_m = -0.26",
            3,
            "mass_per_length_kg_m",
        ),
        (
            "bending_stiffness_nm_per_rad = 0.051",
            "bending_stiffness_nm_per_rad = nan",
            4,
            "bending_stiffness_nm_per_rad",
        ),
        (
            "torsion_stiffness_nm_per_rad = 1.5",
            "torsion_stiffness_nm_per_rad = inf",
            5,
            "torsion_stiffness_nm_per_rad",
        ),
        (
            "min_bend_radius_mm = 48.0",
            "min_bend_radius_mm = -inf",
            6,
            "min_bend_radius_mm",
        ),
        (
            "sub_segment_pitch_mm = 10.0",
            "sub_segment_pitch_mm = 0",
            7,
            "sub_segment_pitch_mm",
        ),
        (
            "axial_stiffness_n = 1.0e4",
            "axial_stiffness_n = -1",
            8,
            "axial_stiffness_n",
        ),
    ];
    for (good, bad, line, field) in cases {
        let message = refusal(&GOOD.replace(good, bad));
        assert!(
            message.starts_with(&format!("c.toml:{line}: `{field}`")),
            "«{message}»"
        );
        assert!(
            message.contains("must be a finite number > 0"),
            "«{message}»"
        );
    }
}

#[test]
fn missing_unknown_and_mistyped_keys_are_refused() {
    let missing = refusal(&GOOD.replace("min_bend_radius_mm = 48.0\n", ""));
    assert!(
        missing.contains("c.toml") && missing.contains("min_bend_radius_mm"),
        "«{missing}»"
    );
    let typo = refusal(&GOOD.replace("diameter_mm", "diametre_mm"));
    assert!(
        typo.contains("c.toml:2") && typo.contains("diametre_mm"),
        "«{typo}»"
    );
    let text = refusal(&GOOD.replace("= 48.0", "= \"48\""));
    assert!(text.contains("c.toml:6"), "«{text}»");
    let unreadable = CableSpec::from_file("no/such/cable.toml")
        .expect_err("missing file")
        .to_string();
    assert!(
        unreadable.contains("no/such/cable.toml") && unreadable.contains("cannot read"),
        "«{unreadable}»"
    );
}
