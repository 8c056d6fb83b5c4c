//! One self-contained HTML page: headings, text, tables (from the Markdown the reports
//! already write) and SVG figures inlined, with no script, font or network reference.

use super::{ReportError, write_file};
use std::path::Path;

/// A page being built; [`HtmlPage::write`] writes it.
#[derive(Debug, Clone, Default)]
pub struct HtmlPage {
    title: String,
    body: String,
}

/// `s` with `&`, `<`, `>` and `"` escaped.
pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Escaped text with `**bold**` spans as `<strong>`.
fn inline(s: &str) -> String {
    let mut out = String::new();
    for (i, part) in escape(s).split("**").enumerate() {
        if i % 2 == 1 {
            out.push_str("<strong>");
            out.push_str(part);
            out.push_str("</strong>");
        } else {
            out.push_str(part);
        }
    }
    out
}

fn cells(line: &str) -> Vec<&str> {
    let t = line.trim().trim_start_matches('|').trim_end_matches('|');
    t.split('|').map(str::trim).collect()
}

impl HtmlPage {
    /// An empty page titled `title` (also its first heading).
    pub fn new(title: &str) -> Self {
        HtmlPage {
            title: title.to_string(),
            body: format!("<h1>{}</h1>\n", escape(title)),
        }
    }

    /// A heading of `level` (2-4).
    pub fn heading(&mut self, level: u8, text: &str) -> &mut Self {
        let l = level.clamp(2, 4);
        self.body
            .push_str(&format!("<h{l}>{}</h{l}>\n", inline(text)));
        self
    }

    /// A paragraph of text (`**bold**` allowed).
    pub fn paragraph(&mut self, text: &str) -> &mut Self {
        self.body.push_str(&format!("<p>{}</p>\n", inline(text)));
        self
    }

    /// Preformatted text (a command, a configuration).
    pub fn code(&mut self, text: &str) -> &mut Self {
        self.body
            .push_str(&format!("<pre>{}</pre>\n", escape(text.trim_end())));
        self
    }

    /// The Markdown the reports write: `#` headings, `- ` lists, pipe tables and paragraphs.
    pub fn markdown(&mut self, md: &str) -> &mut Self {
        let lines: Vec<&str> = md.lines().collect();
        let mut i = 0;
        while i < lines.len() {
            let line = lines[i].trim();
            if line.is_empty() {
                i += 1;
            } else if let Some(h) = line.strip_prefix('#') {
                let level = 1 + h.chars().take_while(|&c| c == '#').count() as u8;
                self.heading(level + 1, h.trim_start_matches('#').trim());
                i += 1;
            } else if line.starts_with("- ") {
                let mut items = Vec::new();
                while i < lines.len() && lines[i].trim().starts_with("- ") {
                    items.push(lines[i].trim()[2..].trim());
                    i += 1;
                }
                self.list(&items);
            } else if line.starts_with('|') {
                let mut rows = Vec::new();
                while i < lines.len() && lines[i].trim().starts_with('|') {
                    rows.push(cells(lines[i]));
                    i += 1;
                }
                // drop the |---| separator line
                rows.retain(|r| {
                    !r.iter()
                        .all(|c| !c.is_empty() && c.chars().all(|ch| ch == '-' || ch == ':'))
                });
                self.table_rows(&rows);
            } else {
                let mut text = Vec::new();
                while i < lines.len() && !lines[i].trim().is_empty() {
                    text.push(lines[i].trim());
                    i += 1;
                }
                self.paragraph(&text.join(" "));
            }
        }
        self
    }

    fn table_rows(&mut self, rows: &[Vec<&str>]) {
        let Some((head, body)) = rows.split_first() else {
            return;
        };
        self.body.push_str("<table>\n<tr>");
        for c in head {
            self.body.push_str(&format!("<th>{}</th>", inline(c)));
        }
        self.body.push_str("</tr>\n");
        for r in body {
            self.body.push_str("<tr>");
            for c in r {
                self.body.push_str(&format!("<td>{}</td>", inline(c)));
            }
            self.body.push_str("</tr>\n");
        }
        self.body.push_str("</table>\n");
    }

