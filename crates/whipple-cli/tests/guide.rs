//! The user guide's shell examples run: every line of a ```sh block in docs/guide/*.md that
//! starts with `whipple ` is run against the real binary, chapter by chapter in a scratch
//! directory holding the field's parameter files the guide names (so later commands can read
//! what earlier ones wrote). A command must succeed and write every `--out`, `--plot` and
//! `--report` it names, unless its comment says `(fails)`: then it must fail with a message.
//! `whipple serve` (which runs until stopped) is the only command not run; the web page has its
//! own tests (crates/whipple-web).

mod common;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// One example: the chapter, the line number, the command's words and whether it must fail.
#[derive(Debug)]
struct Example {
    chapter: String,
    line: usize,
    words: Vec<String>,
    fails: bool,
}

/// Splits a shell line into words: blanks separate, '…' and "…" quote, `#` after a blank starts
/// a comment (returned apart). No variables, globs or escapes: the guide's examples need none,
/// and a line that uses them fails the test instead of running something else.
fn split(line: &str) -> (Vec<String>, String) {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut quote: Option<char> = None;
    for (i, ch) in line.char_indices() {
        match quote {
            Some(q) if ch == q => quote = None,
            Some(_) => word.push(ch),
            None => match ch {
                '\'' | '"' => {
                    quote = Some(ch);
                    in_word = true;
                }
                '#' if !in_word => {
                    return (words, line[i + 1..].trim().to_string());
                }
                c if c.is_whitespace() => {
                    if in_word {
                        words.push(std::mem::take(&mut word));
                        in_word = false;
                    }
                }
                '$' | '*' | '?' | '`' | '\\' | '|' | '>' | '<' | ';' | '&' => {
                    panic!("shell syntax `{ch}` in a guide example: {line}")
                }
                c => {
                    word.push(c);
                    in_word = true;
                }
            },
        }
    }
    assert!(quote.is_none(), "unclosed quote in a guide example: {line}");
    if in_word {
        words.push(word);
    }
    (words, String::new())
}

/// Every `whipple ...` line of the ```sh blocks of one chapter (lines ending in `\` continued).
fn examples(chapter: &str, text: &str) -> Vec<Example> {
    let mut found = Vec::new();
    let mut in_sh = false;
    let mut pending: Option<(usize, String)> = None;
    for (n, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.starts_with("```") {
            in_sh = !in_sh && trimmed == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        let (start, joined) = match pending.take() {
            Some((start, before)) => (start, format!("{before} {trimmed}")),
            None => (n + 1, trimmed.to_string()),
        };
        if let Some(head) = joined.strip_suffix('\\') {
            pending = Some((start, head.trim_end().to_string()));
            continue;
        }
        if !joined.starts_with("whipple ") {
            continue;
        }
        let (words, comment) = split(&joined);
        found.push(Example {
            chapter: chapter.to_string(),
            line: start,
            words: words[1..].to_vec(),
            fails: comment.contains("(fails)"),
        });
    }
    found
}

/// The field's files the guide's examples read, copied into the scratch directory: parameter
/// files, raw bench measurements, an oscillation record and Yeadon riders (folder, and the
/// endings of the files taken from it). docs/hooks/figures.py copies the same for the figures.
const INPUTS: [(&str, &[&str]); 8] = [
    ("bicycleparameters", &[".txt", ".yml"]),
    ("humancontrol", &[".txt", ".yml"]),
    ("humancontrol/gains", &["SteerGains.txt"]),
    ("humancontrol/optimal", &["Par.txt"]),
    ("bicycleparameters-yaml", &[".txt", ".yml"]),
    ("measured", &["Measured.txt"]),
    ("measured/periods", &[".mat"]),
    ("yeadon", &["YeadonMeas.txt", "YeadonCFG.txt"]),
];

fn copy_inputs(dir: &Path) {
    let data = root().join("crates/whipple/tests/data");
    for (sub, endings) in INPUTS {
        for entry in fs::read_dir(data.join(sub)).expect("test data") {
            let path = entry.expect("test data entry").path();
            let name = path.file_name().expect("a file name").to_string_lossy();
            if endings.iter().any(|e| name.ends_with(e)) {
                fs::copy(&path, dir.join(&*name)).expect("copy a parameter file");
            }
        }
    }
}

/// The files a command says it writes.
fn outputs(words: &[String]) -> Vec<&str> {
    words
        .windows(2)
        .filter(|w| matches!(w[0].as_str(), "--out" | "--plot" | "--report"))
        .map(|w| w[1].as_str())
        .collect()
}

fn chapters() -> Vec<(String, String)> {
    let dir = root().join("docs/guide");
    let mut files: Vec<PathBuf> = fs::read_dir(&dir)
        .expect("docs/guide")
        .map(|e| e.expect("a guide entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let name = p
                .file_stem()
                .expect("a chapter name")
                .to_string_lossy()
                .into();
            (name, fs::read_to_string(&p).expect("a chapter"))
        })
        .collect()
}

#[test]
fn the_splitter_quotes_and_comments() {
    let (words, comment) =
        split(r#"whipple simulate --steer-torque "10*lean + 20" -x 'a b'  # note (fails)"#);
    assert_eq!(
        words,
        [
            "whipple",
            "simulate",
            "--steer-torque",
            "10*lean + 20",
            "-x",
            "a b"
        ]
    );
    assert_eq!(comment, "note (fails)");
    let found = examples(
        "t",
        "text\n```sh\nwhipple a \\\n    b # c\ncargo x\n```\n```text\nwhipple no\n```\n",
    );
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].words, ["a", "b"]);
    assert_eq!(found[0].line, 3);
}

