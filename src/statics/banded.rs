//! Symmetric banded matrices and their Cholesky factorization: the linear algebra of one
//! Newton step. A cable node interacts with nodes at most two places away (a bending joint
//! couples three consecutive nodes), so with three coordinates per node the Hessian has a
//! half-bandwidth of 8 and a factorization costs `O(n · 8²)` instead of `O(n³)`.

use nalgebra::Matrix3;

/// Half-bandwidth in scalars: node blocks `(p, q)` with `|p − q| ≤ 2`, three coordinates each.
pub(crate) const HALF_BANDWIDTH: usize = 8;

/// Nodes coupled by one Hessian block at most this many places apart.
pub(crate) const NODE_REACH: usize = 2;

/// Lower band of a symmetric `n × n` matrix: `rows[i][k] = A(i, i − k)`.
#[derive(Debug, Clone, Default)]
pub(crate) struct SymmetricBand {
    rows: Vec<[f64; HALF_BANDWIDTH + 1]>,
}

/// The factorization met a pivot that is not positive: the matrix is not positive definite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotPositiveDefinite;

impl SymmetricBand {
    /// The zero matrix of order `n`.
    #[cfg(test)]
    pub(crate) fn zeros(n: usize) -> Self {
        Self {
            rows: vec![[0.0; HALF_BANDWIDTH + 1]; n],
        }
    }

    /// Order of the matrix.
    pub(crate) fn order(&self) -> usize {
        self.rows.len()
    }

    /// The zero matrix of order `n`, reusing the storage.
    pub(crate) fn reset(&mut self, n: usize) {
        self.rows.clear();
        self.rows.resize(n, [0.0; HALF_BANDWIDTH + 1]);
    }

    /// Adds the node block `(p, q)`, `p ≥ q`, of a symmetric matrix: `A(3p + a, 3q + b) +=
    /// block(a, b)` (for `p = q` the block must be symmetric; its lower triangle is used).
    #[inline]
    pub(crate) fn add_lower_block(&mut self, p: usize, q: usize, block: &Matrix3<f64>) {
        debug_assert!(p >= q && p - q <= NODE_REACH);
        let offset = 3 * (p - q);
        for a in 0..3 {
            let row = &mut self.rows[3 * p + a];
            let columns = if p == q { a + 1 } else { 3 };
            for b in 0..columns {
                row[offset + a - b] += block[(a, b)];
            }
        }
    }

    /// Adds one node block of a Hessian given as the sum of blocks for ordered node pairs:
    /// an off-diagonal block contributes half to `A(p, q)` and half, transposed, to
    /// `A(q, p)`, so it must be added for `(p, q)` and for `(q, p)`; a diagonal block
    /// contributes its symmetric part. Nodes must be at most [`NODE_REACH`] apart.
    #[cfg(test)]
    pub(crate) fn add_node_block(&mut self, p: usize, q: usize, block: &Matrix3<f64>) {
        debug_assert!(p.abs_diff(q) <= NODE_REACH);
        if p == q {
            for a in 0..3 {
                for b in 0..=a {
                    let i = 3 * p + a;
                    self.rows[i][a - b] += 0.5 * (block[(a, b)] + block[(b, a)]);
                }
            }
            return;
        }
        let (row_node, column_node, lower) = if p > q {
            (p, q, *block)
        } else {
            (q, p, block.transpose())
        };
        for a in 0..3 {
            for b in 0..3 {
                let (i, j) = (3 * row_node + a, 3 * column_node + b);
                self.rows[i][i - j] += 0.5 * lower[(a, b)];
            }
        }
    }

    /// Largest absolute diagonal entry (0 for an empty matrix).
    pub(crate) fn max_diagonal(&self) -> f64 {
        self.rows.iter().map(|r| r[0].abs()).fold(0.0, f64::max)
    }

    /// `y = A x`.
    #[cfg(test)]
    pub(crate) fn multiply(&self, x: &[f64]) -> Vec<f64> {
        let n = self.order();
        let mut y = vec![0.0; n];
        for i in 0..n {
            for k in 0..=HALF_BANDWIDTH.min(i) {
                let j = i - k;
                y[i] += self.rows[i][k] * x[j];
                if k > 0 {
                    y[j] += self.rows[i][k] * x[i];
                }
            }
        }
        y
    }

