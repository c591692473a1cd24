//! A DOG scene's `paper` (`docs/scenes.md`, "Paper"): the page's paper in physical units,
//! a built-in stock by name or a stock's figures, given to the book by
//! `folio_book::Paper::apply` over the book's `[book]` settings.
//!
//! ```toml
//! paper = "novel"        # a built-in stock (folio_book::Stock::BUILT_IN), or "seed-card"
//!
//! [paper]                # or the figures, each over the named stock's (all, without one)
//! stock = "novel"
//! grammage = 80.0        # g/m²
//! caliper = 1.1e-4       # m
//! young_across = 3e9     # Pa, across the grain
//! poisson = 0.3
//! page_width = 0.210     # m, binding to fore-edge (default A5's 0.148)
//! ```
//!
//! The page is `page_width` wide and as tall as the book's aspect ratio makes it, so a
//! scene's gestures (in page units) keep their place: only the page's stiffness against its
//! weight (the sag number) and its thickness change. `"seed-card"` is the book's own
//! page, the seed's weights as they are (a sag number of 0.24, a card of about 400 g/m²),
//! which a scene that names no paper also gets.

use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::ops::Range;

use folio_book::{Paper, Stock};
use serde::Deserialize;
use toml::Spanned;
use toml::de::DeValue;

use crate::reader;

/// The name of the book's own page (module docs).
pub const SEED_CARD: &str = "seed-card";

/// Width of an A5 page (ISO 216), m: the page a scene's paper is cut to by default.
pub const A5_WIDTH: f64 = 0.148;

/// The `[paper]` table: a stock's figures over the named stock's.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct PaperTable {
    stock: Option<Spanned<String>>,
    grammage: Option<f64>,
    caliper: Option<f64>,
    young_across: Option<f64>,
    poisson: Option<f64>,
    page_width: Option<f64>,
}

/// Every name `paper` takes, for messages: `seed-card` and the built-in stocks.
#[must_use]
pub fn names() -> String {
    let mut all: Vec<&str> = Vec::from([SEED_CARD]);
    all.extend(Stock::BUILT_IN.iter().map(|(name, _)| *name));
    all.join(", ")
}

/// The paper a scene's `paper` value describes, for a book whose page height is
/// `aspect_ratio` times its width: `None` for `"seed-card"`.
///
/// # Errors
/// An unknown name, an unknown key, a missing figure (a table without `stock` needs
/// `grammage`, `caliper` and `young_across`) or a figure the stock refuses
/// ([`Stock::validate`], [`Paper::validate`]): the span to point at and the message.
pub(crate) fn paper_of(
    value: Spanned<DeValue<'_>>,
    aspect_ratio: f64,
) -> Result<Option<Paper>, (Range<usize>, String)> {
    let span = value.span();
    let unknown = |name: &str, at: Range<usize>| {
        (
            at,
            format!("paper: no paper called `{name}`; one of {}", names()),
        )
    };
    let table = match value.get_ref().as_str() {
        Some(name) => PaperTable {
            stock: Some(Spanned::new(span.clone(), name.to_string())),
            ..PaperTable::default()
        },
        None if !matches!(value.get_ref(), DeValue::Table(_)) => {
            return Err((
                span,
                format!(
                    "paper: a paper's name (one of {}) or a [paper] table of figures",
                    names()
                ),
            ));
        }
        None => reader::read::<PaperTable>(value)
            .map_err(|e| (e.span.unwrap_or(span.clone()), e.message.trim().to_string()))?,
    };
    let base = match &table.stock {
        Some(name) if name.get_ref() == SEED_CARD => {
            let figures = table.grammage.is_some()
                || table.caliper.is_some()
                || table.young_across.is_some()
                || table.poisson.is_some()
                || table.page_width.is_some();
            return if figures {
                Err((
                    name.span(),
                    "paper: the seed's card is the book's own weights; it takes no figures"
                        .to_string(),
                ))
            } else {
                Ok(None)
            };
        }
        Some(name) => {
            Some(Stock::named(name.get_ref()).ok_or_else(|| unknown(name.get_ref(), name.span()))?)
        }
        None => None,
    };
    let figure = |given: Option<f64>, of_base: Option<f64>, key: &str| {
        given.or(of_base).ok_or_else(|| {
            (
                span.clone(),
                format!("paper.{key}: a paper without a `stock` gives every figure"),
            )
        })
    };
    let stock = Stock {
        grammage: figure(table.grammage, base.map(|b| b.grammage), "grammage")?,
        caliper: figure(table.caliper, base.map(|b| b.caliper), "caliper")?,
        young_across: figure(
            table.young_across,
            base.map(|b| b.young_across),
            "young_across",
        )?,
        poisson: table.poisson.or(base.map(|b| b.poisson)).unwrap_or(0.3),
    };
    let refused = |e: folio_kernels::setting::SettingError| (span.clone(), e.to_string());
    stock.validate().map_err(refused)?;
    let width = table.page_width.unwrap_or(A5_WIDTH);
    let paper = stock.cut(width, width * aspect_ratio);
    paper.validate().map_err(|e| match e.path.field() {
        "paper.width" => (span.clone(), e.named("paper.page_width").to_string()),
        _ => refused(e),
    })?;
    Ok(Some(paper))
}

