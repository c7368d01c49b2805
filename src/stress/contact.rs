//! Clearance between the cable and the robot's links (work in progress).
