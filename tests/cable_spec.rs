//! Cable files: the paper presets carry the paper's values (Table 3)
//! converted from per-joint springs to EI and GJ; the realistic presets load without a
//! plausibility warning while the paper's camera cable (23 400 kg/m³) and both paper cables'
//! GJ/EI ≈ 30 warn; every bad value is refused naming the file, the line and the field.

use cable_dict::cable::{CableSpec, DEFAULT_AXIAL_STIFFNESS_N, DEFAULT_SUB_SEGMENT_PITCH_M};
use std::path::Path;

fn bundled(name: &str) -> CableSpec {
    let path = crate::common::root().join("cables").join(name);
    CableSpec::from_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs()
}

#[test]
fn paper_presets_carry_the_papers_values_as_ei_and_gj() {
    // (file, diameter m, kg/m, kb, kt, min bend radius m); EI = kb · 10 mm, GJ = kt · 10 mm.
    let table = [
        ("smc_le_cp_3_paper.toml", 0.008, 0.260, 5.1e-2, 1.5, 0.048),
        ("gev_c6hf_paper.toml", 0.006, 0.662, 6.7e-2, 2.1, 0.060),
    ];
    for (file, diameter, mass, kb, kt, radius) in table {
        let cable = bundled(file);
        assert!(close(cable.diameter_m, diameter), "{file}");
        assert!(close(cable.mass_per_length_kg_m, mass), "{file}");
        assert!(close(cable.bending_stiffness_n_m2, kb * 0.010), "{file}");
        assert!(close(cable.torsion_stiffness_n_m2, kt * 0.010), "{file}");
        assert!(close(cable.bending_stiffness_nm_per_rad(), kb), "{file}");
        assert!(close(cable.torsion_stiffness_nm_per_rad(), kt), "{file}");
        assert!(close(cable.min_bend_radius_m, radius), "{file}");
        assert!(close(cable.sub_segment_pitch_m, 0.010), "{file}");
    }
}

/// Density by hand (m / (π d²/4)) and GJ/EI decide the warnings: the paper's values warn
/// (camera cable: both; SMC: the ratio only), the realistic presets do not.
#[test]
fn implausible_cables_warn_and_the_realistic_presets_do_not() {
    let density = |c: &CableSpec| {
        c.mass_per_length_kg_m / (std::f64::consts::PI * c.diameter_m.powi(2) / 4.0)
    };
    let camera = bundled("gev_c6hf_paper.toml");
    assert!(
        (density(&camera) - 23_413.0).abs() < 1.0,
        "{}",
        density(&camera)
    );
    let warnings = camera.plausibility_warnings();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(warnings[0].contains("23413 kg/m³"), "{warnings:?}");
    assert!(warnings[1].contains("GJ/EI = 31.34"), "{warnings:?}");
    let smc = bundled("smc_le_cp_3_paper.toml");
    let warnings = smc.plausibility_warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("GJ/EI = 29.41"), "{warnings:?}");
    for file in ["smc_le_cp_3.toml", "gev_c6hf.toml"] {
        let cable = bundled(file);
        assert!(cable.plausibility_warnings().is_empty(), "{file}");
        let ratio = cable.torsion_stiffness_n_m2 / cable.bending_stiffness_n_m2;
        assert!((0.67..2.0).contains(&ratio), "{file}: GJ/EI {ratio}");
        assert!((900.0..6000.0).contains(&density(&cable)), "{file}");
    }
}

const GOOD: &str = r#"name = "test cable"
diameter_mm = 8.0
mass_per_length_kg_m = 0.26
bending_stiffness_n_m2 = 6e-3
torsion_stiffness_n_m2 = 7.8e-3
min_bend_radius_mm = 48.0
sub_segment_pitch_mm = 10.0
axial_stiffness_n = 1.0e4
"#;

fn parse(text: &str) -> Result<CableSpec, String> {
    CableSpec::from_toml_str(text, Path::new("c.toml")).map_err(|e| e.to_string())
}

fn refusal(text: &str) -> String {
    parse(text).expect_err("must be refused")
}