    /// `A + shift·I = L D Lᵀ` into `out` (its storage reused), with unit lower-triangular `L`
    /// in the band layout and diagonal `D`, without pivoting: also for indefinite matrices,
    /// whose inertia the signs of `D` give (Sylvester's law). `Err` when a pivot is below
    /// `tiny` in magnitude (relative to the largest diagonal entry), where the factorization
    /// without pivoting is unreliable.
    pub(crate) fn ldlt_into(
        &self,
        shift: f64,
        tiny: f64,
        out: &mut BandLdlt,
    ) -> Result<(), NotPositiveDefinite> {
        let n = self.order();
        let floor = tiny * (self.max_diagonal() + shift.abs()).max(f64::MIN_POSITIVE);
        let factor = &mut out.factor;
        factor.clear();
        factor.extend_from_slice(&self.rows);
        // D⁻¹: a row divides by the same pivots eight times.
        let inverse = &mut out.inverse_pivots;
        inverse.clear();
        inverse.resize(n, 0.0);
        out.negative = 0;
        for i in 0..n {
            let first = i.saturating_sub(HALF_BANDWIDTH);
            // w[j − first] = L(i, j) D(j): the products the rest of row i reuses.
            let mut w = [0.0; HALF_BANDWIDTH];
            let mut pivot = factor[i][0] + shift;
            for j in first..i {
                let row_j = &factor[j];
                let mut sum = factor[i][i - j];
                for k in first..j {
                    sum -= w[k - first] * row_j[j - k];
                }
                w[j - first] = sum;
                let l = sum * inverse[j];
                factor[i][i - j] = l;
                pivot -= l * sum;
            }
            if pivot.is_nan() || pivot.abs() < floor {
                return Err(NotPositiveDefinite);
            }
            if pivot < 0.0 {
                out.negative += 1;
            }
            inverse[i] = 1.0 / pivot;
            factor[i][0] = 1.0;
        }
        Ok(())
    }

    /// [`SymmetricBand::ldlt_into`] a new factorization, without shift.
    #[cfg(test)]
    pub(crate) fn ldlt(&self, tiny: f64) -> Result<BandLdlt, NotPositiveDefinite> {
        let mut out = BandLdlt::default();
        self.ldlt_into(0.0, tiny, &mut out).map(|()| out)
    }
}

/// The `L D Lᵀ` factorization of a [`SymmetricBand`] (see [`SymmetricBand::ldlt_into`]).
#[derive(Debug, Clone, Default)]
pub(crate) struct BandLdlt {
    /// Unit lower-triangular `L`, band layout (`factor[i][0]` = 1).
    factor: Vec<[f64; HALF_BANDWIDTH + 1]>,
    /// `D⁻¹`.
    inverse_pivots: Vec<f64>,
    /// Negative entries of `D`: the number of negative eigenvalues of the factored matrix.
    pub(crate) negative: usize,
}

impl BandLdlt {
    /// Solves `L D Lᵀ x = b` in place (`b` becomes `x`).
    pub(crate) fn solve_in_place(&self, b: &mut [f64]) {
        self.solve_many_in_place(&mut [b]);
    }

