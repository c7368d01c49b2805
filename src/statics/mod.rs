//! Static equilibrium of the discrete cable (work in progress).
