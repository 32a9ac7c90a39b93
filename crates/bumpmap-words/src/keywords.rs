//! A message in the words of a keyword-argument API (the Python package's): each option named
//! as the command line names it, `--bump-scale`, becomes the keyword `bump_scale`. The messages
//! are written once, naming flags; this is how the other skin says them.

/// A keyword's name for an option's long name: `bump-scale` → `bump_scale`.
pub fn keyword(long: &str) -> String {
    long.replace('-', "_")
}

/// `message` in keyword-argument words: each `--long-name` (and its `<VALUE>` placeholder) becomes the
/// keyword `long_name`.
pub fn as_keywords(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(i) = rest.find("--") {
        let (before, after) = rest.split_at(i);
        out.push_str(before);
        let name_len = after[2..]
            .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
            .unwrap_or(after.len() - 2);
        let starts_word = before.is_empty() || before.ends_with([' ', '\'', '(', '"', ',', '`', '[', '/']);
        if name_len == 0
            || !starts_word
            || !after[2..].starts_with(|c: char| c.is_ascii_lowercase())
            || in_quoted_command(&out)
        {
            out.push_str("--");
            rest = &after[2..];
            continue;
        }
        out.push_str(&keyword(&after[2..2 + name_len]));
        rest = &after[2 + name_len..];
        // `--scale <SCALE>`: the placeholder goes too.
        if let Some(p) = rest.strip_prefix(" <")
            && let Some(end) = p.find('>')
            && p[..end].chars().all(|c| c.is_ascii_uppercase() || c == '_' || c == '.')
        {
            rest = &p[end + 1..];
        }
    }
    out.push_str(rest);
    out
}

/// Whether text ending in `so_far` is inside a backticked command line (`` `normalmap
/// --height-out` ``): one that opens with a word, not a flag. Its flags are the command's, and
/// stay flags.
fn in_quoted_command(so_far: &str) -> bool {
    so_far.matches('`').count() % 2 == 1
        && so_far.rfind('`').is_some_and(|i| so_far[i + 1..].starts_with(|c: char| c.is_ascii_alphabetic()))
}

#[cfg(test)]
mod tests {
    use super::as_keywords;

    #[test]
    fn flags_become_keywords_and_lose_their_placeholders() {
        assert_eq!(as_keywords("--bump-scale must be ≥ 0"), "bump_scale must be ≥ 0");
        assert_eq!(as_keywords("use --scale <SCALE> here"), "use scale here");
        assert_eq!(as_keywords("(--size, or --width and --height)"), "(size, or width and height)");
    }

    #[test]
    fn a_quoted_command_keeps_its_flags_and_a_quoted_flag_is_a_keyword() {
        let command = "what `normalmap --height-out` writes";
        assert_eq!(as_keywords(command), command);
        assert_eq!(
            as_keywords("`bumpmap render --technique pom --size 64`"),
            "`bumpmap render --technique pom --size 64`"
        );
        assert_eq!(as_keywords("use `--scale` or --depth"), "use `scale` or depth");
        assert_eq!(as_keywords("`a --b` then --c-d"), "`a --b` then c_d");
    }

    #[test]
    fn dashes_that_are_no_flag_stay() {
        assert_eq!(as_keywords("a--b and -- alone and --X"), "a--b and -- alone and --X");
        assert_eq!(as_keywords("ends with --"), "ends with --");
    }
}
