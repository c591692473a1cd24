//! The global registry of live books, indexed by [`FolioBookHandle`].
//!
//! Slots hold an `Arc<Mutex<Entry>>` with the serial number of the book in it. A lookup
//! takes the registry lock only to clone the `Arc`; the book's own lock is taken after the
//! registry lock is released, so a long step on one book never blocks calls on another.
//! A book destroyed while another thread uses it is freed when that call ends.
//!
//! When the last book is destroyed the slot tables are freed (serial numbers carry on, so
//! old handles stay stale): a program that destroys every book leaves no heap behind.

use alloc::sync::Arc;
use alloc::vec::Vec;
use std::sync::{Mutex, MutexGuard, PoisonError};

use crate::entry::Entry;
use crate::failure::Failure;
use crate::handle::{FolioBookHandle, MAX_SERIAL, SLOT_BITS};
use crate::status::FolioStatus;

/// A live book.
struct Slot {
    serial: u64,
    entry: Arc<Mutex<Entry>>,
}

/// Slots, the free list and the serial counter.
struct Registry {
    slots: Vec<Option<Slot>>,
    free: Vec<usize>,
    /// The serial number of the next book (the first is 1).
    next_serial: u64,
    live: usize,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    slots: Vec::new(),
    free: Vec::new(),
    next_serial: 1,
    live: 0,
});

/// The registry, locked. Its updates below reserve memory before they change anything, so
/// a panic (allocation failure) leaves it consistent, and a poisoned lock is taken over.
fn lock() -> MutexGuard<'static, Registry> {
    REGISTRY.lock().unwrap_or_else(PoisonError::into_inner)
}

fn stale(handle: FolioBookHandle) -> Failure {
    let message = if handle.id == 0 {
        String::from("the zero handle names no book")
    } else {
        format!(
            "handle {:#x} names no live book (destroyed or never created)",
            handle.id
        )
    };
    Failure::new(FolioStatus::StaleHandle, message)
}

/// Registers `entry` and returns its new handle.
pub(crate) fn insert(entry: Entry) -> Result<FolioBookHandle, Failure> {
    let mut guard = lock();
    let r = &mut *guard;
    if r.next_serial > MAX_SERIAL {
        return Err(Failure::new(
            FolioStatus::OutOfHandles,
            "every serial number of this process was used",
        ));
    }
    let slot = match r.free.last() {
        Some(&slot) => slot,
        None if r.slots.len() < 1 << SLOT_BITS => {
            // Room for the new slot, and on the free list for every slot (see `remove`).
            r.slots.reserve(1);
            let want = r.slots.len() + 1;
            r.free.reserve(want.saturating_sub(r.free.len()));
            r.slots.len()
        }
        None => {
            return Err(Failure::new(
                FolioStatus::OutOfHandles,
                format!("{} books are alive", r.live),
            ));
        }
    };
    let serial = r.next_serial;
    let filled = Some(Slot {
        serial,
        entry: Arc::new(Mutex::new(entry)),
    });
    if slot == r.slots.len() {
        r.slots.push(filled);
    } else {
        r.free.pop();
        r.slots[slot] = filled;
    }
    r.next_serial += 1;
    r.live += 1;
    Ok(FolioBookHandle::new(slot, serial))
}

/// The book `handle` names, if it is live.
pub(crate) fn get(handle: FolioBookHandle) -> Result<Arc<Mutex<Entry>>, Failure> {
    let r = lock();
    match r.slots.get(handle.slot()) {
        Some(Some(s)) if s.serial == handle.serial() => Ok(Arc::clone(&s.entry)),
        _ => Err(stale(handle)),
    }
}

/// Unregisters the book `handle` names and returns it (the caller drops it outside the
/// registry lock).
pub(crate) fn remove(handle: FolioBookHandle) -> Result<Arc<Mutex<Entry>>, Failure> {
    let mut guard = lock();
    let r = &mut *guard;
    let slot = handle.slot();
    let live = matches!(r.slots.get(slot), Some(Some(s)) if s.serial == handle.serial());
    if !live {
        return Err(stale(handle));
    }
    let Some(Some(s)) = r.slots.get_mut(slot).map(Option::take) else {
        return Err(stale(handle));
    };
    r.live -= 1;
    if r.live == 0 {
        r.slots = Vec::new();
        r.free = Vec::new();
    } else {
        // Cannot allocate: `insert` reserved room for every slot on the free list.
        r.free.push(slot);
    }
    Ok(s.entry)
}

/// Runs `f` on the book `handle` names, under the book's lock.
///
/// # Errors
/// `STALE_HANDLE`, `POISONED` (an earlier call panicked holding this book), or `f`'s.
pub(crate) fn with_entry<R>(
    handle: FolioBookHandle,
    f: impl FnOnce(&mut Entry) -> Result<R, Failure>,
) -> Result<R, Failure> {
    let entry = get(handle)?;
    let mut guard = entry.lock().map_err(|_| {
        Failure::new(
            FolioStatus::Poisoned,
            "an earlier call panicked while it used this book; destroy it",
        )
    })?;
    f(&mut guard)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::any_book::AnyBook;
    use crate::guard;
    use folio_book::{Book, BookSettings};

    /// A panic while a call holds a book poisons that book only: later calls on it answer
    /// `POISONED`, destroy still works, other books are untouched.
    #[test]
    fn a_panic_holding_a_book_poisons_it_until_destroyed() {
        let book = || AnyBook::F64(Book::new(BookSettings::default()).unwrap());
        let sick = insert(Entry::new(book())).unwrap();
        let well = insert(Entry::new(book())).unwrap();
        let status = guard::call("folio_test", || {
            with_entry(sick, |_| -> Result<(), Failure> {
                panic!("inside the book")
            })
        });
        assert_eq!(status, FolioStatus::Panic);
        let again = guard::call("folio_test", || with_entry(sick, |_| Ok(())));
        assert_eq!(again, FolioStatus::Poisoned);
        assert!(crate::last_error::get().contains("destroy it"));
        assert_eq!(
            guard::call("folio_test", || with_entry(well, |e| e.step().map(|_| ()))),
            FolioStatus::Ok
        );
        for h in [sick, well] {
            assert!(remove(h).is_ok());
            assert!(get(h).is_err(), "stale after removal");
        }
    }
}
