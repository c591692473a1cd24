//! The scene reader: the serde `Deserializer` that turns a parsed TOML document (the
//! `toml` crate's [`DeValue`] tree, every value with its byte span) into the scene types.
//!
//! Why not `toml`'s own deserializer: serde instantiates a format's generic code once for
//! every pair of (format type, visitor type), and `toml` passes a value through several
//! deserializer and access types (document, value, table, array, key, spanned), so the scene schema's few dozen field types made its
//! deserializer and `serde_spanned`'s visitors 45 % of the browser build's code (issue 23:
//! the `.wasm` was 339 KB gzipped, 286 KB with this reader). Here one [`Reader`] reads
//! every value, handing each visitor only the kind of value its type takes; one `Entries`
//! walks every table and every `toml::Spanned` (its start, end and value); one `Elements`
//! every array. What is not generic (numbers, messages, an error's place) is in plain
//! functions.
//!
//! What it reads is what `toml`'s deserializer reads, with the same serde messages at the
//! same places (tests: every built-in scene, and a bad value for each kind of key of the
//! schema, against `toml`'s): an error inside a value is placed at that value's span, an
//! unknown or bad key at the key's, a missing field at its table's. It differs in three
//! ways: an array longer than its Rust type (`[f64; 2]` given three numbers) is refused
//! instead of being cut short, a date or time is refused as the value no scene key takes,
//! and an enum given no string says what it was given ("invalid type: integer `64`,
//! expected enum Precision", where `toml` says "wanted string or table").

use alloc::borrow::Cow;
use alloc::string::{String, ToString};
use alloc::vec;
use core::fmt;
use core::ops::Range;

use serde::de::{self, DeserializeSeed, IntoDeserializer, Unexpected, Visitor};
use serde_spanned::de::is_spanned;
use toml::Spanned;
use toml::de::{DeArray, DeFloat, DeInteger, DeString, DeTable, DeValue};

/// Why a value does not read: a message, at a byte span of the file when it has one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError {
    /// What is wrong (serde's words for a wrong type, an unknown or missing key).
    pub message: String,
    /// The byte range of the file the error is at.
    pub span: Option<Range<usize>>,
}

impl ReadError {
    /// The error placed at `span`, unless it already has a place (the innermost wins).
    fn at(mut self, span: &Range<usize>) -> Self {
        if self.span.is_none() {
            self.span = Some(span.clone());
        }
        self
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl core::error::Error for ReadError {}

impl de::Error for ReadError {
    fn custom<T: fmt::Display>(message: T) -> Self {
        Self {
            message: message.to_string(),
            span: None,
        }
    }
}

/// Reads a `T` from the document (or part of it) `value`.
///
/// # Errors
/// [`ReadError`] at the span of the key or value that does not fit `T`.
pub fn read<'i, T: de::Deserialize<'i>>(value: Spanned<DeValue<'i>>) -> Result<T, ReadError> {
    T::deserialize(Reader::from(value))
}

/// Reads a `T` from the whole document `table`, as [`read`].
///
/// # Errors
/// As [`read`].
pub fn read_table<'i, T: de::Deserialize<'i>>(table: Spanned<DeTable<'i>>) -> Result<T, ReadError> {
    let span = table.span();
    read(Spanned::new(span, DeValue::Table(table.into_inner())))
}

/// One value of the document and its byte span: the deserializer of every value.
pub struct Reader<'i> {
    value: Value<'i>,
    span: Range<usize>,
}

/// What a [`Reader`] reads: a value of the file, or a byte offset of one (the start and
/// end of a `toml::Spanned`).
enum Value<'i> {
    Toml(DeValue<'i>),
    Offset(usize),
}

impl<'i> From<Spanned<DeValue<'i>>> for Reader<'i> {
    fn from(value: Spanned<DeValue<'i>>) -> Self {
        let span = value.span();
        Self {
            value: Value::Toml(value.into_inner()),
            span,
        }
    }
}

/// A TOML integer as serde sees it (TOML integers are 64-bit signed; an unsigned one is
/// taken as far as `u64`).
enum Integer {
    Signed(i64),
    Unsigned(u64),
}

