//! The built-in scenes (`scenes/*.toml`, embedded in the binary).

/// Name and text of every built-in scene; the first is the default.
pub const SCENES: [(&str, &str); 14] = [
    ("page-turn", include_str!("../../scenes/page-turn.toml")),
    (
        "page-turn-mcu",
        include_str!("../../scenes/page-turn-mcu.toml"),
    ),
    ("peek", include_str!("../../scenes/peek.toml")),
    (
        "bookmark-flip",
        include_str!("../../scenes/bookmark-flip.toml"),
    ),
    ("stack", include_str!("../../scenes/stack.toml")),
    ("paperback", include_str!("../../scenes/paperback.toml")),
    (
        "three-and-back",
        include_str!("../../scenes/three-and-back.toml"),
    ),
    ("cone-turn", include_str!("../../scenes/cone-turn.toml")),
    (
        "mass-spring-turn",
        include_str!("../../scenes/mass-spring-turn.toml"),
    ),
    ("xpbd-turn", include_str!("../../scenes/xpbd-turn.toml")),
    (
        "tear-straight",
        include_str!("../../scenes/tear-straight.toml"),
    ),
    ("tear-curved", include_str!("../../scenes/tear-curved.toml")),
    ("tear-zigzag", include_str!("../../scenes/tear-zigzag.toml")),
    ("tear-twist", include_str!("../../scenes/tear-twist.toml")),
];

/// The text of built-in scene `name`.
#[must_use]
pub fn scene(name: &str) -> Option<&'static str> {
    SCENES.iter().find(|s| s.0 == name).map(|s| s.1)
}

#[cfg(test)]
mod tests {
    use crate::scene::{Precision, Scene};
    use crate::settings::book_settings;
    use folio_book::BookSettings;

    /// `page-turn-mcu` is `BookSettings::microcontroller` in `f32` on the default scene's
    /// input: the firmware's `mcu` run and the scene are one book.
    #[test]
    fn the_mcu_scene_is_the_microcontroller_book_in_f32() {
        let mcu = Scene::parse(super::scene("page-turn-mcu").expect("built in")).expect("parses");
        let turn = Scene::parse(super::scene("page-turn").expect("built in")).expect("parses");
        assert_eq!(mcu.precision(), Precision::F32);
        assert_eq!(
            book_settings::<f32>(&mcu).expect("reads"),
            BookSettings::<f32>::microcontroller()
        );
        let fixture = |s: &Scene| {
            s.input
                .get_ref()
                .fixture
                .as_ref()
                .map(|f| f.get_ref().clone())
        };
        assert_eq!(fixture(&mcu), fixture(&turn), "the page turn's gesture");
        assert!(fixture(&mcu).is_some());
    }
}
