//! Fuzzes the motion CSV reader with the bundled robot: any text must give a motion or an
//! error, never a panic.
#![no_main]

use cable_dict::robot::Robot;
use std::sync::OnceLock;

fn robot() -> &'static Robot {
    static ROBOT: OnceLock<Robot> = OnceLock::new();
    ROBOT.get_or_init(|| {
        let text = include_str!("../../robots/viper_s850/viper_s850.urdf");
        Robot::from_urdf_str(text, std::path::Path::new("viper_s850.urdf")).expect("bundled")
    })
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let path = std::path::Path::new("fuzz.csv");
        let _ = cable_dict::motion::Motion::from_csv_str(robot(), text, path);
    }
});
