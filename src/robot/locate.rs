//! Finding *where* a URDF document is malformed.
//!
//! urdf-rs re-serialises a document before deserialising it, so its error messages carry no
//! position in the user's file. When it refuses a document, this module reads the original text
//! once more and points at the first XML syntax error or malformed number. It also finds the
//! first use of xacro, which a URDF must not contain.

use crate::input::line_of;
use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};
use quick_xml::name::QName;

/// URDF attributes that hold numbers, with how many each must hold.
const NUMERIC_ATTRIBUTES: [(&str, usize); 16] = [
    ("xyz", 3),
    ("rpy", 3),
    ("size", 3),
    ("scale", 3),
    ("quat_xyzw", 4),
    ("rgba", 4),
    ("radius", 1),
    ("length", 1),
    ("lower", 1),
    ("upper", 1),
    ("velocity", 1),
    ("effort", 1),
    ("multiplier", 1),
    ("offset", 1),
    ("damping", 1),
    ("friction", 1),
];

/// Deepest element nesting a URDF may have. Real ones nest 5–10 deep (robot, link,
/// collision, geometry, mesh; a Gazebo plugin's options); the URDF parser recurses once per
/// level, so a document 100 000 levels deep would overflow the stack.
pub const MAX_XML_DEPTH: usize = 64;

/// The 1-based line of the first element nested deeper than [`MAX_XML_DEPTH`], read without
/// recursion; `None` when none is (syntax errors are left to [`first_problem`]).
pub(super) fn too_deep(text: &str) -> Option<usize> {
    let mut reader = Reader::from_str(text);
    let mut depth = 0usize;
    loop {
        let element_start = reader.buffer_position() as usize;
        match reader.read_event() {
            Ok(Event::Start(_)) => {
                depth += 1;
                if depth > MAX_XML_DEPTH {
                    return Some(line_of(text, element_start));
                }
            }
            Ok(Event::End(_)) => depth = depth.saturating_sub(1),
            Ok(Event::Eof) | Err(_) => return None,
            Ok(_) => {}
        }
    }
}

/// The 1-based line and description of the first syntax error or malformed number in `text`,
/// or `None` when the text looks well-formed (the problem is then structural).
pub(super) fn first_problem(text: &str) -> Option<(usize, String)> {
    let mut reader = Reader::from_str(text);
    let mut open_elements = 0usize;
    loop {
        let element_start = reader.buffer_position() as usize;
        let event = match reader.read_event() {
            Ok(event) => event,
            Err(e) => {
                let line = line_of(text, reader.error_position() as usize);
                return Some((line, format!("XML syntax error: {e}")));
            }
        };
        let element = match event {
            Event::Start(element) => {
                open_elements += 1;
                element
            }
            Event::Empty(element) => element,
            Event::End(_) => {
                open_elements = open_elements.saturating_sub(1);
                continue;
            }
            Event::Eof if open_elements > 0 => {
                let problem = "the document ends before all its elements are closed";
                return Some((line_of(text, text.len()), problem.into()));
            }
            Event::Eof => return None,
            _ => continue,
        };
        if let Some(problem) = malformed_number(&element) {
            return Some((line_of(text, element_start), problem));
        }
    }
}

/// The 1-based line and description of the first use of xacro in `text`: an element or
/// attribute with the `xacro:` prefix (`<xacro:macro>`, `<xacro:include>`, …) or a `${…}` /
/// `$(…)` substitution in an attribute value or in text. Comments do not count, and neither
/// does the `xmlns:xacro` declaration alone: URDFs expanded by xacro (ROS-Industrial
/// descriptions among them) keep it on `<robot>`. `None` also when the XML is malformed before
/// any xacro use; the URDF parser then reports the syntax error.
pub(super) fn first_xacro_use(text: &str) -> Option<(usize, String)> {
    let mut reader = Reader::from_str(text);
    loop {
        let start = reader.buffer_position() as usize;
        let found = match reader.read_event() {
            Ok(Event::Start(element) | Event::Empty(element)) => {
                xacro_in_element(&element).map(|problem| (start, problem))
            }
            Ok(Event::Text(content)) => substitution_at(&content).map(|offset| {
                let problem = "a xacro substitution (${…} or $(…)) in the text";
                (start + offset, problem.to_string())
            }),
            Ok(Event::Eof) | Err(_) => return None,
            Ok(_) => None,
        };
        if let Some((offset, problem)) = found {
            return Some((line_of(text, offset), problem));
        }
    }
}

/// Describes how `element` uses xacro, if it does.
fn xacro_in_element(element: &BytesStart<'_>) -> Option<String> {
    let is_xacro = |name: QName<'_>| name.prefix().is_some_and(|p| p.as_ref() == b"xacro");
    let tag = String::from_utf8_lossy(element.name().as_ref()).into_owned();
    if is_xacro(element.name()) {
        return Some(format!("<{tag}> is a xacro element"));
    }
    for attribute in element.attributes().flatten() {
        let key = String::from_utf8_lossy(attribute.key.as_ref()).into_owned();
        if is_xacro(attribute.key) {
            return Some(format!("<{tag}>: {key} is a xacro attribute"));
        }
        if substitution_at(&attribute.value).is_some() {
            let value = String::from_utf8_lossy(&attribute.value).into_owned();
            return Some(format!("<{tag} {key}=\"{value}\">: a xacro substitution"));
        }
    }
    None
}

