//! Every public item has one public path (plus the prelude): no file declares a public module
//! and also re-exports that module's items (`pub mod m;` with `pub use m::X;` gives X two
//! paths, `m::X` and `X`), nor re-exports the items of a public module it re-exports itself
//! (`pub use harness::trial;` with `pub use trial::TrialLog;`), and no leaf file (anything but
//! a `mod.rs`, `lib.rs` or `prelude.rs`) re-exports a sibling's or another module's items
//! (`pub use super::...`, `pub use crate::...`).

use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The file's code without comments (line comments and doc comments; the crate writes no
/// block comments around `pub use` or `pub mod`).
fn code_lines(text: &str) -> String {
    text.lines()
        .map(|line| match line.find("//") {
            Some(i) => &line[..i],
            None => line,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The statements of the file that start with `start` (e.g. `pub use `), whitespace
/// collapsed, up to their `;`.
fn statements(code: &str, start: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find(start) {
        let before_ok = i == 0 || {
            let c = rest.as_bytes()[i - 1];
            !(c.is_ascii_alphanumeric() || c == b'_')
        };
        let tail = &rest[i + start.len()..];
        let end = tail.find([';', '{']).map_or(tail.len(), |e| {
            if tail.as_bytes()[e] == b'{' && start.starts_with("pub use") {
                tail.find(';').unwrap_or(tail.len())
            } else {
                e
            }
        });
        if before_ok {
            found.push(tail[..end].split_whitespace().collect::<Vec<_>>().join(" "));
        }
        rest = &tail[end.min(tail.len())..];
    }
    found
}

/// The full paths a use tree names (`a::{b, c::{d as e}}` -> `a::b`, `a::c::d`), each with
/// the name it is known by (its last segment or its `as` alias).
fn use_paths(tree: &str) -> Vec<(String, String)> {
    fn split_top(s: &str) -> Vec<&str> {
        let (mut depth, mut start, mut parts) = (0, 0, Vec::new());
        for (i, c) in s.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    parts.push(&s[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        parts.push(&s[start..]);
        parts
            .into_iter()
            .map(str::trim)
            .filter(|p| !p.is_empty())
            .collect()
    }
    fn walk(prefix: &str, tree: &str, out: &mut Vec<(String, String)>) {
        let tree = tree.trim();
        if let Some(open) = tree.find('{') {
            let head = tree[..open].trim().trim_end_matches("::");
            let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
            let prefix = join(prefix, head);
            for part in split_top(inner) {
                walk(&prefix, part, out);
            }
        } else {
            let (path, name) = match tree.split_once(" as ") {
                Some((path, alias)) => (path.trim(), alias.trim().to_string()),
                None => (tree, tree.rsplit("::").next().unwrap_or(tree).to_string()),
            };
            out.push((join(prefix, path), name));
        }
    }
    fn join(prefix: &str, path: &str) -> String {
        match (prefix.is_empty(), path.is_empty()) {
            (true, _) => path.to_string(),
            (_, true) => prefix.to_string(),
            _ => format!("{prefix}::{path}"),
        }
    }
    let mut out = Vec::new();
    walk("", tree, &mut out);
    out
}

/// Whether `path`, named in the file `file` under `src`, is a module with a file of its own.
fn is_module_file(src: &Path, file: &Path, path: &str) -> bool {
    let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let parent = file.parent().unwrap_or(src);
    // The folder that holds this file's child modules.
    let mut dir = if matches!(stem, "mod" | "lib") {
        parent.to_path_buf()
    } else {
        parent.join(stem)
    };
    let mut segments: Vec<&str> = path.split("::").collect();
    match segments.first() {
        Some(&"crate") => {
            dir = src.to_path_buf();
            segments.remove(0);
        }
        Some(&"self") => {
            segments.remove(0);
        }
        _ => {}
    }
    while segments.first() == Some(&"super") {
        dir = dir.parent().unwrap_or(src).to_path_buf();
        segments.remove(0);
    }
    if segments.is_empty() {
        return false;
    }
    let joined: PathBuf = segments.iter().collect();
    dir.join(&joined).with_extension("rs").is_file() || dir.join(&joined).join("mod.rs").is_file()
}

/// What in one file gives an item a second public path, one line per finding.
fn second_paths(src: &Path, file: &Path, text: &str) -> Vec<String> {
    let name = file.strip_prefix(src).unwrap_or(file).display().to_string();
    let code = code_lines(text);
    let mut public_modules: Vec<String> = statements(&code, "pub mod ")
        .into_iter()
        .map(|m| m.trim().to_string())
        .collect();
    let uses = statements(&code, "pub use ");
    for tree in &uses {
        for (path, known_as) in use_paths(tree) {
            if is_module_file(src, file, &path) {
                public_modules.push(known_as);
            }
        }
    }
    let mut found = Vec::new();
    for tree in &uses {
        let head = tree.trim_start_matches("self::");
        let first = head.split("::").next().unwrap_or("").trim();
        if head.contains("::") && public_modules.iter().any(|m| m == first) {
            found.push(format!(
                "{name}: module `{first}` is public and its items are re-exported too (`pub use {tree}`)"
            ));
        }
    }
    let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    if !matches!(stem, "mod" | "lib" | "prelude") {
        for tree in &uses {
            if tree.starts_with("super::") || tree.starts_with("crate::") {
                found.push(format!(
                    "{name}: a leaf module re-exports another module's items (`pub use {tree}`)"
                ));
            }
        }
    }
    found
}

fn src() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src")
}

#[test]
fn every_public_item_has_one_public_path() {
    let src = src();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    assert!(
        files.len() > 50,
        "found only {} files under src/",
        files.len()
    );
    let found: Vec<String> = files
        .iter()
        .flat_map(|file| {
            let text = std::fs::read_to_string(file).unwrap();
            second_paths(&src, file, &text)
        })
        .collect();
    assert!(
        found.is_empty(),
        "second public paths:\n{}",
        found.join("\n")
    );
}

/// The check finds each kind of second path (so that an empty finding means something).
#[test]
fn the_check_finds_second_paths() {
    let src = src();
    let control = src.join("control").join("mod.rs");
    let found = second_paths(&src, &control, "pub mod walker;\npub use walker::Walker;\n");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].contains("control/mod.rs") && found[0].contains("`walker`"));
    let found = second_paths(
        &src,
        &control,
        "pub mod lipm;\npub use self::lipm::{\n    Lipm,\n};\n",
    );
    assert_eq!(found.len(), 1, "{found:?}");
    let experiments = src.join("experiments").join("mod.rs");
    let found = second_paths(
        &src,
        &experiments,
        "pub use harness::{aligned, trial};\npub use trial::TrialLog;\n",
    );
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].contains("`trial`"));
    let walker = src.join("control").join("walker.rs");
    let found = second_paths(&src, &walker, "pub use super::policy::FootstepPolicy;\n");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].contains("control/walker.rs"));
    let found = second_paths(&src, &walker, "pub use crate::robot::Side;\n");
    assert_eq!(found.len(), 1, "{found:?}");
    // A private module's items re-exported, and a function named like its module, are fine.
    let replay = src.join("replay").join("mod.rs");
    let fine = "mod page;\npub use page::{embedded_replay, page};\n// pub mod x; pub use x::Y;\n";
    assert!(second_paths(&src, &replay, fine).is_empty());
    assert!(second_paths(&src, &walker, "use super::policy::FootstepPolicy;\n").is_empty());
    assert!(second_paths(&src, &walker, "pub(crate) use super::policy::X;\n").is_empty());
}