#[test]
fn every_shell_example_of_the_guide_runs() {
    let mut count = 0;
    let mut commands_seen = std::collections::BTreeSet::new();
    for (chapter, text) in chapters() {
        let found = examples(&chapter, &text);
        if found.is_empty() {
            continue;
        }
        let dir = common::scratch(&format!("guide-{chapter}"));
        copy_inputs(&dir);
        for example in found {
            let Example {
                chapter,
                line,
                words,
                fails,
            } = &example;
            if words.first().map(String::as_str) == Some("serve") {
                continue;
            }
            commands_seen.insert(words.first().cloned().unwrap_or_default());
            let done = Command::new(env!("CARGO_BIN_EXE_whipple"))
                .args(words)
                .current_dir(&dir)
                .output()
                .expect("the whipple binary runs");
            let stderr = String::from_utf8_lossy(&done.stderr);
            let place = format!(
                "docs/guide/{chapter}.md:{line}: whipple {}",
                words.join(" ")
            );
            if *fails {
                assert!(
                    !done.status.success(),
                    "{place}: succeeded, the guide says it fails"
                );
                assert!(
                    stderr.contains("error"),
                    "{place}: failed without a message"
                );
            } else {
                assert!(done.status.success(), "{place}: failed:\n{stderr}");
                assert!(
                    !done.stdout.is_empty() || !outputs(words).is_empty(),
                    "{place}: printed nothing and wrote nothing"
                );
                for out in outputs(words) {
                    let path = dir.join(out);
                    assert!(path.exists(), "{place}: did not write {out}");
                }
            }
            count += 1;
        }
    }
    // The guide shows the commands of every chapter: a parser that found few has broken.
    assert!(
        count >= 30,
        "only {count} shell examples found in docs/guide"
    );
    for command in [
        "eig",
        "speeds",
        "modes",
        "matrices",
        "sensitivity",
        "simulate",
        "validate",
        "turn",
        "turns",
        "map",
        "study",
        "merge",
        "convert",
        "show",
        "draw",
        "presets",
    ] {
        assert!(
            commands_seen.contains(command),
            "the guide has no example of `whipple {command}`"
        );
    }
}
