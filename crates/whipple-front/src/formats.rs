//! The parameter file formats as help texts and messages list them, generated from the
//! library's one list ([`whipple::advanced::io::FORMATS`] and [`Format::extensions`]), never
//! restated.

use whipple::advanced::io::{FORMATS, Format};

/// The formats' names, in the library's order, comma separated: `toml, json, m, bp-txt,
/// hc-txt, yaml`.
pub fn names() -> String {
    FORMATS.map(|(_, name, _)| name).join(", ")
}

/// Every format's name and what it is, one per line (`toml: TOML, whipple's …`).
pub fn described() -> String {
    FORMATS
        .map(|(_, name, what)| format!("{name}: {what}"))
        .join("\n")
}

/// Every file name extension a format has, with its dot, each once, in the library's order:
/// `.toml`, `.json`, `.m`, `.txt`, `.yml`, `.yaml`.
pub fn extensions() -> Vec<String> {
    let mut all: Vec<String> = Vec::new();
    for extension in FORMATS.iter().flat_map(|(f, _, _)| Format::extensions(*f)) {
        let dotted = format!(".{extension}");
        if !all.contains(&dotted) {
            all.push(dotted);
        }
    }
    all
}

/// The extensions as a list in words: `.toml, .json, .m, .txt, .yml or .yaml`.
pub fn extensions_in_words() -> String {
    let all = extensions();
    match all.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        Some((last, _)) => last.clone(),
        None => String::new(),
    }
}

/// The help of an option taking a bicycle: `A preset name or a parameter file (.toml, .json,
/// .m, .txt, .yml, .yaml)` (no full stop, as clap prints one-line helps).
pub fn bike_help() -> String {
    format!(
        "A preset name or a parameter file ({})",
        extensions().join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every format the readers take is listed, each extension once.
    #[test]
    fn lists_come_from_the_library() {
        assert_eq!(names(), "toml, json, m, bp-txt, hc-txt, yaml");
        assert_eq!(
            extensions(),
            [".toml", ".json", ".m", ".txt", ".yml", ".yaml"]
        );
        assert_eq!(
            extensions_in_words(),
            ".toml, .json, .m, .txt, .yml or .yaml"
        );
        assert_eq!(
            bike_help(),
            "A preset name or a parameter file (.toml, .json, .m, .txt, .yml, .yaml)"
        );
        for (format, name, _) in FORMATS {
            assert!(described().contains(&format!("{name}: ")), "{format:?}");
        }
    }

    /// An extension names a format when one format has it; `.txt` does not (the content
    /// decides between BicycleParameters and HumanControl).
    #[test]
    fn extensions_name_their_format() {
        for (format, _, _) in FORMATS {
            for extension in format.extensions() {
                let named = Format::from_extension(extension);
                if *extension == "txt" {
                    assert_eq!(named, None);
                } else {
                    assert_eq!(named, Some(format), "{extension}");
                    assert_eq!(
                        Format::from_extension(&extension.to_uppercase()),
                        Some(format)
                    );
                }
            }
        }
        assert_eq!(Format::from_extension("csv"), None);
    }
}