    /// An SVG figure inlined (its XML prolog dropped) with a one-line caption.
    pub fn figure(&mut self, svg: &str, caption: &str) -> &mut Self {
        let svg = match svg.find("<svg") {
            Some(start) => &svg[start..],
            None => svg,
        };
        self.body.push_str(&format!(
            "<figure>\n{}\n<figcaption>{}</figcaption>\n</figure>\n",
            svg.trim(),
            inline(caption)
        ));
        self
    }

    /// A figure left out of the page to keep it small: a link to its file at the relative
    /// path `href`, with its caption.
    pub fn figure_link(&mut self, href: &str, caption: &str) -> &mut Self {
        self.body.push_str(&format!(
            "<p class=\"figure-link\"><a href=\"{}\">Figure (not inlined): {}</a></p>\n",
            escape(href),
            inline(caption)
        ));
        self
    }

    /// A paragraph that links the relative path `href`, with `text` (`**bold**` allowed).
    pub fn link(&mut self, href: &str, text: &str) -> &mut Self {
        self.body.push_str(&format!(
            "<p class=\"link\"><a href=\"{}\">{}</a></p>\n",
            escape(href),
            inline(text)
        ));
        self
    }

    /// A bulleted list, one item per entry (`**bold**` allowed).
    pub fn list(&mut self, items: &[&str]) -> &mut Self {
        self.body.push_str("<ul>\n");
        for item in items {
            self.body.push_str(&format!("<li>{}</li>\n", inline(item)));
        }
        self.body.push_str("</ul>\n");
        self
    }

    /// The whole page.
    pub fn to_html(&self) -> String {
        format!(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <title>{}</title>\n<style>\n\
             body {{ font-family: sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em; color: #222; }}\n\
             table {{ border-collapse: collapse; margin: 1em 0; font-size: 0.9em; }}\n\
             th, td {{ border: 1px solid #bbb; padding: 0.25em 0.5em; text-align: left; }}\n\
             th {{ background: #eee; }}\n\
             figure {{ margin: 1.5em 0; }} figure svg {{ max-width: 100%; height: auto; }}\n\
             figcaption {{ color: #555; font-size: 0.9em; }}\n\
             pre {{ background: #f6f6f6; padding: 0.5em; overflow-x: auto; }}\n\
             </style>\n</head>\n<body>\n{}</body>\n</html>\n",
            escape(&self.title),
            self.body
        )
    }

    /// Writes the page to `path` atomically.
    pub fn write(&self, path: &Path) -> Result<(), ReportError> {
        write_file(path, self.to_html().as_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_tables_headings_and_figures() {
        let mut page = HtmlPage::new("Run <1>");
        page.markdown("# Claims\n\n## 1. A & B\n\n**reproduced** (2 of 2 seeds)\n\n| seed | holds |\n|---|---|\n| 0 | yes |\n| 1 | no |\n");
        page.figure(
            "<?xml version=\"1.0\"?>\n<svg width=\"10\"></svg>",
            "a figure",
        );
        let html = page.to_html();
        assert!(html.contains("<h1>Run &lt;1&gt;</h1>"));
        assert!(html.contains("<h2>Claims</h2>"));
        assert!(html.contains("<h3>1. A &amp; B</h3>"));
        assert!(html.contains("<p><strong>reproduced</strong> (2 of 2 seeds)</p>"));
        assert!(html.contains("<tr><th>seed</th><th>holds</th></tr>"));
        assert!(html.contains("<tr><td>1</td><td>no</td></tr>"));
        assert!(!html.contains("---"));
        assert!(html.contains("<figure>\n<svg width=\"10\"></svg>"));
        assert!(!html.contains("<?xml"));
    }

    #[test]
    fn markdown_lists_and_figure_links() {
        let mut page = HtmlPage::new("t");
        page.markdown("- Claim 1: **better**\n- Claim 2: level\n\nText.\n");
        page.figure_link("run/a b.svg", "a <figure>");
        let html = page.to_html();
        assert!(html.contains(
            "<ul>\n<li>Claim 1: <strong>better</strong></li>\n<li>Claim 2: level</li>\n</ul>"
        ));
        assert!(html.contains("<p>Text.</p>"));
        assert!(
            html.contains("<a href=\"run/a b.svg\">Figure (not inlined): a &lt;figure&gt;</a>")
        );
    }
}