fn integer(v: &DeInteger<'_>) -> Result<Integer, ReadError> {
    let (digits, radix) = (v.as_str(), v.radix());
    if let Ok(i) = i64::from_str_radix(digits, radix) {
        Ok(Integer::Signed(i))
    } else if let Ok(u) = u64::from_str_radix(digits, radix) {
        Ok(Integer::Unsigned(u))
    } else {
        Err(de::Error::custom("integer number overflowed"))
    }
}

/// A TOML float; `inf` and `nan` are TOML's own words, a finite literal that overflows is
/// refused.
fn float(v: &DeFloat<'_>) -> Result<f64, ReadError> {
    let text = v.as_str();
    match text.parse::<f64>() {
        Ok(f) if f.is_finite() || text.contains("inf") || text.contains("nan") => Ok(f),
        _ => Err(de::Error::custom("floating-point number overflowed")),
    }
}

/// What serde calls a value in a message ("invalid type: string \"x\", expected f64").
fn unexpected<'a>(value: &'a Value<'_>) -> Unexpected<'a> {
    let Value::Toml(value) = value else {
        return Unexpected::Other("a byte offset");
    };
    match value {
        DeValue::String(s) => Unexpected::Str(s),
        DeValue::Integer(v) => match integer(v) {
            Ok(Integer::Signed(i)) => Unexpected::Signed(i),
            Ok(Integer::Unsigned(u)) => Unexpected::Unsigned(u),
            Err(_) => Unexpected::Other("an integer"),
        },
        DeValue::Float(v) => float(v).map_or(Unexpected::Other("a float"), Unexpected::Float),
        DeValue::Boolean(b) => Unexpected::Bool(*b),
        DeValue::Datetime(_) => Unexpected::Other("a date or time"),
        DeValue::Array(_) => Unexpected::Seq,
        DeValue::Table(_) => Unexpected::Map,
    }
}

/// `value` is not of the kind the visitor `expected` takes.
fn wrong_type(value: &Value<'_>, expected: &dyn de::Expected) -> ReadError {
    de::Error::invalid_type(unexpected(value), expected)
}

/// The number a value holds, for serde's number visitors: an integer, a float (when
/// `floats`), or an offset; else `None`.
fn number(value: &Value<'_>, floats: bool) -> Option<Result<Number, ReadError>> {
    match value {
        Value::Offset(n) => Some(Ok(Number::Unsigned(*n as u64))),
        Value::Toml(DeValue::Integer(v)) => Some(integer(v).map(|i| match i {
            Integer::Signed(i) => Number::Signed(i),
            Integer::Unsigned(u) => Number::Unsigned(u),
        })),
        Value::Toml(DeValue::Float(v)) if floats => Some(float(v).map(Number::Float)),
        _ => None,
    }
}

/// A number for a visitor.
enum Number {
    Signed(i64),
    Unsigned(u64),
    Float(f64),
}

impl<'de> Reader<'de> {
    /// Calls `visit` with the value, and places an error without a place at the value.
    ///
    /// Each `deserialize_*` method below hands serde's visitor only the kinds of value its
    /// type takes (a number to a number's visitor, a table to a struct's), and refuses the
    /// rest with serde's own message: the generic code per visitor stays small.
    fn visit<T>(
        self,
        visit: impl FnOnce(Value<'de>) -> Result<T, ReadError>,
    ) -> Result<T, ReadError> {
        let span = self.span;
        visit(self.value).map_err(|e| e.at(&span))
    }

    /// A number visited as what it is (integers, and floats when `floats`).
    fn visit_number<V: Visitor<'de>>(
        self,
        visitor: V,
        floats: bool,
    ) -> Result<V::Value, ReadError> {
        self.visit(|value| match number(&value, floats) {
            Some(Ok(Number::Signed(i))) => visitor.visit_i64(i),
            Some(Ok(Number::Unsigned(u))) => visitor.visit_u64(u),
            Some(Ok(Number::Float(f))) => visitor.visit_f64(f),
            Some(Err(e)) => Err(e),
            None => Err(wrong_type(&value, &visitor)),
        })
    }
}