    /// Solves `L D Lᵀ x = b` for several right-hand sides at once, in place: one pass over
    /// the factor, the substitutions' dependency chains of the systems interleaved.
    pub(crate) fn solve_many_in_place(&self, systems: &mut [&mut [f64]]) {
        let n = self.factor.len();
        for i in 0..n {
            let reach = HALF_BANDWIDTH.min(i);
            let row = &self.factor[i][1..=reach];
            for b in systems.iter_mut() {
                let (before, rest) = b.split_at_mut(i);
                let sum: f64 = row
                    .iter()
                    .zip(before[i - reach..].iter().rev())
                    .map(|(l, x)| l * x)
                    .sum();
                rest[0] -= sum;
            }
        }
        for b in systems.iter_mut() {
            for (value, inverse) in b.iter_mut().zip(&self.inverse_pivots) {
                *value *= inverse;
            }
        }
        // Lᵀ by columns of L (rows of the band): each solved value is taken out of the ones
        // before it, reading the band row by row.
        for i in (0..n).rev() {
            let reach = HALF_BANDWIDTH.min(i);
            let row = &self.factor[i][1..=reach];
            for b in systems.iter_mut() {
                let (before, rest) = b.split_at_mut(i);
                let value = rest[0];
                for (l, x) in row.iter().zip(before[i - reach..].iter_mut().rev()) {
                    *x -= l * value;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// A symmetric positive definite banded matrix built from random-looking node blocks.
    fn example(nodes: usize) -> (SymmetricBand, DMatrix<f64>) {
        let n = 3 * nodes;
        let mut band = SymmetricBand::zeros(n);
        let mut dense = DMatrix::zeros(n, n);
        let value = |p: usize, q: usize, a: usize, b: usize| {
            (((7 * p + 3 * q + 5 * a + 11 * b) % 17) as f64 - 8.0) / 10.0
        };
        for p in 0..nodes {
            for q in p.saturating_sub(NODE_REACH)..=(p + NODE_REACH).min(nodes - 1) {
                let block = Matrix3::from_fn(|a, b| {
                    // A symmetric pair of blocks: (p, q) and (q, p) transposed.
                    let (lo, hi, x, y) = if p <= q { (p, q, a, b) } else { (q, p, b, a) };
                    value(lo, hi, x, y) + if p == q && a == b { 12.0 } else { 0.0 }
                });
                let block = if p == q {
                    0.5 * (block + block.transpose())
                } else {
                    block
                };
                band.add_node_block(p, q, &block);
                for a in 0..3 {
                    for b in 0..3 {
                        dense[(3 * p + a, 3 * q + b)] += 0.5 * block[(a, b)];
                        dense[(3 * q + b, 3 * p + a)] += 0.5 * block[(a, b)];
                    }
                }
            }
        }
        (band, dense)
    }

    /// Lower blocks added directly give the matrix the ordered-pair blocks give.
    #[test]
    fn lower_blocks_build_the_same_matrix() {
        let (band, _) = example(5);
        let mut lower = SymmetricBand::zeros(15);
        for p in 0..5_usize {
            for q in p.saturating_sub(NODE_REACH)..=p {
                let entry = |i: usize, j: usize| band.rows[i.max(j)][i.max(j) - i.min(j)];
                let block = Matrix3::from_fn(|a, b| entry(3 * p + a, 3 * q + b));
                lower.add_lower_block(p, q, &block);
            }
        }
        assert_eq!(lower.rows, band.rows);
    }

    #[test]
    fn band_product_matches_the_dense_matrix() {
        let (band, dense) = example(7);
        let x: Vec<f64> = (0..21).map(|i| (i as f64 * 0.37).sin()).collect();
        let expected = &dense * DVector::from_column_slice(&x);
        for (y, e) in band.multiply(&x).iter().zip(expected.iter()) {
            assert!((y - e).abs() < 1e-12);
        }
    }

    #[test]
    fn ldlt_solves_against_nalgebra_lu() {
        let (band, dense) = example(9);
        let b: Vec<f64> = (0..27).map(|i| (i as f64 * 1.3).cos()).collect();
        let mut x = b.clone();
        let factor = band.ldlt(1e-14).unwrap();
        assert_eq!(factor.negative, 0);
        factor.solve_in_place(&mut x);
        let reference = dense.lu().solve(&DVector::from_column_slice(&b)).unwrap();
        for (x, r) in x.iter().zip(reference.iter()) {
            assert!((x - r).abs() < 1e-12, "{x} vs {r}");
        }
    }

    /// An indefinite matrix: the factorization solves it and counts its negative eigenvalues
    /// as nalgebra's symmetric eigen-decomposition does.
    #[test]
    fn ldlt_of_an_indefinite_matrix_gives_its_inertia() {
        let (mut band, mut dense) = example(9);
        for (node, shift) in [(2, -14.0), (6, -13.0)] {
            band.add_node_block(node, node, &Matrix3::from_diagonal_element(shift));
            for a in 0..3 {
                dense[(3 * node + a, 3 * node + a)] += shift;
            }
        }
        let negative = dense
            .clone()
            .symmetric_eigen()
            .eigenvalues
            .iter()
            .filter(|v| **v < 0.0)
            .count();
        let factor = band.ldlt(1e-14).unwrap();
        assert!(negative > 0);
        assert_eq!(factor.negative, negative);
        let b: Vec<f64> = (0..27).map(|i| (i as f64 * 0.7).sin()).collect();
        let mut x = b.clone();
        factor.solve_in_place(&mut x);
        let reference = dense.lu().solve(&DVector::from_column_slice(&b)).unwrap();
        for (x, r) in x.iter().zip(reference.iter()) {
            assert!((x - r).abs() < 1e-9, "{x} vs {r}");
        }
    }

    #[test]
    fn a_zero_pivot_is_refused() {
        let mut band = SymmetricBand::zeros(6);
        band.add_node_block(0, 0, &Matrix3::identity());
        band.add_node_block(1, 1, &Matrix3::zeros());
        assert_eq!(band.ldlt(1e-12).err(), Some(NotPositiveDefinite));
    }
}
