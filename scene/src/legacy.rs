//! The older spellings of scene keys, read for one release. Since issue 41 a scene's keys
//! are the field names of its model's settings type (`[book]` is `folio_book::BookSettings`,
//! `[spring]`, `[xpbd]` and `[sheet]` the page models' and the sheet's settings). A file in
//! the older spelling (`[weights]`, `[tearing]`, `[book] pages`, the shared `[solver]` table)
//! is rewritten in the parsed document before it is read: each older key's value moves to
//! its new key, keeping its place in the file (an error about it points at what the file
//! wrote), and a [`Notice`] names the new key.

use alloc::string::String;
#[cfg(not(feature = "older-keys"))]
use alloc::vec::Vec;
use core::ops::Range;

#[cfg(not(feature = "older-keys"))]
use toml::{Spanned, de::DeTable};

/// An older key the file uses, at the span of its value, and the message naming its new key.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Notice {
    /// Byte span of the older key's value.
    pub span: Range<usize>,
    /// "`solver.grid` is now `book.quads_across` and `book.quads_along` ...".
    pub message: String,
}

/// Why an older key cannot be read: its span and the message.
pub type Refusal = (Range<usize>, String);

/// Refuses the older keys in a build without them (feature `older-keys`, off in the
/// browser build): the older top-level tables, at their place.
///
/// # Errors
/// The first older table, and where its keys are now.
#[cfg(not(feature = "older-keys"))]
pub fn modernize(doc: &mut Spanned<DeTable<'_>>, _model: &str) -> Result<Vec<Notice>, Refusal> {
    for old in ["solver", "weights", "tearing"] {
        if let Some(value) = doc.get_ref().get(old) {
            return Err((
                value.span(),
                alloc::format!(
                    "`{old}` is an older key, which this build does not read (folio-scene \
                     without its `older-keys` feature): docs/scenes.md, \"Older keys\", \
                     gives its new place"
                ),
            ));
        }
    }
    Ok(Vec::new())
}

#[cfg(feature = "older-keys")]
mod older {
    use super::{Notice, Refusal};
    use alloc::borrow::Cow;
    use alloc::format;
    use alloc::string::String;
    use alloc::vec::Vec;
    use core::ops::Range;

    use toml::Spanned;
    use toml::de::{DeTable, DeValue};

    use crate::scene::ModelKind;

    /// The fields of `folio_book::BookParams`, which older files wrote in `[book]` itself (now
    /// `[book.params]`), with the two older names of its fields.
    const BOOK_PARAMS: [(&str, &str); 11] = [
        ("total_pages", "total_pages"),
        ("pages", "total_pages"),
        ("left_pages", "left_pages"),
        ("page_width", "page_width"),
        ("aspect_ratio", "aspect_ratio"),
        ("page_thickness", "page_thickness"),
        ("thickness", "page_thickness"),
        ("cover", "cover"),
        ("cover_thickness", "cover_thickness"),
        ("cover_overhang", "cover_overhang"),
        ("midline_nodes", "midline_nodes"),
    ];

