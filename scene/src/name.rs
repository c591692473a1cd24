//! A scene's `name`: one file-name component. `folio run` writes into `out/<name>/` when no
//! `--out` is given, so a name with a path separator or a `..` would write elsewhere; such
//! names are refused when the scene is checked.

/// The longest name (bytes): file systems allow 255 per component.
pub const MAX_NAME_BYTES: usize = 100;

/// Checks that `name` is one file-name component: not empty, at most [`MAX_NAME_BYTES`]
/// bytes, not `.` or `..`, not starting with `.`, and without `/`, `\`, `:` or a control
/// character.
///
/// # Errors
/// What is wrong with the name.
pub fn check(name: &str) -> Result<(), String> {
    let why = if name.is_empty() {
        "is empty"
    } else if name.len() > MAX_NAME_BYTES {
        "is longer than 100 bytes"
    } else if name.starts_with('.') {
        "starts with `.` (`..` would leave the output folder; `.x` would hide it)"
    } else if name.contains(['/', '\\', ':']) {
        "holds a path separator (`/`, `\\` or `:`)"
    } else if name.chars().any(char::is_control) {
        "holds a control character"
    } else {
        return Ok(());
    };
    Err(format!(
        "the scene name {why}: it names the output folder `out/<name>/`, one file-name component"
    ))
}

#[cfg(test)]
mod tests {
    use super::check;

    #[test]
    fn only_single_components_pass() {
        for good in ["page-turn", "a b", "tear_1.v2", "héllo"] {
            assert_eq!(check(good), Ok(()), "{good}");
        }
        for bad in [
            "", ".", "..", "../x", "a/b", "a\\b", "c:x", ".hidden", "a\nb",
        ] {
            assert!(check(bad).is_err(), "{bad}");
        }
        assert!(check(&"x".repeat(101)).is_err());
    }
}
