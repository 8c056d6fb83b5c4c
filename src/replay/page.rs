//! The replay page: one HTML file with three.js, the viewer and the recording inlined; it
//! fetches nothing.

use super::{Replay, ReplayError};

/// The version of three.js inlined in every page (npm package `three`).
pub const THREE_VERSION: &str = "0.170.0";
/// three.js's licence.
pub const THREE_LICENSE: &str = include_str!("../../assets/three/LICENSE");
const THREE_JS: &str = include_str!("../../assets/three/three.module.min.js");
const VIEWER_JS: &str = include_str!("viewer.js");

const DATA_OPEN: &str = "<script type=\"application/json\" id=\"replay-data\">";
const DATA_CLOSE: &str = "</script>";

/// three.js as a script that defines `const THREE` instead of exporting.
fn three_script() -> Result<String, ReplayError> {
    let start = THREE_JS
        .rfind("export{")
        .ok_or_else(|| ReplayError::Page("the vendored three.js has no export list".into()))?;
    let list = THREE_JS[start + "export{".len()..]
        .trim_end()
        .trim_end_matches(';')
        .trim_end_matches('}');
    let mut object = String::from("const THREE={");
    for item in list.split(',') {
        let (local, name) = match item.split_once(" as ") {
            Some((l, n)) => (l.trim(), n.trim()),
            None => (item.trim(), item.trim()),
        };
        object.push_str(name);
        object.push(':');
        object.push_str(local);
        object.push(',');
    }
    object.push_str("};");
    Ok(format!("{}\n{object}", &THREE_JS[..start]))
}

/// The page of `replay`.
///
/// three.js's single-file module build is turned into a plain object `THREE` (its final
/// `export{local as Name,...}` becomes `const THREE={Name:local,...}`) and the viewer's code
/// follows it in the same `<script type="module">`. The recording is JSON in a
/// `<script type="application/json" id="replay-data">`, read back by [`embedded_replay`].
pub fn page(replay: &Replay) -> Result<String, ReplayError> {
    let data = serde_json::to_string(replay)
        .map_err(|e| ReplayError::Page(e.to_string()))?
        .replace("</", "<\\/");
    let moment = match replay.span {
        Some(_) => super::moment_name(replay),
        None => format!("push {} ({:.2} Ns)", replay.push, replay.impulse),
    };
    let title = format!(
        "steplearn replay: {} seed {}, {moment}",
        replay.experiment, replay.seed
    );
    let three = three_script()?;
    let licence = THREE_LICENSE.replace("*/", "* /");
    Ok(format!(
        r#"<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>{title}</title>
<style>
body{{font:14px system-ui,sans-serif;margin:0;background:#f4f4f4}}
header,#controls,#legend,footer{{padding:4px 10px}}
#view{{width:100%;height:60vh;display:block;background:#dde4ea}}
#timeline{{width:100%;height:180px;display:block;background:#fff}}
#errors{{color:#b00;margin:0 10px}}
.key{{display:inline-block;width:10px;height:10px;margin:0 4px 0 12px}}
</style></head>
<body data-frames-drawn="0">
<header><strong>{title}</strong> &middot; {approx} + {rule}</header>
<canvas id="view"></canvas>
<div id="controls">
<button id="play">pause</button>
<input id="scrub" type="range" min="0" max="1000" value="0" style="width:50%">
<span id="clock">0.00 s</span>
<label>speed <select id="speed"><option value="0.25">0.25x</option><option value="0.5">0.5x</option><option value="1" selected>1x</option></select></label>
<label><input id="overlay" type="checkbox"> overlaid</label>
</div>
<canvas id="timeline"></canvas>
<div id="legend"></div>
<pre id="errors"></pre>
<footer>Drag to orbit, wheel to zoom. Spheres: CoM (red), capture point (orange, on the ground).
Footsteps: commanded (blue rings), realised (green boxes). Arrow: the push. Red cross: the fall.
Rendered with three.js r{version} (MIT licence, inlined).</footer>
{DATA_OPEN}{data}{DATA_CLOSE}
<script type="module">
/* three.js {version} (npm package `three`), MIT licence:
{licence}*/
{three}
{VIEWER_JS}
</script>
</body></html>
"#,
        approx = replay.approx,
        rule = replay.rule,
        version = THREE_VERSION,
    ))
}

/// The recording a page holds.
pub fn embedded_replay(html: &str) -> Result<Replay, ReplayError> {
    let start = html
        .find(DATA_OPEN)
        .ok_or_else(|| ReplayError::Page("no replay-data element".into()))?
        + DATA_OPEN.len();
    let len = html[start..]
        .find(DATA_CLOSE)
        .ok_or_else(|| ReplayError::Page("the replay-data element is not closed".into()))?;
    serde_json::from_str(&html[start..start + len]).map_err(|e| ReplayError::Page(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_title_gives_the_impulse_to_two_decimals() {
        let replay = Replay {
            experiment: "A".into(),
            approx: "lwpr".into(),
            rule: "pendulum-cart".into(),
            seed: 3,
            push: 2,
            impulse: 3.491584701138599,
            direction: [1.0, 0.0, 0.0],
            window_s: 1.0,
            span: None,
            changes: Vec::new(),
            walks: Vec::new(),
        };
        let html = page(&replay).unwrap();
        let start = html.find("<title>").unwrap() + "<title>".len();
        let title = &html[start..start + html[start..].find("</title>").unwrap()];
        assert_eq!(title, "steplearn replay: A seed 3, push 2 (3.49 Ns)");
        let header = format!("<strong>{title}</strong>");
        assert!(html.contains(&header), "the header repeats the title");
        // The data keeps the impulse whole; only the text shown is rounded.
        assert!(!title.contains("3.4915") && html.contains("3.491584701138599"));
    }
}
