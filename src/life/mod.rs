//! How long the cable lasts: the fatigue of its conductors over the cycles of a motion.
//!
//! Every point of the cable bends and twists back and forth as the motion repeats. The
//! history of each is counted into cycles ([`rainflow`], ASTM E1049), each cycle's damage is
//! the reciprocal of the cycles to failure at its range on the cable's life curve
//! ([`curve`]), and the damages add up (Miner's rule): a point fails when they reach 1.

pub mod curve;
pub mod damage;
pub mod estimate;
pub mod rainflow;
