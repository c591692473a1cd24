//! `folio_book_create_from_scene`: a book from a scene file's text.

use core::ffi::{CStr, c_char};

use folio_book::{Book, BookSettings};
use folio_scene::scene::{ModelKind, Precision, Scene};
use folio_scene::settings::{SceneReal, book_settings};

use crate::any_book::AnyBook;
use crate::create::register;
use crate::failure::Failure;
use crate::guard;
use crate::handle::FolioBookHandle;
use crate::pointer;
use crate::status::FolioStatus;

/// `INVALID_SCENE` with `message`.
fn invalid(message: impl Into<String>) -> Failure {
    Failure::new(FolioStatus::InvalidScene, message)
}

/// The scene's book in precision `T`.
fn settings<T: SceneReal>(scene: &Scene) -> Result<BookSettings<T>, Failure> {
    book_settings(scene).map_err(|e| invalid(e.to_string()))
}

/// Creates a book from the text of a scene file (TOML, the format of `docs/scenes.md`, as
/// `folio check` reads it) and writes its handle to `*out`. The scene must name
/// `model = "dog"`. Its `[book]` (every field of the book's settings, by its name:
/// `[book.params]`, `[book.weights]`, `[book.solver]`, `quads_across`, ...) and `effects`
/// define the book, simulated in the scene's `precision` (double by default); its input, frames,
/// outputs and expectations are checked but not used: the caller drives the book with
/// grab, drag, release and step. The smallest
/// scene is `name = "s"`, `model = "dog"`, `input = { fixture = "page-turn" }`.
///
/// Returns `FOLIO_STATUS_NULL_POINTER` for a NULL argument, `FOLIO_STATUS_INVALID_SCENE`
/// for text that is not UTF-8, does not parse or check (the message gives the line and
/// column: `line L, column C: message`), names another model or settings the book refuses,
/// `FOLIO_STATUS_OUT_OF_HANDLES`. On failure `*out` is left as it was.
///
/// # Safety
/// `toml_utf8` is NULL or points to a NUL-terminated string; `out` is NULL or valid for a
/// write of one `FolioBookHandle`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_book_create_from_scene(
    toml_utf8: *const c_char,
    out: *mut FolioBookHandle,
) -> FolioStatus {
    guard::call("folio_book_create_from_scene", || {
        pointer::check(out, "out")?;
        if toml_utf8.is_null() {
            return Err(Failure::null("toml_utf8"));
        }
        // SAFETY: non-NULL (checked) and NUL-terminated (contract); the bytes are only read,
        // and only during this call.
        let text = unsafe { CStr::from_ptr(toml_utf8) };
        // The same reading as `folio check`: UTF-8 (else the bad byte's place), then the
        // scene's checks.
        let scene = Scene::parse_bytes(text.to_bytes()).map_err(|e| invalid(e.to_string()))?;
        let model = *scene.model.get_ref();
        if model != ModelKind::Dog {
            return Err(invalid(format!(
                "the scene's model is {model:?}; the C API simulates the DOG book (model = \"dog\")"
            )));
        }
        let refused = |e| {
            let f = Failure::book(e);
            match f.status {
                FolioStatus::InvalidArgument => invalid(f.message),
                _ => f,
            }
        };
        let book = match scene.precision() {
            Precision::F64 => AnyBook::F64(Book::new(settings(&scene)?).map_err(refused)?),
            Precision::F32 => AnyBook::F32(Book::new(settings(&scene)?).map_err(refused)?),
        };
        // SAFETY: `out` was checked non-NULL and aligned above; writable by contract.
        unsafe { register(book, out) }
    })
}
