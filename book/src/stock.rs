//! Paper stocks: what a paper is, whatever page is cut from it, and the built-in ones a
//! scene names (`paper = "novel"`, `docs/scenes.md`).
//!
//! A stock is its grammage, caliper (thickness), Young's modulus across the grain and
//! Poisson's ratio. A book's pages are cut with the grain parallel to the spine (the
//! binder's rule: the pages then turn and lie flat), so a page turning about the spine
//! bends its cross-grain fibres, and its plate stiffness is
//! $$D = \frac{E_{\mathrm{across}}\thinspace t^3}{12\,(1 - \nu^2)}.$$
//! [`Stock::cut`] gives the page of one size in this stock as a [`Paper`], whose
//! [`Paper::apply`] gives it to a book.
//!
//! **The built-in stocks** ([`Stock::BUILT_IN`]). Their grammages and calipers are usual
//! catalogue figures for each kind of paper (grammage by ISO 536, caliper by ISO 534), not
//! one mill's product; their moduli lie in the 2 to 8 GPa of machine-made papers, with the
//! cross-grain modulus, the one given here, about half the grain's (in-plane moduli and
//! their anisotropy of 1.5 to 3 in Alava and Niskanen, *The physics of paper*, Rep. Prog.
//! Phys. 69 (2006) 669); a coated paper is denser and stiffer in-plane than an uncoated
//! one. The DOG page bends alike in every direction, so the grain's own modulus, which
//! only a page bent along the spine would feel, is not a figure of the stock. The sag number
//! $\alpha = \rho g L^3 / D$ on an A5 page ($L$ = 148 mm) decides the shapes at rest
//! ([`Paper::sag_number`]); each stock's is in its doc and checked by a test:
//!
//! | stock | g/m² | caliper | $E$ across the grain | $\alpha$ on A5 |
//! |---|---|---|---|---|
//! | `bible` | 36 | 45 µm | 2.5 GPa | 55 |
//! | `novel` | 70 | 100 µm | 2.2 GPa | 11 |
//! | `magazine` (coated) | 115 | 95 µm | 3.5 GPa | 13 |
//! | `card` | 300 | 380 µm | 3 GPa | 0.63 |
//!
//! Paper is not known better than this: its moduli move by ±20 % with the grain's angle,
//! the humidity and the make, which moves a sagging page's tip by about 5 % of its width.

use folio_kernels::setting::{SettingError, require};

use super::paper::Paper;

/// A paper stock (module docs). Units: grammage in g/m², caliper in m, moduli in Pa.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stock {
    /// Mass per area (g/m²; finite, $> 0$).
    pub grammage: f64,
    /// Caliper, the sheet's thickness $t$ (m; finite, $> 0$).
    pub caliper: f64,
    /// Young's modulus across the grain (Pa; finite, $> 0$): the direction a turning page
    /// bends in, so the one its $D$ is made of.
    pub young_across: f64,
    /// Poisson's ratio $\nu$ (finite, in $[0, 0.5)$).
    pub poisson: f64,
}

impl Stock {
    /// Bible paper, 36 g/m², 45 µm (a density of 800 kg/m³): the thinnest book paper,
    /// $\alpha$ = 55 on an A5 page, a page that hangs almost straight down.
    pub const BIBLE: Self = Self::new(36.0, 45e-6, 2.5e9);
    /// Novel (book wove) paper, 70 g/m², 100 µm (a bulky 700 kg/m³): the paperback's and
    /// the hardback novel's page, $\alpha$ = 11 on an A5 page.
    pub const NOVEL: Self = Self::new(70.0, 100e-6, 2.2e9);
    /// Coated magazine paper, 115 g/m², 95 µm (1,210 kg/m³), $\alpha$ = 13 on an A5 page
    /// (38 on an A4 page, 210 mm wide).
    pub const MAGAZINE: Self = Self::new(115.0, 95e-6, 3.5e9);
    /// Card, 300 g/m², 380 µm (790 kg/m³): a cover or a postcard, $\alpha$ = 0.63 on an A5
    /// page, a page that barely sags.
    pub const CARD: Self = Self::new(300.0, 380e-6, 3e9);