/// Where `bytes` hold a xacro substitution: `${` (property or expression) or `$(` (`$(arg …)`,
/// `$(find …)`).
fn substitution_at(bytes: &[u8]) -> Option<usize> {
    bytes
        .windows(2)
        .position(|pair| pair == b"${" || pair == b"$(")
}

/// Describes the first numeric attribute of `element` that does not hold its count of numbers.
fn malformed_number(element: &BytesStart<'_>) -> Option<String> {
    let tag = String::from_utf8_lossy(element.name().as_ref()).into_owned();
    for attribute in element.attributes() {
        let Ok(attribute) = attribute else {
            return Some(format!("<{tag}>: malformed attribute"));
        };
        let key = String::from_utf8_lossy(attribute.key.as_ref()).into_owned();
        let Some(&(_, count)) = NUMERIC_ATTRIBUTES.iter().find(|(name, _)| *name == key) else {
            continue;
        };
        let value = String::from_utf8_lossy(&attribute.value).into_owned();
        let numbers: Vec<Result<f64, _>> =
            value.split_whitespace().map(str::parse::<f64>).collect();
        if numbers.len() != count || numbers.iter().any(Result::is_err) {
            let expected = if count == 1 {
                "a number".to_string()
            } else {
                format!("{count} numbers")
            };
            return Some(format!("<{tag} {key}=\"{value}\">: expected {expected}"));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::{MAX_XML_DEPTH, first_problem, first_xacro_use, too_deep};

    #[test]
    fn nesting_is_measured_without_recursion() {
        let deep = |n: usize| format!("<robot>\n{}{}</robot>", "<a>".repeat(n), "</a>".repeat(n));
        assert_eq!(too_deep(&deep(MAX_XML_DEPTH - 1)), None);
        assert_eq!(too_deep(&deep(MAX_XML_DEPTH)), Some(2));
        assert_eq!(too_deep(&deep(100_000)), Some(2));
    }

    #[test]
    fn points_at_the_line_of_the_problem() {
        let bad_number =
            "<robot>\n<link name=\"a\">\n<collision><geometry>\n<box size=\"0.1 0.1\"/>";
        let (line, problem) = first_problem(bad_number).expect("found");
        assert_eq!(line, 4);
        assert!(
            problem.contains("<box size=\"0.1 0.1\">: expected 3 numbers"),
            "{problem}"
        );

        let not_a_number = "<robot>\n<joint>\n<limit lower=\"0\" upper=\"x\"/></joint></robot>";
        let (line, problem) = first_problem(not_a_number).expect("found");
        assert_eq!(line, 3);
        assert!(problem.contains("upper=\"x\"") && problem.contains("expected a number"));

        let (line, problem) = first_problem("<robot>\n<link name=\"a\">\n").expect("found");
        assert_eq!(line, 3);
        assert!(problem.contains("ends before"), "{problem}");

        let (line, problem) = first_problem("<robot>\n<link name=\"a\"></joint>").expect("found");
        assert_eq!(line, 2);
        assert!(problem.contains("XML syntax error"), "{problem}");

        assert_eq!(first_problem("<robot><link name=\"a\"/></robot>"), None);
    }

    #[test]
    fn finds_xacro_elements_attributes_and_substitutions_but_not_the_namespace_alone() {
        let ns = r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">"#;
        let plain = format!(
            "{ns}\n<!-- <xacro:include filename=\"${{x}}\"/> -->\n<link name=\"a\"/></robot>"
        );
        assert_eq!(first_xacro_use(&plain), None);

        let cases = [
            (
                "<xacro:macro name=\"m\" params=\"p\">\n</xacro:macro>",
                3,
                "<xacro:macro> is a xacro element",
            ),
            (
                "<xacro:include filename=\"x.xacro\"/>",
                3,
                "<xacro:include> is a xacro element",
            ),
            (
                "<link name=\"${prefix}a\"/>",
                3,
                "<link name=\"${prefix}a\">: a xacro substitution",
            ),
            (
                "<link name=\"a\" xacro:if=\"1\"/>",
                3,
                "xacro:if is a xacro attribute",
            ),
            (
                "<link name=\"a\">\n<x>\n$(arg y)</x></link>",
                5,
                "substitution (${…} or $(…)) in the text",
            ),
        ];
        for (body, line, expected) in cases {
            let text = format!("{ns}\n\n{body}\n</robot>");
            let (found_line, problem) = first_xacro_use(&text).expect(body);
            assert_eq!(found_line, line, "{body}");
            assert!(problem.contains(expected), "{body}: {problem}");
        }
        // Malformed XML is the URDF parser's to report.
        assert_eq!(first_xacro_use("<robot><link></robot>"), None);
    }
}
