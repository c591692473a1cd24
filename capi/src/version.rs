//! The API version: one integer shared by the header and the library.

/// The version of the C API this header describes.
///
/// **Rule.** The number grows by one with every change that can break a program compiled
/// against an older header: a function removed or renamed, an argument or return type
/// changed, a struct's fields or layout changed, a constant's or status code's meaning
/// changed. Purely additive changes keep it: a new function, a new constant, a new status
/// code appended at the end. A program checks at startup that
/// `folio_api_version() == FOLIO_API_VERSION` (the library it runs with against the header it
/// was compiled with) and refuses to run otherwise.
pub const FOLIO_API_VERSION: u32 = 1;

/// The `FOLIO_API_VERSION` this library was built with. Never fails.
#[unsafe(no_mangle)]
pub extern "C" fn folio_api_version() -> u32 {
    FOLIO_API_VERSION
}
