//! Errors of setup loading: the file, the line, the key and the problem.

use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A setup file that cannot be used.
///
/// Displayed as `file:line: key: problem`; the line and the key are left out where they are
/// not known (a file that cannot be read, a TOML syntax error that names no key).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{}{}{}: {problem}",
    file.display(),
    line.map(|l| format!(":{l}")).unwrap_or_default(),
    key.as_ref().map(|k| format!(": {k}")).unwrap_or_default()
)]
pub struct SetupError {
    /// The setup file.
    pub file: PathBuf,
    /// 1-based line of the offending value or table, when known.
    pub line: Option<usize>,
    /// Path of the offending key, e.g. `guides[1].link` (array indices 0-based).
    pub key: Option<String>,
    /// What is wrong.
    pub problem: String,
}

/// The text of the file being loaded, to turn byte spans into located errors.
#[derive(Clone, Copy)]
pub(super) struct Source<'a> {
    pub file: &'a Path,
    pub text: &'a str,
    /// Byte offset of every `\n` of `text`, so that a line is found by bisection: a
    /// catalogue of 10⁵ entries, each located, would otherwise rescan the file 10⁵ times.
    pub newlines: &'a [usize],
}

/// The byte offsets of the `\n` of `text`, for [`Source::newlines`].
pub(super) fn newline_offsets(text: &str) -> Vec<usize> {
    text.bytes()
        .enumerate()
        .filter(|&(_, b)| b == b'\n')
        .map(|(i, _)| i)
        .collect()
}

impl Source<'_> {
    /// The three numbers of `value`, refused (at `key`) unless all are finite.
    pub fn finite3(
        &self,
        value: &Spanned<[f64; 3]>,
        key: impl Into<String>,
    ) -> Result<[f64; 3], SetupError> {
        let v = *value.get_ref();
        if v.iter().all(|x| x.is_finite()) {
            Ok(v)
        } else {
            Err(self.error(
                value.span(),
                key,
                format!("{v:?} must be three finite numbers"),
            ))
        }
    }

    /// An error at the value whose byte span is `span`.
    pub fn error(
        &self,
        span: Range<usize>,
        key: impl Into<String>,
        problem: impl Into<String>,
    ) -> SetupError {
        SetupError {
            file: self.file.to_path_buf(),
            line: Some(self.line_of(span.start)),
            key: Some(key.into()),
            problem: problem.into(),
        }
    }

    /// 1-based line number of a byte offset.
    pub fn line_of(&self, offset: usize) -> usize {
        self.newlines.partition_point(|&n| n < offset) + 1
    }

    /// A TOML syntax or shape error (unknown or missing key, wrong type). The key is the
    /// table the error is in, when the line is known and inside one (`thresholds`,
    /// `guides[1]`); the message itself names the field.
    pub fn toml_error(&self, error: &toml::de::Error) -> SetupError {
        let line = error.span().map(|s| self.line_of(s.start));
        SetupError {
            file: self.file.to_path_buf(),
            line,
            key: line.and_then(|l| enclosing_table(self.text, l)),
            problem: error.message().trim_end().to_string(),
        }
    }
}

/// The `[table]` or `[[array]]` header at or above 1-based `line`, as `table` or
/// `array[index]` (0-based index among the headers of that array so far).
fn enclosing_table(text: &str, line: usize) -> Option<String> {
    let lines: Vec<&str> = text.lines().take(line).collect();
    let (at, name, array) = lines
        .iter()
        .enumerate()
        .rev()
        .find_map(|(i, l)| header(l).map(|(name, array)| (i, name, array)))?;
    if !array {
        return Some(name.to_string());
    }
    let index = lines[..at]
        .iter()
        .filter(|l| header(l) == Some((name, true)))
        .count();
    Some(format!("{name}[{index}]"))
}

/// `Some((name, is_array))` for a header line `[name]` or `[[name]]` (comments allowed).
fn header(line: &str) -> Option<(&str, bool)> {
    let code = line.split('#').next().unwrap_or("").trim();
    let (inner, array) = match code.strip_prefix("[[") {
        Some(rest) => (rest.strip_suffix("]]")?, true),
        None => (code.strip_prefix('[')?.strip_suffix(']')?, false),
    };
    let name = inner.trim();
    let plain = |c: char| c.is_ascii_alphanumeric() || "_-.".contains(c);
    (!name.is_empty() && name.chars().all(plain)).then_some((name, array))
}
