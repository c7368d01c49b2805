//! Reading the report's pictures of the cable on the robot in tests: every element of an SVG,
//! parsed with a real XML parser, with the view panel and the group it is drawn in.

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};
use std::collections::BTreeMap;

/// The three views every picture has.
pub const VIEWS: [&str; 3] = ["front", "side", "top"];

/// One element of a picture.
#[derive(Debug)]
pub struct Element {
    /// Tag name, e.g. `polygon`.
    pub name: String,
    /// Attributes, unescaped.
    pub attributes: BTreeMap<String, String>,
    /// The view panel (`front`, `side`, `top`) it is inside, if any.
    pub view: Option<String>,
    /// The class of the innermost `<g>` it is inside, if any.
    pub group: Option<String>,
}

impl Element {
    /// The attribute `name`, or "" without it.
    pub fn attribute(&self, name: &str) -> &str {
        self.attributes.get(name).map_or("", String::as_str)
    }

    /// Whether it is a `name` element drawn in `view`'s panel in a `<g class="group">`.
    pub fn is(&self, name: &str, view: &str, group: &str) -> bool {
        self.name == name
            && self.view.as_deref() == Some(view)
            && self.group.as_deref() == Some(group)
    }
}

/// Every element of `svg`, in document order; panics unless `svg` is well-formed XML.
pub fn elements(svg: &str) -> Vec<Element> {
    let mut reader = Reader::from_str(svg);
    let mut open: Vec<Element> = Vec::new();
    let mut all = Vec::new();
    loop {
        match reader.read_event().expect("well-formed XML") {
            Event::Start(start) => {
                let element = element(&start, &open);
                open.push(element);
            }
            Event::Empty(empty) => all.push(element(&empty, &open)),
            Event::End(_) => all.push(open.pop().expect("balanced tags")),
            Event::Eof => break,
            _ => {}
        }
    }
    assert!(open.is_empty(), "unclosed elements");
    all
}

/// `start` with its enclosing view and group, from the elements open around it.
fn element(start: &BytesStart<'_>, open: &[Element]) -> Element {
    let attributes = start
        .attributes()
        .map(|a| {
            let a = a.expect("a well-formed attribute");
            let key = String::from_utf8_lossy(a.key.as_ref()).into_owned();
            (
                key,
                a.unescape_value().expect("an attribute value").into_owned(),
            )
        })
        .collect();
    let class_of = |name: &str| {
        open.iter()
            .rev()
            .find(|e| e.name == name && e.attributes.contains_key("class"))
            .map(|e| e.attribute("class").to_string())
    };
    let view = class_of("svg").and_then(|c| c.strip_prefix("view ").map(str::to_string));
    Element {
        name: String::from_utf8_lossy(start.name().as_ref()).into_owned(),
        attributes,
        view,
        group: class_of("g"),
    }
}

/// The `x,y x,y …` of a `points` attribute.
pub fn points(list: &str) -> Vec<[f64; 2]> {
    list.split_whitespace()
        .map(|pair| {
            let (x, y) = pair.split_once(',').expect("x,y");
            [x.parse().expect("x"), y.parse().expect("y")]
        })
        .collect()
}