/// The [`Reader`]'s `deserialize_*` methods of the integer types: each visits an integer.
macro_rules! integers {
    ($($method:ident)*) => {
        $(
            fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
                self.visit_number(visitor, false)
            }
        )*
    };
}

impl<'de> de::Deserializer<'de> for Reader<'de> {
    type Error = ReadError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        match &self.value {
            Value::Toml(DeValue::String(_)) => self.deserialize_str(visitor),
            Value::Toml(DeValue::Boolean(_)) => self.deserialize_bool(visitor),
            Value::Toml(DeValue::Array(_)) => self.deserialize_seq(visitor),
            Value::Toml(DeValue::Table(_)) => self.deserialize_map(visitor),
            _ => self.visit_number(visitor, true),
        }
    }

    fn deserialize_bool<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        self.visit(|value| match value {
            Value::Toml(DeValue::Boolean(b)) => visitor.visit_bool(b),
            other => Err(wrong_type(&other, &visitor)),
        })
    }

    // Integers only (serde's integer visitors take no float, and check the range).
    integers! {
        deserialize_i8 deserialize_i16 deserialize_i32 deserialize_i64
        deserialize_u8 deserialize_u16 deserialize_u32 deserialize_u64
    }

    // serde's floats take integers too (`time_step = 1`).
    fn deserialize_f64<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        self.visit_number(visitor, true)
    }

    fn deserialize_f32<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        self.visit_number(visitor, true)
    }

    fn deserialize_str<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        self.visit(|value| match value {
            Value::Toml(DeValue::String(Cow::Borrowed(s))) => visitor.visit_borrowed_str(s),
            Value::Toml(DeValue::String(Cow::Owned(s))) => visitor.visit_string(s),
            other => Err(wrong_type(&other, &visitor)),
        })
    }

    fn deserialize_string<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        self.deserialize_str(visitor)
    }

    // A key, or a struct's field name.
    fn deserialize_identifier<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        self.deserialize_str(visitor)
    }

    fn deserialize_seq<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        self.visit(|value| match value {
            Value::Toml(DeValue::Array(items)) => visit_array(items, visitor),
            other => Err(wrong_type(&other, &visitor)),
        })
    }

    fn deserialize_tuple<V: Visitor<'de>>(
        self,
        _len: usize,
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        self.deserialize_seq(visitor)
    }

    fn deserialize_map<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        self.visit(|value| match value {
            Value::Toml(DeValue::Table(entries)) => visitor.visit_map(Entries::table(entries)),
            other => Err(wrong_type(&other, &visitor)),
        })
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        match fields {
            // `toml::Spanned<T>` asks for its start, its end and its value by these names.
            [start, end, value] if is_spanned(name) => {
                visitor.visit_map(Entries::spanned([start, end, value], self))
            }
            _ => self.deserialize_map(visitor),
        }
    }

    // A value that is there is `Some`; a missing key is `None` (serde's own rule).
    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        let span = self.span.clone();
        visitor.visit_some(self).map_err(|e| e.at(&span))
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        let span = self.span.clone();
        visitor.visit_newtype_struct(self).map_err(|e| e.at(&span))
    }

    // The scene's enums are unit variants written as strings (`model = "dog"`).
    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        self.visit(|value| match value {
            Value::Toml(DeValue::String(name)) => {
                visitor.visit_enum(IntoDeserializer::<ReadError>::into_deserializer(name))
            }
            other => Err(wrong_type(&other, &visitor)),
        })
    }

    serde::forward_to_deserialize_any! {
        i128 u128 char bytes byte_buf unit unit_struct tuple_struct ignored_any
    }
}

/// Visits an array's elements, then refuses the elements the visitor left (a fixed-size
/// array given too many).
fn visit_array<'de, V: Visitor<'de>>(
    items: DeArray<'de>,
    visitor: V,
) -> Result<V::Value, ReadError> {
    let length = items.len();
    let mut elements = Elements {
        items: items.into_iter(),
    };
    let value = visitor.visit_seq(&mut elements)?;
    match elements.items.len() {
        0 => Ok(value),
        left => Err(too_long(length, left)),
    }
}

