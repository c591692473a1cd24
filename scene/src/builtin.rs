//! The built-in scenes (`scenes/*.toml`, embedded in the binary).

/// Name and text of every built-in scene; the first is the default.
pub const SCENES: [(&str, &str); 13] = [
    ("page-turn", include_str!("../../scenes/page-turn.toml")),
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