    /// The section of the model named `model` (`crate::scene::ModelKind::section`).
    fn section(model: &str) -> Option<&'static str> {
        ModelKind::ALL
            .iter()
            .find(|m| m.name() == model)
            .and_then(|m| m.section())
    }

    /// Where the older `[solver]` key `key` lives now in a scene of `model`: new paths, or why
    /// the key does not apply.
    fn solver_key(model: &str, key: &str) -> Result<Vec<String>, String> {
        let page = section(model);
        let dog = |new: &str| {
            if model == "dog" {
                Ok(alloc::vec![format!("book.{new}")])
            } else {
                Err(format!("solver.{key} is for model = \"dog\" only"))
            }
        };
        match key {
            "precision" => Ok(alloc::vec!["precision".into()]),
            "time_step" => match (model, page) {
                ("dog", _) => dog("solver.time_step"),
                (_, Some(s)) => Ok(alloc::vec![format!("{s}.time_step")]),
                _ => Err("[solver] is for the dog, mass-spring, xpbd and sheet models".into()),
            },
            "newton_iterations" | "constraint_hessian" | "krylov_restart" => {
                dog(&format!("solver.{key}"))
            }
            "newton_tolerance" => dog("solver.tolerance"),
            "max_corrections" => dog("projection_iterations"),
            "collision_rounds" => dog("collision_rounds"),
            "substeps" => match model {
                "mass-spring" | "xpbd" => {
                    Ok(alloc::vec![format!("{}.substeps", page.unwrap_or(""))])
                }
                _ => Err("solver.substeps is for model = \"mass-spring\" or \"xpbd\" only".into()),
            },
            "integrator" if model == "mass-spring" => Ok(alloc::vec!["spring.integrator".into()]),
            "integrator" => Err("solver.integrator is for model = \"mass-spring\" only".into()),
            "grid" => match model {
                "dog" | "xpbd" => {
                    let s = page.unwrap_or("");
                    Ok(alloc::vec![
                        format!("{s}.quads_across"),
                        format!("{s}.quads_along")
                    ])
                }
                "mass-spring" => Ok(alloc::vec![
                    "spring.particles_across".into(),
                    "spring.particles_along".into(),
                ]),
                "sheet" => Err(
                    "solver.grid is for the dog, mass-spring and xpbd models; a sheet \
                                sets its quads with sheet.nx and sheet.ny"
                        .into(),
                ),
                _ => Err("solver.grid is for the dog, mass-spring and xpbd models".into()),
            },
            _ => Err(format!("unknown key `solver.{key}`")),
        }
    }

    /// A value to put at `path`, at `span` of the file.
    struct Move<'i> {
        path: Vec<String>,
        span: Range<usize>,
        value: DeValue<'i>,
    }

    /// Rewrites the older keys of `doc` (a scene file of `model`, if it names one) into the
    /// new ones, and returns a notice for each.
    ///
    /// # Errors
    /// An older key that does not apply to the model, or whose new key the file also sets.
    pub fn modernize(doc: &mut Spanned<DeTable<'_>>, model: &str) -> Result<Vec<Notice>, Refusal> {
        let mut notices = Vec::new();
        let mut moves = Vec::new();
        let root = doc.get_mut();
        for (old, new) in [("weights", "book.weights"), ("tearing", "sheet.tearing")] {
            if let Some((_, value)) = root.remove_entry(old) {
                notices.push(notice(&value.span(), old, &[new]));
                let span = value.span();
                moves.push(Move {
                    path: split(new),
                    span,
                    value: value.into_inner(),
                });
            }
        }
        if let Some(book) = root.get_mut("book") {
            if let DeValue::Table(table) = book.get_mut() {
                for (old, new) in BOOK_PARAMS {
                    if let Some((_, value)) = table.remove_entry(old) {
                        let new = format!("book.params.{new}");
                        notices.push(notice(&value.span(), &format!("book.{old}"), &[&new]));
                        let span = value.span();
                        moves.push(Move {
                            path: split(&new),
                            span,
                            value: value.into_inner(),
                        });
                    }
                }
            }
        }
        if let Some((_, solver)) = root.remove_entry("solver") {
            let span = solver.span();
            let DeValue::Table(table) = solver.into_inner() else {
                return Err((span, "solver must be a table".into()));
            };
            if section(model).is_none() {
                return Err((
                    span,
                    "[solver] is for the dog, mass-spring, xpbd and sheet models".into(),
                ));
            }
            solver_moves(model, table, &mut moves, &mut notices)?;
        }
        for m in moves {
            put(root, m)?;
        }
        notices.sort_by_key(|n| n.span.start);
        Ok(notices)
    }

    /// The moves of the older `[solver]` table's keys.
    fn solver_moves<'i>(
        model: &str,
        table: DeTable<'i>,
        moves: &mut Vec<Move<'i>>,
        notices: &mut Vec<Notice>,
    ) -> Result<(), Refusal> {
        let projection = table
            .get("projection")
            .map(|p| (p.span(), p.get_ref().as_bool()));
        let corrections = table.get("max_corrections").map(Spanned::span);
        for (key, value) in table {
            let (name, span) = (key.get_ref().as_ref(), value.span());
            let old = format!("solver.{name}");
            if name == "projection" {
                continue;
            }
            let paths = solver_key(model, name).map_err(|m| (span.clone(), m))?;
            let names: Vec<&str> = paths.iter().map(String::as_str).collect();
            notices.push(notice(&span, &old, &names));
            let values = match (name, value.into_inner()) {
                ("grid", DeValue::Array(items)) if items.len() == 2 => {
                    let spring = model == "mass-spring";
                    let mut out = Vec::new();
                    for item in items.iter() {
                        // A mass-spring page counts particles, one more than quads.
                        out.push(if spring {
                            plus_one(item).ok_or_else(|| {
                                (
                                    span.clone(),
                                    "solver.grid = [across, along] quads, each between 2 and 64"
                                        .into(),
                                )
                            })?
                        } else {
                            item.get_ref().clone()
                        });
                    }
                    out
                }
                ("grid", _) => {
                    return Err((span, "solver.grid = [across, along] quads".into()));
                }
                (_, value) => alloc::vec![value],
            };
            for (path, value) in paths.iter().zip(values) {
                moves.push(Move {
                    path: split(path),
                    span: span.clone(),
                    value,
                });
            }
        }
        if let Some((span, on)) = projection {
            if model != "dog" {
                return Err((span, "solver.projection is for model = \"dog\" only".into()));
            }
            let Some(on) = on else {
                return Err((span, "solver.projection must be true or false".into()));
            };
            notices.push(notice(
                &span,
                "solver.projection",
                &["book.projection_iterations"],
            ));
            match (on, corrections.map(|_| older_corrections(moves))) {
                (false, None) => moves.push(Move {
                    path: split("book.projection_iterations"),
                    span,
                    value: number(0).unwrap_or(DeValue::Boolean(false)),
                }),
                (true, Some(n)) if n != Some(0) => {}
                (false, Some(Some(0))) | (true, None) => {}
                (true, Some(_)) => {
                    return Err((
                        span,
                        "solver.projection = true needs solver.max_corrections of at least 1 \
                         (max_corrections = 0 switches the projection off); both are now \
                         book.projection_iterations"
                            .into(),
                    ));
                }
                (false, Some(_)) => {
                    return Err((
                        span,
                        "solver.projection = false switches the projection off: leave out \
                         solver.max_corrections (or set it to 0); both are now \
                         book.projection_iterations"
                            .into(),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The older `max_corrections` value among the moves.
    fn older_corrections(moves: &[Move<'_>]) -> Option<i64> {
        moves
            .iter()
            .find(|m| m.path.last().is_some_and(|k| k == "projection_iterations"))
            .and_then(|m| integer(&m.value))
    }

    /// The value of a TOML integer.
    fn integer(value: &DeValue<'_>) -> Option<i64> {
        let i = value.as_integer()?;
        i64::from_str_radix(i.as_str(), i.radix()).ok()
    }

    /// The integers 0 to 65 as TOML text: [`number`]'s values borrow no file.
    const NUMBERS: &str = "0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 \
    28 29 30 31 32 33 34 35 36 37 38 39 40 41 42 43 44 45 46 47 48 49 50 51 52 53 54 55 56 57 58 \
    59 60 61 62 63 64 65";

    /// The TOML integer `n`, for `n` in 0 to 65 (an older grid's quads plus one, or no
    /// projection).
    fn number(n: i64) -> Option<DeValue<'static>> {
        let text = NUMBERS.split(' ').nth(usize::try_from(n).ok()?)?;
        DeValue::parse(text).ok().map(Spanned::into_inner)
    }

    /// The older grid's quads `item` plus one: the particles of a mass-spring page.
    fn plus_one(item: &Spanned<DeValue<'_>>) -> Option<DeValue<'static>> {
        let n = integer(item.get_ref())?;
        // The older key took 2 to 64 quads.
        (2..=64).contains(&n).then(|| number(n + 1))?
    }

    /// `a.b.c` as its segments.
    fn split(path: &str) -> Vec<String> {
        path.split('.').map(String::from).collect()
    }

    /// The notice that `old` is now `new`.
    fn notice(span: &Range<usize>, old: &str, new: &[&str]) -> Notice {
        let names: Vec<String> = new.iter().map(|n| format!("`{n}`")).collect();
        Notice {
            span: span.clone(),
            message: format!(
                "`{old}` is the older spelling of {}: it is read until the next release",
                names.join(" and ")
            ),
        }
    }

    /// Puts `m.value` at `m.path` of `root`, creating its tables.
    fn put<'i>(root: &mut DeTable<'i>, m: Move<'i>) -> Result<(), Refusal> {
        let Some((last, tables)) = m.path.split_last() else {
            return Ok(());
        };
        let mut table = root;
        for (depth, name) in tables.iter().enumerate() {
            let entry = table
                .entry(Spanned::new(m.span.clone(), Cow::Owned(name.clone())))
                .or_insert_with(|| Spanned::new(m.span.clone(), DeValue::Table(DeTable::new())));
            let DeValue::Table(inner) = entry.get_mut() else {
                let at = tables[..=depth].join(".");
                return Err((m.span, format!("{at} must be a table")));
            };
            table = inner;
        }
        let key = Spanned::new(m.span.clone(), Cow::Owned(last.clone()));
        if table.contains_key(last.as_str()) {
            let path = m.path.join(".");
            return Err((
                m.span,
                format!("the file sets `{path}` twice: in its older spelling and its new one"),
            ));
        }
        table.insert(key, Spanned::new(m.span, m.value));
        Ok(())
    }
}

#[cfg(feature = "older-keys")]
pub use older::modernize;