fn too_long(length: usize, left: usize) -> ReadError {
    de::Error::custom(format!(
        "invalid length {length}, expected {} elements",
        length - left
    ))
}

/// The elements of an array, each read by a [`Reader`].
struct Elements<'i> {
    items: vec::IntoIter<Spanned<DeValue<'i>>>,
}

impl<'de> de::SeqAccess<'de> for Elements<'de> {
    type Error = ReadError;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, ReadError> {
        self.items
            .next()
            .map(|item| seed.deserialize(Reader::from(item)))
            .transpose()
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.items.len())
    }
}

/// The entries a struct's visitor reads, each key and each value by a [`Reader`]: a
/// table's, in the file's order (a key at its own span), or the three of a
/// `toml::Spanned` (the value's start and end offsets, then the value itself).
///
/// One type serves both, so that a `Spanned<T>`'s visitor is instantiated once.
struct Entries<'i> {
    /// What is left to read, last entry first.
    entries: alloc::vec::Vec<(Reader<'i>, Reader<'i>)>,
    value: Option<Reader<'i>>,
}

impl<'i> Entries<'i> {
    fn table(table: DeTable<'i>) -> Self {
        let entries = table
            .into_iter()
            .rev()
            .map(|(key, value)| {
                let span = key.span();
                let key: DeString<'i> = key.into_inner();
                let key = Reader::from(Spanned::new(span, DeValue::String(key)));
                (key, Reader::from(value))
            })
            .collect();
        Self {
            entries,
            value: None,
        }
    }

