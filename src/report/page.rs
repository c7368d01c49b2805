//! `index.html`: the summary, the 3D view, the pictures and the plots on one page that needs
//! nothing but the folder it is in (no fonts, no network; the only scripts are the view's own
//! files in the folder).

use crate::escape::html as escape;
use pulldown_cmark::{Event, Options, Parser, html};

/// A titled group of figures on the page.
pub struct Section<'a> {
    /// The section's heading.
    pub heading: &'a str,
    /// A paragraph above the figures; empty for none.
    pub intro: &'a str,
    /// `(file, caption)` of each figure, an image of the folder.
    pub figures: Vec<(&'a str, &'a str)>,
}

/// The page: `summary_md` rendered up to its second heading, the 3D view's markup `view`, the
/// rest of the summary, then each section that has figures, each figure an image of the
/// folder with its caption.
pub fn index_html(title: &str, summary_md: &str, sections: &[Section<'_>], view: &str) -> String {
    let mut body = String::new();
    // Raw HTML in the Markdown is shown as text: the summary escapes the names it quotes,
    // and this keeps any it missed from becoming markup.
    let events = Parser::new_ext(summary_md, Options::ENABLE_TABLES).map(|event| match event {
        Event::Html(raw) | Event::InlineHtml(raw) => Event::Text(raw),
        other => other,
    });
    html::push_html(&mut body, events);
    let mut page = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{}</title>\n<style>\n{STYLE}{}</style>\n</head>\n<body>\n<main>\n",
        escape(title),
        super::view::VIEW_STYLE
    );
    // The view goes right under the summary's first section (the answer), before the tables.
    let split = body
        .match_indices("<h2>")
        .nth(1)
        .map_or(body.len(), |(at, _)| at);
    page.push_str(&body[..split]);
    page.push_str(view);
    page.push_str(&body[split..]);
    for section in sections.iter().filter(|s| !s.figures.is_empty()) {
        page.push_str(&format!("<h2>{}</h2>\n", escape(section.heading)));
        if !section.intro.is_empty() {
            page.push_str(&format!("<p>{}</p>\n", escape(section.intro)));
        }
        for (file, caption) in &section.figures {
            page.push_str(&format!(
                "<figure>\n<img src=\"{file}\" alt=\"{alt}\">\n<figcaption>{alt}</figcaption>\n</figure>\n",
                alt = escape(caption)
            ));
        }
    }
    page.push_str("</main>\n</body>\n</html>\n");
    page
}

/// Plain, print-friendly styling; system fonts only.
const STYLE: &str = "body { font-family: sans-serif; margin: 0; background: #fafafa; color: #222; }
main { max-width: 1100px; margin: 0 auto; padding: 1em 2em; background: white; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; }
th { background: #eee; }
figure { margin: 1.5em 0; }
figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { color: #555; font-size: 0.9em; }
code { background: #f2f2f2; padding: 0 0.2em; }
";
