//! The user guide's and the README's shell examples run exactly as written from an install:
//! every line of a ```sh block in docs/guide/*.md and README.md that starts with `whipple `, and
//! every `$ whipple ` line of a guide's ```output block (whose output docs/hooks/outputs.py
//! inserts at build time), is run against the real binary, page by page in an empty scratch
//! directory (so later commands read what earlier ones wrote, and the field's files only after
//! the page's own `whipple examples --out .`). A command must succeed and write every `--out`,
//! `--plot` and `--report` it names, unless its comment says `(fails)` or it ends an
//! ```output fails block: then it must fail with a message. `whipple serve` (which runs until
//! stopped) is the only command not run; the web page has its own tests in crates/whipple-web.
//! The README's ```text blocks that begin with `$ whipple ` show exactly what the command
//! prints today (`WHIPPLE_UPDATE_README=1` writes them again).

use crate::common;

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

/// Which kind of fenced block a line is in.
#[derive(Clone, Copy, PartialEq)]
enum Block {
    Prose,
    Shell,
    Output { fails: bool },
    Other,
}

/// Every `whipple ...` line of the ```sh blocks of one page and every `$ whipple ...` line of
/// its ```output blocks (lines ending in `\` continued).
fn examples(chapter: &str, text: &str) -> Vec<Example> {
    let mut found: Vec<Example> = Vec::new();
    let mut block = Block::Prose;
    let mut pending: Option<(usize, String)> = None;
    for (n, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.starts_with("```") {
            if let Block::Output { fails: true } = block {
                if let Some(last) = found.last_mut() {
                    last.fails = true;
                }
            }
            block = match (block, trimmed) {
                (Block::Prose, "```sh") => Block::Shell,
                (Block::Prose, "```output") => Block::Output { fails: false },
                (Block::Prose, "```output fails") => Block::Output { fails: true },
                (Block::Prose, _) => Block::Other,
                _ => Block::Prose,
            };
            continue;
        }
        let trimmed = match block {
            Block::Shell => trimmed,
            Block::Output { .. } => match (trimmed.strip_prefix("$ "), &pending) {
                (Some(command), None) => command,
                (None, Some(_)) => trimmed,
                _ => panic!(
                    "{chapter}:{}: an output block holds `$ whipple` lines only",
                    n + 1
                ),
            },
            Block::Prose | Block::Other => continue,
        };
        let (start, joined) = match pending.take() {
            Some((start, before)) => (start, format!("{before} {trimmed}")),
            None => (n + 1, trimmed.to_string()),
        };
        if let Some(head) = joined.strip_suffix('\\') {
            pending = Some((start, head.trim_end().to_string()));
            continue;
        }
        if !joined.starts_with("whipple ") {
            assert!(
                block == Block::Shell,
                "{chapter}:{start}: an output block holds `$ whipple` lines only"
            );
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

/// The files a command says it writes.
fn outputs(words: &[String]) -> Vec<&str> {
    words
        .windows(2)
        .filter(|w| matches!(w[0].as_str(), "--out" | "--plot" | "--report"))
        .map(|w| w[1].as_str())
        .collect()
}

/// The pages whose examples run, as (path from the repository's root, text): the guide's
/// chapters and the README.
fn chapters() -> Vec<(String, String)> {
    let mut pages = guide_chapters();
    pages.push((
        "README.md".into(),
        fs::read_to_string(root().join("README.md")).expect("the README"),
    ));
    pages
}

fn guide_chapters() -> Vec<(String, String)> {
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
            let name = p.file_name().expect("a chapter name").to_string_lossy();
            (
                format!("docs/guide/{name}"),
                fs::read_to_string(&p).expect("a chapter"),
            )
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
        let scratch_name = chapter.replace(['/', '.'], "-");
        // Empty, as a reader's folder is: a page reads the field's files only after its own
        // `whipple examples --out .`.
        let dir = common::scratch(&format!("guide-{scratch_name}"));
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
            let place = format!("{chapter}:{line}: whipple {}", words.join(" "));
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

/// A README block that shows output: ```text whose first line is `$ whipple ...`; its start and
/// end (byte offsets of the text between the fences) and the command's words.
fn readme_outputs(text: &str) -> Vec<(usize, usize, Vec<String>)> {
    let mut found = Vec::new();
    let mut rest = 0;
    while let Some(open) = text[rest..].find("```text\n$ whipple ") {
        let start = rest + open + "```text\n".len();
        let end = start
            + text[start..]
                .find("\n```")
                .expect("a closed ```text block in the README")
            + 1;
        let first = text[start..end].lines().next().unwrap_or_default();
        let (words, _) = split(&first["$ ".len()..]);
        found.push((start, end, words[1..].to_vec()));
        rest = end;
    }
    found
}

/// The README's output blocks show exactly what their commands print today (standard output,
/// then standard error), run in an empty folder as a newcomer would; its figures under
/// docs/readme are exactly what the README's command that names them draws.
/// `WHIPPLE_UPDATE_README=1` writes both again.
#[test]
fn the_readme_shows_what_its_commands_print() {
    let path = root().join("README.md");
    let text = fs::read_to_string(&path).expect("the README");
    let update = std::env::var_os("WHIPPLE_UPDATE_README").is_some();
    let dir = common::scratch("guide-readme-outputs");
    let mut fresh = text.clone();
    let blocks = readme_outputs(&text);
    assert!(!blocks.is_empty(), "the README shows no command's output");
    for (start, end, words) in blocks.into_iter().rev() {
        let done = Command::new(env!("CARGO_BIN_EXE_whipple"))
            .args(&words)
            .current_dir(&dir)
            .output()
            .expect("the whipple binary runs");
        assert!(
            done.status.success(),
            "README: whipple {}: {}",
            words.join(" "),
            String::from_utf8_lossy(&done.stderr)
        );
        let shown = format!(
            "$ whipple {}\n{}{}",
            words.join(" "),
            String::from_utf8_lossy(&done.stdout),
            String::from_utf8_lossy(&done.stderr)
        );
        if update {
            fresh.replace_range(start..end, &shown);
        } else {
            assert_eq!(
                text[start..end],
                shown,
                "README.md shows an old output of `whipple {}`: \
                 WHIPPLE_UPDATE_README=1 cargo test -p whipple-cli --test suite -- guide:: writes it again",
                words.join(" ")
            );
        }
    }
    let mut figures = 0;
    for shown in text.split("](docs/readme/").skip(1) {
        let name = &shown[..shown.find(')').expect("a closed image link")];
        let (_, _, words) = examples("README.md", &text)
            .into_iter()
            .map(|e| (e.chapter, e.line, e.words))
            .find(|(_, _, w)| w.windows(2).any(|p| p[0] == "--plot" && p[1] == name))
            .unwrap_or_else(|| panic!("no README command draws docs/readme/{name}"));
        let done = Command::new(env!("CARGO_BIN_EXE_whipple"))
            .args(&words)
            .current_dir(&dir)
            .output()
            .expect("the whipple binary runs");
        assert!(done.status.success(), "README: whipple {}", words.join(" "));
        let drawn = fs::read(dir.join(name)).expect("the figure drawn");
        let kept = root().join("docs/readme").join(name);
        if update {
            fs::write(&kept, &drawn).expect("write the README's figure");
        } else {
            assert!(
                fs::read(&kept).ok().as_deref() == Some(&drawn[..]),
                "docs/readme/{name} is not what `whipple {}` draws today: \
                 WHIPPLE_UPDATE_README=1 cargo test -p whipple-cli --test suite -- guide:: writes it again",
                words.join(" ")
            );
        }
        figures += 1;
    }
    assert!(figures >= 1, "the README shows no figure drawn by whipple");
    if update && fresh != text {
        fs::write(&path, fresh).expect("write the README");
    }
}