/// The paper's per-joint springs are read with the file's pitch; the pitch and EA default
/// when left out; a file written by `to_toml` reads back to the same values.
#[test]
fn per_joint_springs_convert_and_defaults_apply() {
    let legacy = GOOD
        .replace(
            "bending_stiffness_n_m2 = 6e-3",
            "bending_stiffness_nm_per_rad = 0.3",
        )
        .replace("sub_segment_pitch_mm = 10.0", "sub_segment_pitch_mm = 20.0");
    let cable = parse(&legacy).unwrap();
    assert!(close(cable.bending_stiffness_n_m2, 0.3 * 0.020));
    assert!(close(cable.bending_stiffness_nm_per_rad(), 0.3));
    assert!(close(cable.torsion_stiffness_nm_per_rad(), 7.8e-3 / 0.020));
    let minimal = GOOD
        .replace("sub_segment_pitch_mm = 10.0\n", "")
        .replace("axial_stiffness_n = 1.0e4\n", "");
    let cable = parse(&minimal).unwrap();
    assert_eq!(cable.sub_segment_pitch_m, DEFAULT_SUB_SEGMENT_PITCH_M);
    assert_eq!(cable.axial_stiffness_n, DEFAULT_AXIAL_STIFFNESS_N);
    let round_trip = parse(&cable.to_toml("written by a test\n\nsecond line")).unwrap();
    assert_eq!(round_trip, cable);
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
            "bending_stiffness_n_m2 = 6e-3",
            "bending_stiffness_n_m2 = nan",
            4,
            "bending_stiffness_n_m2",
        ),
        (
            "torsion_stiffness_n_m2 = 7.8e-3",
            "torsion_stiffness_n_m2 = inf",
            5,
            "torsion_stiffness_n_m2",
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
    let tiny = refusal(&GOOD.replace("sub_segment_pitch_mm = 10.0", "sub_segment_pitch_mm = 1e-6"));
    assert!(
        tiny.starts_with("c.toml:7: `sub_segment_pitch_mm` = 0.000001 is outside 1 to 100 mm"),
        "«{tiny}»"
    );
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

/// Each stiffness exactly once; a per-joint spring only with its pitch.
#[test]
fn stiffness_given_twice_missing_or_without_its_pitch_is_refused() {
    let twice = refusal(&GOOD.replace(
        "bending_stiffness_n_m2 = 6e-3",
        "bending_stiffness_n_m2 = 6e-3\nbending_stiffness_nm_per_rad = 0.6",
    ));
    assert!(
        twice.contains("c.toml:5") && twice.contains("not both"),
        "«{twice}»"
    );
    let missing = refusal(&GOOD.replace("torsion_stiffness_n_m2 = 7.8e-3\n", ""));
    assert!(
        missing.contains("missing `torsion_stiffness_n_m2`"),
        "«{missing}»"
    );
    let no_pitch = refusal(
        &GOOD
            .replace(
                "bending_stiffness_n_m2 = 6e-3",
                "bending_stiffness_nm_per_rad = 0.6",
            )
            .replace("sub_segment_pitch_mm = 10.0\n", ""),
    );
    assert!(
        no_pitch.contains("c.toml:4") && no_pitch.contains("sub_segment_pitch_mm"),
        "«{no_pitch}»"
    );
}

#[test]
fn unknown_and_mistyped_keys_and_missing_files_are_refused() {
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

/// The cut allowances are optional lengths ≥ 0 in mm: absent they are `None` (never a silent
/// 0), given they are read in metres, and a negative or non-finite one is refused with its
/// line.
#[test]
fn cut_allowances_are_optional_lengths() {
    let cable = parse(GOOD).unwrap();
    assert_eq!(cable.tool_end_allowance_m, None);
    assert_eq!(cable.base_end_allowance_m, None);
    let with = format!("{GOOD}tool_end_allowance_mm = 40.0\nbase_end_allowance_mm = 0.0\n");
    let cable = parse(&with).unwrap();
    assert!(close(cable.tool_end_allowance_m.unwrap(), 0.040));
    assert_eq!(cable.base_end_allowance_m, Some(0.0));
    let lines = GOOD.lines().count();
    for bad in ["-5.0", "inf", "nan"] {
        let text = format!("{GOOD}tool_end_allowance_mm = {bad}\n");
        let message = refusal(&text);
        assert!(
            message.starts_with(&format!("c.toml:{}:", lines + 1))
                && message.contains("tool_end_allowance_mm"),
            "{message}"
        );
    }
}

/// The part number is the file's text, trimmed, for the installation sheet; an empty one, a
/// second line or more than 100 characters are refused naming the line and the key.
#[test]
fn a_part_number_is_one_short_line() {
    let base = std::fs::read_to_string(crate::common::root().join("cables/smc_le_cp_3.toml"))
        .expect("cable");
    let with = |value: &str| format!("{base}part_number = {value}\n");
    let source = Path::new("cable.toml");
    let cable = CableSpec::from_toml_str(&with("\" LE-CP-3-S \""), source).expect("loads");
    assert_eq!(cable.part_number.as_deref(), Some("LE-CP-3-S"));
    assert_eq!(bundled("smc_le_cp_3.toml").part_number, None);
    let lines = base.lines().count() + 1;
    for bad in ["\"\"", "\"a\\nb\"", &format!("\"{}\"", "x".repeat(101))] {
        let error = CableSpec::from_toml_str(&with(bad), source)
            .expect_err("refused")
            .to_string();
        assert!(error.contains("part_number"), "{error}");
        assert!(error.contains(&format!(":{lines}")), "{error}");
    }
}

/// A datasheet's limits: both bend radii, the torsion limit, the conductors' offset and a
/// rated life read in SI units and written back by `to_toml`; a file with the single older
/// radius keeps loading, that radius the fixed one and nothing else invented (the summary's
/// list of what is missing says so); contradictions are refused naming the line and key.
#[test]
fn a_datasheet_states_two_radii_a_torsion_limit_and_a_rated_life() {
    let sheet = GOOD.replace(
        "min_bend_radius_mm = 48.0\n",
        "min_bend_radius_fixed_mm = 32.0\nmin_bend_radius_flexing_mm = 80.0\n\
         torsion_limit_deg_per_m = 360.0\nconductor_offset_mm = 2.5\n",
    ) + "\n[rated_life]\ncycles = 5e6\nbend_radius_mm = 80.0\ntorsion_deg_per_m = 360.0\n";
    let cable = parse(&sheet).unwrap();
    assert!(close(cable.min_bend_radius_m, 0.032));
    let d = &cable.datasheet;
    assert!(close(d.min_bend_radius_flexing_m.unwrap(), 0.080));
    assert_eq!(d.torsion_limit_deg_per_m, Some(360.0));
    assert!(close(d.conductor_offset_m.unwrap(), 0.0025));
    let life = d.rated_life.unwrap();
    assert_eq!(life.cycles, 5e6);
    assert!(close(life.bend_radius_m.unwrap(), 0.080));
    assert_eq!(life.torsion_deg_per_m, Some(360.0));
    assert!(!life.exponent_stated);
    assert!(d.missing().is_empty(), "{:?}", d.missing());
    assert_eq!(parse(&cable.to_toml("")).unwrap(), cable);

    let older = parse(GOOD).unwrap();
    assert!(close(older.min_bend_radius_m, 0.048));
    assert_eq!(older.datasheet, Default::default());
    assert_eq!(older.datasheet.missing().len(), 3);

    let cases = [
        (
            sheet.replace(
                "min_bend_radius_flexing_mm = 80.0",
                "min_bend_radius_flexing_mm = 30.0",
            ),
            "c.toml:7",
            "min_bend_radius_flexing_mm",
        ),
        (
            sheet.replace("conductor_offset_mm = 2.5", "conductor_offset_mm = 4.0"),
            "c.toml:9",
            "conductor_offset_mm",
        ),
        (
            sheet.replace(
                "min_bend_radius_fixed_mm = 32.0\n",
                "min_bend_radius_fixed_mm = 32.0\nmin_bend_radius_mm = 48.0\n",
            ),
            "c.toml:7",
            "min_bend_radius_mm",
        ),
        (
            sheet
                .replace("bend_radius_mm = 80.0\n", "")
                .replace("torsion_deg_per_m = 360.0\n", ""),
            "c.toml:13",
            "neither",
        ),
        (
            sheet.replace("cycles = 5e6", "cycles = 0.5"),
            "c.toml:14",
            "rated_life.cycles",
        ),
        (
            sheet.replace(
                "torsion_limit_deg_per_m = 360.0",
                "torsion_limit_deg_per_m = -1.0",
            ),
            "c.toml:8",
            "torsion_limit_deg_per_m",
        ),
    ];
    for (text, line, key) in cases {
        let message = refusal(&text);
        assert!(
            message.contains(line) && message.contains(key),
            "«{message}»"
        );
    }
}