#[cfg(test)]
mod tests {
    use folio_book::{BookSettings, Stock};

    use super::A5_WIDTH;
    use crate::scene::Scene;
    use crate::settings::book_settings;

    const DOG: &str = "name = \"x\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n";

    /// The book of the scene `DOG` + `extra`, in f64.
    fn book(extra: &str) -> BookSettings<f64> {
        let scene = Scene::parse(&format!("{DOG}{extra}")).unwrap_or_else(|e| panic!("{e}"));
        book_settings(&scene).unwrap()
    }

    /// The refusal of `DOG` + `extra`: line, column, message.
    fn refused(extra: &str) -> (usize, usize, String) {
        let e = Scene::parse(&format!("{DOG}{extra}")).expect_err(extra);
        (e.line, e.column, e.message)
    }

    /// The sag number of the book's own page ([`BookSettings::sag_number`]).
    fn sag_number(s: &BookSettings<f64>) -> f64 {
        s.sag_number()
    }

    #[test]
    fn a_named_stock_gives_the_book_its_sag_number_and_thickness() {
        let seed = book("");
        let aspect = seed.params.aspect_ratio;
        for (name, stock) in Stock::BUILT_IN {
            let s = book(&format!("paper = \"{name}\"\n"));
            let paper = stock.cut(A5_WIDTH, A5_WIDTH * aspect);
            let alpha = sag_number(&s);
            assert!(
                (alpha / paper.sag_number() - 1.0).abs() < 1e-12,
                "{name}: {alpha}"
            );
            let thickness = stock.caliper / A5_WIDTH * seed.params.page_width;
            assert!(
                (s.params.page_thickness / thickness - 1.0).abs() < 1e-12,
                "{name}"
            );
            // The page keeps its size in page units, so the scene's gestures keep their place.
            assert_eq!(s.params.page_width, seed.params.page_width, "{name}");
            assert!(
                (s.params.aspect_ratio / aspect - 1.0).abs() < 1e-12,
                "{name}"
            );
            // The page keeps its weight and every weight tuned to it; its bending is the
            // paper's, under the projected isometry Hessian where it is softer than the
            // exact one holds.
            assert_eq!(s.page_mass, seed.page_mass, "{name}");
            let others = |w: folio_book::Weights<f64>| [w.bend_blocks, w.glue, w.iso_page, w.pull];
            assert_eq!(others(s.weights), others(seed.weights), "{name}");
            let soft = folio_book::IsometryHessian::for_bend_page(s.weights.bend_page)
                == folio_book::IsometryHessian::Projected;
            let projected = s.isometry_hessian == folio_book::IsometryHessian::Projected;
            assert_eq!(projected, soft, "{name}");
            assert_eq!(s.validate(), Ok(()), "{name}");
        }
    }

