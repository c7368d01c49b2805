//! Plain-text tables for the terminal whose columns are as wide as their widest cell, so that
//! long link, joint or clamp names from a robot description never shift the columns after
//! them.

use std::fmt;

/// How a column's cells are aligned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Align {
    /// Text: padded on the right.
    Left,
    /// Numbers: padded on the left.
    Right,
}

/// A table: a header row, then rows of as many cells, each line indented by `indent`.
#[derive(Debug, Clone)]
pub struct TextTable {
    indent: usize,
    columns: Vec<(String, Align)>,
    rows: Vec<Vec<String>>,
}

impl TextTable {
    /// An empty table with these column titles and alignments.
    pub fn new(indent: usize, columns: &[(&str, Align)]) -> TextTable {
        TextTable {
            indent,
            columns: columns
                .iter()
                .map(|(title, align)| (title.to_string(), *align))
                .collect(),
            rows: Vec::new(),
        }
    }

    /// Adds a row; missing cells are empty, extra ones are dropped.
    pub fn row(&mut self, cells: Vec<String>) {
        let mut cells = cells;
        cells.resize(self.columns.len(), String::new());
        self.rows.push(cells);
    }

    /// The width (characters) of column `k`.
    fn width(&self, k: usize) -> usize {
        self.rows
            .iter()
            .map(|row| row[k].chars().count())
            .chain(std::iter::once(self.columns[k].0.chars().count()))
            .max()
            .unwrap_or(0)
    }

    fn write_line(&self, f: &mut fmt::Formatter<'_>, cells: &[&str]) -> fmt::Result {
        let mut line = " ".repeat(self.indent);
        for (k, cell) in cells.iter().enumerate() {
            if k > 0 {
                line.push(' ');
            }
            let pad = " ".repeat(self.width(k) - cell.chars().count());
            match self.columns[k].1 {
                Align::Left => {
                    line.push_str(cell);
                    line.push_str(&pad);
                }
                Align::Right => {
                    line.push_str(&pad);
                    line.push_str(cell);
                }
            }
        }
        writeln!(f, "{}", line.trim_end())
    }
}

impl fmt::Display for TextTable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let titles: Vec<&str> = self.columns.iter().map(|(t, _)| t.as_str()).collect();
        self.write_line(f, &titles)?;
        for row in &self.rows {
            let cells: Vec<&str> = row.iter().map(String::as_str).collect();
            self.write_line(f, &cells)?;
        }
        Ok(())
    }
}

/// `value` with `digits` decimals, never as a negative zero (`-0.0` is `0.0`: a value that
/// rounds to zero has no sign worth showing).
pub fn decimal(value: f64, digits: usize) -> String {
    let text = format!("{value:.digits$}");
    match text.strip_prefix('-') {
        Some(magnitude) if magnitude.chars().all(|c| c == '0' || c == '.') => magnitude.to_string(),
        _ => text,
    }
}

/// A count in words: `105.2 million` from a million up, else whole (`350697`); `no end` for
/// an infinite one.
pub fn count_words(n: f64) -> String {
    if !n.is_finite() {
        "no end".to_string()
    } else if n >= 1e6 {
        format!("{} million", decimal(n / 1e6, 1))
    } else {
        decimal(n, 0)
    }
}

/// `values` each to `digits` decimals ([`decimal`]), comma-separated: `-156.3, 48.2, 71.2`.
pub fn decimals(values: &[f64], digits: usize) -> String {
    let texts: Vec<String> = values.iter().map(|&v| decimal(v, digits)).collect();
    texts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_that_rounds_to_zero_has_no_sign() {
        assert_eq!(decimal(-0.0, 1), "0.0");
        assert_eq!(decimal(-0.04, 1), "0.0");
        assert_eq!(decimal(-0.05001, 1), "-0.1");
        assert_eq!(decimal(12.345, 2), "12.35");
        assert_eq!(decimal(-3.0, 0), "-3");
    }

    #[test]
    fn columns_are_as_wide_as_their_widest_cell() {
        let mut table = TextTable::new(2, &[("link", Align::Left), ("mm", Align::Right)]);
        table.row(vec!["wrist_3_link_with_a_long_name".into(), "5".into()]);
        table.row(vec!["l→4".into(), "120".into()]);
        let text = table.to_string();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "  link                           mm");
        assert_eq!(lines[1], "  wrist_3_link_with_a_long_name   5");
        assert_eq!(lines[2], "  l→4                           120");
        // Every line ends its last column at the same character.
        let ends: Vec<usize> = lines.iter().map(|l| l.chars().count()).collect();
        assert!(ends.iter().all(|&e| e == ends[0]), "{ends:?}");
    }
}
