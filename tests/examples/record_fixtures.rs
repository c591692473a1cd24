//! Writes the recorded inputs in `tests/fixtures/`:
//! - for the book (see `folio_book::script`): a camera above and in front of the
//!   default book, and finger paths on the table plane turned into camera rays, as a touch
//!   screen with that camera would produce them;
//! - for the page models (see `folio_pages::touch`): the shared page turn
//!   `page_turn.touch` and seed 003's experiment `seed003_turn.touch`, finger positions in
//!   the page frame.
//!
//! `cargo run -p folio-tests --example record_fixtures` rewrites them.

use core::fmt::Write as _;

const HEIGHT: f64 = 12.0 * core::f64::consts::SQRT_2;

struct Recorder {
    camera: [f64; 3],
    text: String,
}

impl Recorder {
    fn new(frames: u32, title: &str) -> Self {
        let camera = [0.0, 30.0, HEIGHT / 2.0 - 22.0];
        let look = [0.0, 0.0, HEIGHT / 2.0];
        let f: Vec<f64> = (0..3).map(|k| look[k] - camera[k]).collect();
        let n = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let mut text = format!("folio-input 1\n# {title}\nframes {frames}\n");
        let _ = writeln!(
            text,
            "camera {} {} {} {:.9} {:.9} {:.9}",
            camera[0],
            camera[1],
            camera[2],
            f[0] / n,
            f[1] / n,
            f[2] / n
        );
        Self { camera, text }
    }
    /// The ray direction from the camera to the table point `(x, 0.5, z)`.
    fn ray(&self, x: f64, z: f64) -> String {
        let d = [x - self.camera[0], 0.5 - self.camera[1], z - self.camera[2]];
        format!("{:.9} {:.9} {:.9}", d[0], d[1], d[2])
    }
    fn grab(&mut self, frame: u32, x: f64, z: f64, pages: u32) {
        let r = self.ray(x, z);
        let _ = writeln!(self.text, "{frame} grab {r} {pages}");
    }
    /// Drags from `(x0, z0)` to `(x1, z1)` over frames `from..to` with smoothstep easing.
    fn swipe(&mut self, from: u32, to: u32, start: (f64, f64), end: (f64, f64)) {
        for frame in from..to {
            let u = f64::from(frame - from + 1) / f64::from(to - from);
            let s = u * u * (3.0 - 2.0 * u);
            let x = start.0 + (end.0 - start.0) * s;
            let z = start.1 + (end.1 - start.1) * s;
            let r = self.ray(x, z);
            let _ = writeln!(self.text, "{frame} drag {r}");
        }
    }
    fn line(&mut self, frame: u32, event: &str) {
        let _ = writeln!(self.text, "{frame} {event}");
    }
}

fn main() -> std::io::Result<()> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    std::fs::create_dir_all(&dir)?;
    let mid = HEIGHT / 2.0;

    let mut turn = Recorder::new(
        750,
        "page turn: grab near the right page's outer edge, swipe over the spine, release over the left page",
    );
    turn.grab(30, 10.5, mid, 1);
    turn.swipe(31, 131, (10.5, mid), (-6.0, mid - 1.0));
    turn.line(131, "release");
    std::fs::write(dir.join("page_turn.input"), turn.text)?;

    let mut peek = Recorder::new(
        450,
        "peek and return: lift the right page to look under it, put it back",
    );
    peek.grab(30, 10.5, mid + 2.0, 1);
    peek.swipe(31, 91, (10.5, mid + 2.0), (4.0, mid + 2.0));
    peek.swipe(121, 181, (4.0, mid + 2.0), (10.5, mid + 2.0));
    peek.line(181, "release");
    std::fs::write(dir.join("peek.input"), peek.text)?;

    let mut flip = Recorder::new(
        600,
        "finger-bookmarking: hold a page up, flip three more into the grip, let one go back, turn the rest",
    );
    flip.grab(20, 10.5, mid, 1);
    flip.swipe(21, 81, (10.5, mid), (3.0, mid));
    for frame in [100, 130, 160] {
        flip.line(frame, "bookmark-add");
    }
    flip.line(200, "bookmark-remove");
    flip.swipe(231, 331, (3.0, mid), (-6.0, mid - 1.0));
    flip.line(331, "release");
    std::fs::write(dir.join("bookmark_flip.input"), flip.text)?;

    let touch =
        folio_pages::TouchScript::page_turn(12.0, 12.0 * core::f64::consts::SQRT_2, 10, 120, 240);
    let header = "# The shared page turn of the page models: grab the fore-edge near the bottom corner, carry it over the spine in 2 s, let go.\n";
    std::fs::write(
        dir.join("page_turn.touch"),
        format!("{header}{}", touch.to_text()),
    )?;

    // Seed 003's experiment (Sec. 3.1): the 25 x 25 page of 6 x 6 particles, its moved edge
    // carried over the fixed spine.
    let path = (0..120)
        .map(|k| {
            let s = f64::from(k) / 119.0;
            let phi = core::f64::consts::PI * s * s * (3.0 - 2.0 * s);
            [25.0 * phi.cos(), 17.5 * phi.sin(), 12.5]
        })
        .collect();
    let seed = folio_pages::TouchScript {
        frames: 300,
        grab: [25.0, 12.5],
        grab_frame: 10,
        path,
    };
    let header = "# Seed 003's experiment: the edge of the 25 x 25 page carried over the fixed spine in 2 s, let go.\n";
    std::fs::write(
        dir.join("seed003_turn.touch"),
        format!("{header}{}", seed.to_text()),
    )?;
    Ok(())
}