    #[test]
    fn the_seed_card_is_the_book_as_it_is() {
        assert_eq!(book("paper = \"seed-card\"\n"), book(""));
        // The seed's page, as documented: a sag number of 0.24.
        assert!((sag_number(&book("")) - 0.24).abs() < 0.005);
    }

    #[test]
    fn figures_replace_the_named_stocks() {
        let novel = sag_number(&book("paper = \"novel\"\n"));
        // Twice the grammage: twice the weight against the same D.
        let heavy = sag_number(&book("[paper]\nstock = \"novel\"\ngrammage = 140.0\n"));
        assert!((heavy / novel - 2.0).abs() < 1e-12, "{heavy} {novel}");
        // A page 1.5 times as wide: alpha grows as L^3.
        let wide = sag_number(&book(&format!(
            "[paper]\nstock = \"novel\"\npage_width = {}\n",
            1.5 * A5_WIDTH
        )));
        assert!((wide / novel - 3.375).abs() < 1e-9, "{wide} {novel}");
        // Every figure given, no stock: the stock of those figures.
        let n = Stock::NOVEL;
        let own = sag_number(&book(&format!(
            "[paper]\ngrammage = {}\ncaliper = {}\nyoung_across = {}\n",
            n.grammage, n.caliper, n.young_across
        )));
        assert!((own / novel - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bad_paper_is_refused_at_its_key() {
        let (line, column, message) = refused("paper = \"newsprint\"\n");
        assert_eq!((line, column), (4, 9), "{message}");
        assert!(message.contains("newsprint") && message.contains("seed-card, bible, novel"));
        let (line, _, message) = refused("[paper]\nstock = \"novel\"\ngrammage = -3.0\n");
        assert_eq!(line, 4, "{message}");
        assert!(
            message.contains("paper.grammage") && message.contains("-3"),
            "{message}"
        );
        let (_, _, message) = refused("[paper]\ngrammage = 80.0\nyoung_across = 3e9\n");
        assert!(message.contains("paper.caliper"), "{message}");
        let (line, column, message) = refused("[paper]\nstock = \"novel\"\ncolour = 3\n");
        assert_eq!((line, column), (6, 1), "{message}");
        let (_, _, message) = refused("[paper]\nstock = \"novel\"\npage_width = 0.0\n");
        assert!(message.contains("paper.page_width"), "{message}");
        let (_, _, message) = refused("[paper]\nstock = \"novel\"\npoisson = 0.5\n");
        assert!(message.contains("paper.poisson"), "{message}");
        let (_, _, message) = refused("[paper]\nstock = \"seed-card\"\ngrammage = 80.0\n");
        assert!(message.contains("takes no figures"), "{message}");
        let (_, _, message) = refused("paper = 3\n");
        assert!(
            message.contains("a paper's name (one of seed-card"),
            "{message}"
        );
        let (line, _, message) = refused("paper = \"novel\"\n[book.weights]\nbend_page = 100.0\n");
        assert_eq!(line, 6, "{message}");
        assert!(
            message.contains("the paper sets the page's bending"),
            "{message}"
        );
        // The scene's own choice of Hessian stands; the exact one does not hold a novel page.
        let (_, _, message) = refused("paper = \"novel\"\n[book]\nisometry_hessian = \"exact\"\n");
        assert!(
            message.contains("bend_page") && message.contains("[30, 200]"),
            "{message}"
        );
        let cone = crate::builtin::scene("cone-turn").unwrap().replacen(
            "model = \"cone\"\n",
            "model = \"cone\"\npaper = \"novel\"\n",
            1,
        );
        let e = Scene::parse(&cone).unwrap_err();
        assert!(e.message.contains("is for model = \"dog\" only"), "{e}");
    }
}
