//! Strings from inputs (names in setups, URDFs and dictionaries, file names) shown safely:
//! on a terminal, in HTML or SVG, and in Markdown. A name is shown as written, never obeyed:
//! `<img onerror=…>` stays text on a page, an ANSI escape sequence stays text on a terminal.
//! In JSON, serde escapes the control characters below U+0020; [`json`] escapes the others a
//! terminal would obey.

use std::borrow::Cow;
use std::fmt::Write;

/// `text` for a terminal: control characters other than newline and tab (ANSI escape
/// sequences start with one), and the invisible characters that reorder text (bidirectional
/// overrides and isolates), written as `\u{…}`.
pub fn terminal(text: &str) -> Cow<'_, str> {
    with_hidden_written(text, |shown, code| {
        let _ = write!(shown, "\\u{{{code:x}}}");
    })
}

/// Serialized JSON with every character a terminal would hide written as a `\uXXXX`
/// escape (serde escapes only those below U+0020), so that printing it needs no other care
/// and it stays valid JSON.
pub fn json(serialized: String) -> String {
    // Every such character lies in the Basic Multilingual Plane: one escape each.
    let escaped = with_hidden_written(&serialized, |shown, code| {
        let _ = write!(shown, "\\u{code:04x}");
    });
    match escaped {
        Cow::Borrowed(_) => serialized,
        Cow::Owned(escaped) => escaped,
    }
}

/// `text` with each character a terminal would hide replaced by what `write_code` writes for
/// its code point.
fn with_hidden_written(text: &str, write_code: impl Fn(&mut String, u32)) -> Cow<'_, str> {
    if !text.chars().any(hidden_on_terminal) {
        return Cow::Borrowed(text);
    }
    let mut shown = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if hidden_on_terminal(c) {
            write_code(&mut shown, u32::from(c));
        } else {
            shown.push(c);
        }
    }
    Cow::Owned(shown)
}

/// Characters a terminal would obey or hide rather than show.
fn hidden_on_terminal(c: char) -> bool {
    (c.is_control() && c != '\n' && c != '\t')
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// `text` as HTML or XML character data or attribute value: `&`, `<`, `>`, `"` and `'` as
/// entities, and what a terminal would hide as `\u{…}`.
pub fn html(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in terminal(text).chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            '\'' => escaped.push_str("&#39;"),
            c => escaped.push(c),
        }
    }
    escaped
}

/// `text` as literal Markdown inline text (a table cell, a sentence): the characters that
/// Markdown reads as markup inside a line (emphasis, code, links, tables, raw HTML, entities,
/// a heading) backslash-escaped, line breaks as spaces, and what a terminal would hide as
/// `\u{…}`. Other punctuation stays as it is, so the file reads well as plain text.
pub fn markdown(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in terminal(text).chars() {
        match c {
            '\n' | '\r' => escaped.push(' '),
            '\\' | '`' | '*' | '_' | '[' | ']' | '<' | '>' | '&' | '|' | '~' | '#' => {
                escaped.push('\\');
                escaped.push(c);
            }
            c => escaped.push(c),
        }
    }
    escaped
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_terminal_sees_escape_sequences_as_text() {
        assert_eq!(terminal("link_4"), "link_4");
        assert_eq!(terminal("a\u{1b}[31mred"), "a\\u{1b}[31mred");
        assert_eq!(terminal("line\nnext\ttab"), "line\nnext\ttab");
        assert_eq!(terminal("abc\u{202e}cba"), "abc\\u{202e}cba");
        assert_eq!(terminal("bell\u{7}"), "bell\\u{7}");
    }

    #[test]
    fn json_stays_valid_and_shows_hidden_characters_as_escapes() {
        let value = serde_json::json!({ "name": "a\u{7f}b\u{202e}c\u{9b}d\u{1b}e" });
        let text = json(serde_json::to_string(&value).unwrap_or_default());
        assert!(!text.chars().any(hidden_on_terminal), "{text}");
        let back: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
        assert_eq!(back, value);
    }

    #[test]
    fn html_keeps_markup_as_text() {
        assert_eq!(
            html("<img src=x onerror=\"alert('x')\">&"),
            "&lt;img src=x onerror=&quot;alert(&#39;x&#39;)&quot;&gt;&amp;"
        );
    }

    #[cfg(feature = "report")]
    #[test]
    fn markdown_keeps_markup_as_text() {
        let rendered = |md: &str| {
            let mut html = String::new();
            pulldown_cmark::html::push_html(&mut html, pulldown_cmark::Parser::new(md));
            html
        };
        for name in [
            "<img src=x onerror=alert(1)>",
            "*bold* _em_ `code` [link](http://x) | cell |",
            "&lt; &amp;",
            "# heading",
            "line\nbreak",
        ] {
            let html = rendered(&markdown(name));
            let text = html
                .trim()
                .trim_start_matches("<p>")
                .trim_end_matches("</p>");
            // Rendered, the escaped name is the name itself, as HTML text.
            assert_eq!(text, super::html(&name.replace('\n', " ")), "{name}");
        }
    }
}
