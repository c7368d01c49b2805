//! Dynamics of the discrete cable in rapier3d (work in progress).