    /// The built-in stocks by the names a scene gives them, thinnest first.
    pub const BUILT_IN: [(&'static str, Self); 4] = [
        ("bible", Self::BIBLE),
        ("novel", Self::NOVEL),
        ("magazine", Self::MAGAZINE),
        ("card", Self::CARD),
    ];

    /// A stock of `grammage` (g/m²), `caliper` (m) and modulus across the grain (Pa), with
    /// the usual Poisson's ratio of paper, 0.3.
    #[must_use]
    pub const fn new(grammage: f64, caliper: f64, young_across: f64) -> Self {
        Self {
            grammage,
            caliper,
            young_across,
            poisson: 0.3,
        }
    }

    /// The built-in stock called `name` ([`Stock::BUILT_IN`]).
    #[must_use]
    pub fn named(name: &str) -> Option<Self> {
        Self::BUILT_IN
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, stock)| stock)
    }

    /// `Ok` when every figure is finite and positive and $\nu \in [0, 0.5)$.
    ///
    /// # Errors
    /// The first figure that is not, under `paper.<field>`.
    pub fn validate(&self) -> Result<(), SettingError> {
        for (field, v) in [
            ("paper.grammage", self.grammage),
            ("paper.caliper", self.caliper),
            ("paper.young_across", self.young_across),
        ] {
            require(v.is_finite() && v > 0.0, field, "finite and > 0", v)?;
        }
        require(
            (0.0..0.5).contains(&self.poisson),
            "paper.poisson",
            "in [0, 0.5)",
            self.poisson,
        )
    }

    /// The page of `width` (binding to fore-edge) and `height` (along the binding), both
    /// in m, cut from this stock with the grain along the binding: its areal density
    /// (kg/m²) is the grammage over 1000 and its $D$ the cross-grain plate stiffness
    /// (module docs).
    #[must_use]
    pub fn cut(&self, width: f64, height: f64) -> Paper {
        Paper::from_modulus(
            width,
            height,
            self.caliper,
            self.grammage * 1e-3,
            self.young_across,
            self.poisson,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::Stock;

    /// A5's width (ISO 216), m.
    const A5_WIDTH: f64 = 0.148;

    /// Each stock's sag number on an A5 page, from its figures by hand:
    /// alpha = (g/1000) 9.81 L^3 12 (1 - 0.09) / (E_across t^3), against the table of
    /// the module docs (the figure the docs round).
    #[test]
    fn each_stock_has_the_sag_number_its_docs_give() {
        let table = [
            ("bible", 55.0),
            ("novel", 11.0),
            ("magazine", 13.0),
            ("card", 0.63),
        ];
        for (name, documented) in table {
            let s = Stock::named(name).unwrap();
            let by_hand = s.grammage * 1e-3 * 9.81 * A5_WIDTH.powi(3) * 12.0 * 0.91
                / (s.young_across * s.caliper.powi(3));
            let alpha = s.cut(A5_WIDTH, 0.210).sag_number();
            assert!(
                (alpha / by_hand - 1.0).abs() < 1e-12,
                "{name}: {alpha} {by_hand}"
            );
            assert!(
                (alpha / documented - 1.0).abs() < 0.05,
                "{name}: alpha {alpha}, documented {documented}"
            );
            assert_eq!(s.validate(), Ok(()), "{name}");
        }
    }

    /// Real book paper (bible to novel) is far softer against its weight than the seed's
    /// page (alpha 0.24), a card stiffer than any book paper; densities are those of
    /// paper (500 to 1300 kg/m^3) and moduli those of machine-made paper across the grain.
    #[test]
    fn the_stocks_are_ordered_as_paper_is() {
        let alpha = |s: Stock| s.cut(A5_WIDTH, 0.210).sag_number();
        assert!(alpha(Stock::BIBLE) > alpha(Stock::NOVEL));
        assert!(alpha(Stock::NOVEL) > 5.0 && alpha(Stock::NOVEL) < 15.0);
        assert!(alpha(Stock::CARD) < 1.0 && alpha(Stock::CARD) > 0.24);
        for (name, s) in Stock::BUILT_IN {
            let density = s.grammage * 1e-3 / s.caliper;
            assert!((500.0..1300.0).contains(&density), "{name}: {density}");
            assert!((1e9..5e9).contains(&s.young_across), "{name}");
        }
        assert_eq!(Stock::named("newsprint"), None);
    }

    #[test]
    fn bad_stocks_are_named() {
        let field = |s: Stock| s.validate().unwrap_err().path.field();
        let n = Stock::NOVEL;
        assert_eq!(field(Stock { grammage: 0.0, ..n }), "paper.grammage");
        assert_eq!(
            field(Stock {
                caliper: f64::NAN,
                ..n
            }),
            "paper.caliper"
        );
        assert_eq!(
            field(Stock {
                young_across: f64::INFINITY,
                ..n
            }),
            "paper.young_across"
        );
        assert_eq!(field(Stock { poisson: 0.5, ..n }), "paper.poisson");
        assert_eq!(field(Stock { poisson: -0.1, ..n }), "paper.poisson");
    }
}