    fn spanned(names: [&&'static str; 3], value: Reader<'i>) -> Self {
        let span = value.span.clone();
        let at = |v| Reader {
            value: v,
            span: span.clone(),
        };
        let name = |n: &&'static str| at(Value::Toml(DeValue::String(Cow::Borrowed(*n))));
        let entries = alloc::vec![
            (name(names[2]), value),
            (name(names[1]), at(Value::Offset(span.end))),
            (name(names[0]), at(Value::Offset(span.start))),
        ];
        Self {
            entries,
            value: None,
        }
    }
}

impl<'de> de::MapAccess<'de> for Entries<'de> {
    type Error = ReadError;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, ReadError> {
        let Some((key, value)) = self.entries.pop() else {
            return Ok(None);
        };
        self.value = Some(value);
        seed.deserialize(key).map(Some)
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, ReadError> {
        match self.value.take() {
            Some(value) => seed.deserialize(value),
            None => Err(de::Error::custom("a table's value was read before its key")),
        }
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.entries.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Probe {
        a: Spanned<f64>,
        #[serde(default)]
        b: Option<[u32; 2]>,
        c: Option<Spanned<Vec<Spanned<String>>>>,
        d: Option<Kind>,
    }

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(rename_all = "kebab-case")]
    enum Kind {
        One,
        TwoWords,
    }

    fn probe(text: &str) -> Result<Probe, ReadError> {
        read_table(DeTable::parse(text).expect("TOML"))
    }

    fn error_at(text: &str) -> (String, String) {
        let e = probe(text).expect_err("refused");
        let span = e.span.expect("placed");
        (e.message, text[span].to_string())
    }

    #[test]
    fn values_read_with_their_spans() {
        let text = "a = 2\nb = [0x10, 3]\nc = ['x', \"y\\n\"]\nd = 'two-words'\n";
        let p = probe(text).expect("reads");
        assert_eq!(*p.a.get_ref(), 2.0);
        assert_eq!(&text[p.a.span()], "2");
        assert_eq!(p.b, Some([16, 3]));
        let c = p.c.expect("c");
        assert_eq!(&text[c.span()], "['x', \"y\\n\"]");
        assert_eq!(c.get_ref()[1].get_ref(), "y\n");
        assert_eq!(&text[c.get_ref()[0].span()], "'x'");
        assert_eq!(p.d, Some(Kind::TwoWords));
    }

    #[test]
    fn errors_are_placed_where_toml_places_them() {
        // A wrong type at the value, an unknown key at the key, a missing key at its table
        // (the document's span is its start, as in `toml`).
        let (message, at) = error_at("a = 'x'\n");
        assert!(message.contains("invalid type: string \"x\""), "{message}");
        assert_eq!(at, "'x'");
        let (message, at) = error_at("a = 1\nzz = 2\n");
        assert!(message.contains("unknown field `zz`"), "{message}");
        assert_eq!(at, "zz");
        let (message, at) = error_at("b = [1, 2]\n");
        assert!(message.contains("missing field `a`"), "{message}");
        assert_eq!(at, "");
        let (message, at) = error_at("a = 1\nd = 'three'\n");
        assert!(message.contains("unknown variant `three`"), "{message}");
        assert_eq!(at, "'three'");
        let (message, at) = error_at("a = 1\nb = [1, -2]\n");
        assert!(message.contains("invalid value: integer `-2`"), "{message}");
        assert_eq!(at, "-2");
    }

    #[test]
    fn hostile_values_are_refused() {
        let (message, at) = error_at("a = 1\nb = [1, 2, 3]\n");
        assert!(
            message.contains("invalid length 3, expected 2"),
            "{message}"
        );
        assert_eq!(at, "[1, 2, 3]");
        let (message, at) = error_at("a = 1979-05-27\n");
        assert!(message.contains("a date or time"), "{message}");
        assert_eq!(at, "1979-05-27");
        let (message, _) = error_at("a = 1e999\n");
        assert!(message.contains("overflowed"), "{message}");
        let (message, _) = error_at("a = 1\nb = [18446744073709551616, 1]\n");
        assert!(message.contains("overflowed"), "{message}");
        let (message, at) = error_at("a = 1\nd = { one = 1 }\n");
        assert!(message.contains("invalid type"), "{message}");
        assert_eq!(at, "{ one = 1 }");
        // TOML's own infinities and NaN are numbers (the scene's checks refuse them).
        let p = probe("a = -inf\n").expect("reads");
        assert_eq!(*p.a.get_ref(), f64::NEG_INFINITY);
        assert!(probe("a = nan\n").expect("reads").a.get_ref().is_nan());
    }

    /// The scene, its notch and its model's settings (read apart, as `Scene::parse` and
    /// `crate::settings` do), or the first error.
    type Read =
        Result<(crate::scene::Scene, Option<Notch>, Sections), (String, Option<Range<usize>>)>;
    type Notch = Spanned<Vec<Spanned<[f64; 2]>>>;
    type Sections = (
        Option<folio_book::BookSettings<f64>>,
        Option<folio_tearing::sheet::SheetSettings<f64>>,
    );

    /// The document of `text` with its notch and its `[book]` and `[sheet]` taken out.
    fn parts(text: &str) -> [Option<Spanned<DeValue<'_>>>; 4] {
        let mut doc = DeTable::parse(text).expect("TOML");
        let notch = crate::keys::take(&mut doc, "sheet", "notch");
        let book = doc.get_ref().get("book").cloned();
        let sheet = doc.get_ref().get("sheet").cloned();
        let span = doc.span();
        [
            Some(Spanned::new(span, DeValue::Table(doc.into_inner()))),
            notch,
            book,
            sheet,
        ]
    }

    /// The scene as `toml`'s own deserializer reads it: the independent reference.
    fn by_toml(text: &str) -> Read {
        let [doc, notch, book, sheet] = parts(text);
        let error = |e: toml::de::Error| (e.message().to_string(), e.span());
        fn typed<'de, T: de::Deserialize<'de>>(
            v: Option<Spanned<DeValue<'de>>>,
        ) -> Result<Option<T>, toml::de::Error> {
            v.map(|v| T::deserialize(IntoDeserializer::into_deserializer(v)))
                .transpose()
        }
        let scene = typed(doc).map_err(error)?.expect("a document");
        let notch = typed(notch).map_err(error)?;
        let sections = (typed(book).map_err(error)?, typed(sheet).map_err(error)?);
        Ok((scene, notch, sections))
    }

    fn by_reader(text: &str) -> Read {
        let [doc, notch, book, sheet] = parts(text);
        let error = |e: ReadError| (e.message, e.span);
        let typed = |v: Option<Spanned<DeValue<'_>>>| v.map(read).transpose();
        let scene = doc
            .map(read)
            .transpose()
            .map_err(error)?
            .expect("a document");
        let notch = typed(notch).map_err(error)?;
        let book = book.map(read).transpose().map_err(error)?;
        let sheet = sheet.map(read).transpose().map_err(error)?;
        Ok((scene, notch, (book, sheet)))
    }

    /// Every built-in scene reads to the same value as with `toml`'s deserializer.
    #[test]
    fn the_built_in_scenes_read_as_toml_reads_them() {
        for (name, text) in crate::builtin::SCENES {
            let ours = format!("{:?}", by_reader(text).expect(name));
            let reference = format!("{:?}", by_toml(text).expect(name));
            assert_eq!(ours, reference, "{name}");
        }
    }

    /// Bad scenes are refused with `toml`'s message at `toml`'s place, one case for each
    /// kind of value and key of the schema.
    #[test]
    fn bad_scenes_are_refused_as_toml_refuses_them() {
        let base = "name = \"x\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n";
        let cases = [
            "frmes = 3\n",
            "frames = -1\n",
            "frames = 1.5\n",
            "frames = \"3\"\n",
            "effects = \"gravity\"\n",
            "effects = [1, 2]\n",
            "effects = [[\"gravity\"]]\n",
            "[book.solver]\ntime_step = \"x\"\n",
            "[book.solver]\ntime_step = [1]\n",
            "[book]\nquads_across = [1]\n",
            "[book]\nquads_across = -2\n",
            "[book]\nquads_along = { a = 1 }\n",
            "precision = \"f16\"\n",
            "[book.solver]\nconstraint_hessian = 1\n",
            "[book.solver]\nnewton_iterations = 4294967296\n",
            "[book.solver]\nextra = 1\n",
            "[book.params]\npage_width = true\n",
            "[book.params]\nwidth = 1\n",
            "[book.weights]\nbending = \"soft\"\n",
            "[expect]\nfinal_pages = [1, 2]\n",
            "[expect]\ntear_start = \"elsewhere\"\n",
            "[output]\nreport = \"yes\"\n",
            "[[input.events]]\nframe = 1\ngrab = [1.0, \"a\"]\n",
            "[[input.events]]\nframe = 1\nside = \"up\"\n",
            "[[input.events]]\nframe = 1\nwhat = 1\n",
            "[[input.hands]]\nmoves = []\n",
            "[[input.hands]]\nfingers = [[1.0, 2.0]]\nmoves = [{ start = \"now\" }]\n",
            "[sheet]\nnx = -3\n",
            "[sheet]\nmembrane = 3\n",
            "[sheet.tearing]\nestimator = \"guess\"\n",
            "[sheet.tearing.fibers]\nscale = \"x\"\n",
            "[sheet.tearing.nope]\na = 1\n",
        ];
        let mut checked = 0;
        for case in cases {
            let text = match case.strip_prefix("[[input.") {
                Some(_) => format!("name = \"x\"\nmodel = \"dog\"\n{case}"),
                None => format!("{base}{case}"),
            };
            let reference = by_toml(&text).map(|_| ()).expect_err(case);
            let ours = by_reader(&text).map(|_| ()).expect_err(case);
            assert_eq!(ours, reference, "{case}");
            checked += 1;
        }
        assert_eq!(checked, cases.len());
        // An enum given no string: `toml` says "wanted string or table", the reader what it
        // got and what the key takes, at the same place.
        let text = format!("{base}precision = 64\n");
        let reference = by_toml(&text).map(|_| ()).expect_err("enum");
        let ours = by_reader(&text).map(|_| ()).expect_err("enum");
        assert_eq!(ours.1, reference.1);
        assert_eq!(
            ours.0,
            "invalid type: integer `64`, expected enum Precision"
        );
        // And the scene without its `name`, a missing field at the document.
        let text = "model = \"dog\"\ninput = { fixture = \"page-turn\" }\n";
        assert_eq!(
            by_reader(text).map(|_| ()).expect_err("missing"),
            by_toml(text).map(|_| ()).expect_err("missing")
        );
    }
}
