//! Where each key of a scene file sits: the byte span of every value, by its dotted path
//! (`"sheet.width"`, `"tearing.detail.sigma"`), read from the parsed document once. A
//! setting that a model's own `validate()` refuses is reported at the key that set it.

use core::ops::Range;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// The value span of every key of a scene file, by dotted path (tables too; array
/// elements are not listed).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct KeySpans {
    spans: Vec<(String, Range<usize>)>,
}

impl KeySpans {
    /// Every key path of `table` (under the prefix `prefix`, empty at the root).
    #[must_use]
    pub fn of(table: &DeTable<'_>) -> Self {
        let mut out = Self::default();
        out.collect("", table);
        out
    }

    fn collect(&mut self, prefix: &str, table: &DeTable<'_>) {
        for (key, value) in table {
            let path = if prefix.is_empty() {
                key.get_ref().to_string()
            } else {
                format!("{prefix}.{}", key.get_ref())
            };
            if let DeValue::Table(inner) = value.get_ref() {
                self.collect(&path, inner);
            }
            self.spans.push((path, value.span()));
        }
    }

    /// The span of the value at `path`, if the file sets it.
    #[must_use]
    pub fn span(&self, path: &str) -> Option<Range<usize>> {
        self.spans
            .iter()
            .find(|(p, _)| p == path)
            .map(|(_, span)| span.clone())
    }
}

/// Takes the value at `section.key` out of `root` (the scene keys that are no setting of
/// the section's settings type, such as a sheet's notch).
pub fn take<'i>(
    root: &mut Spanned<DeTable<'i>>,
    section: &str,
    key: &str,
) -> Option<Spanned<DeValue<'i>>> {
    let table = root.get_mut().get_mut(section)?;
    match table.get_mut() {
        DeValue::Table(inner) => inner.remove(key),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_value_is_found_at_its_place() {
        let text = "a = 1\n[b]\nc = 2.5\n[b.d]\ne = true\n";
        let doc = DeTable::parse(text).unwrap();
        let keys = KeySpans::of(doc.get_ref());
        assert_eq!(&text[keys.span("a").unwrap()], "1");
        assert_eq!(&text[keys.span("b.c").unwrap()], "2.5");
        assert_eq!(&text[keys.span("b.d.e").unwrap()], "true");
        assert!(keys.span("b.x").is_none());
    }

    #[test]
    fn a_taken_key_is_gone_and_kept() {
        let text = "[s]\nn = [1, 2]\nw = 3\n";
        let mut doc = DeTable::parse(text).unwrap();
        let n = take(&mut doc, "s", "n").unwrap();
        assert_eq!(&text[n.span()], "[1, 2]");
        assert!(take(&mut doc, "s", "n").is_none());
        assert!(take(&mut doc, "t", "n").is_none());
        assert!(KeySpans::of(doc.get_ref()).span("s.w").is_some());
    }
}
