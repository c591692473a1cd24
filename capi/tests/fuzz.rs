//! A seeded random walk through the whole API with good and bad arguments: no call panics
//! (no `FOLIO_STATUS_PANIC` or `POISONED`), every status is a known one, every failure
//! leaves a message naming its function and every success an empty one, and every report
//! and mesh that comes back is finite.

#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

mod common;

use common::*;
use core::ptr;
use folio_capi::*;

/// xorshift64* (Vigna): enough randomness for argument choice, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn chance(&mut self, percent: u64) -> bool {
        self.below(100) < percent
    }
    /// A coordinate: usually in the book's range, sometimes NaN, infinite or huge.
    fn coordinate(&mut self) -> f64 {
        match self.below(20) {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => f64::NEG_INFINITY,
            3 => 1e300,
            4 => -1e-310,
            _ => (self.below(40_000) as f64 - 20_000.0) / 1000.0,
        }
    }
    /// A buffer length around `needed`.
    fn length(&mut self, needed: usize) -> usize {
        match self.below(5) {
            0 => 0,
            1 => needed.saturating_sub(1 + self.below(5) as usize),
            2 => needed + self.below(4) as usize,
            _ => needed,
        }
    }
}

/// Checks a call's status and the thread's message.
fn checked(call: &str, status: FolioStatus) -> FolioStatus {
    assert!(
        !matches!(status, FolioStatus::Panic | FolioStatus::Poisoned),
        "{call}: {status:?}: {}",
        last_error()
    );
    let message = last_error();
    if status == FolioStatus::Ok {
        assert_eq!(message, "", "{call}");
    } else {
        assert!(
            message.starts_with("folio_"),
            "{call}: {status:?}: {message:?}"
        );
    }
    status
}

/// Mostly valid settings. At least 10 pages: a book of very few pages does not reach the
/// settle tolerance and runs all 20000 settle steps at creation (seconds).
fn random_settings(rng: &mut Rng) -> FolioBookSettings {
    let mut s = FolioBookSettings::default();
    s.total_pages = 10 + rng.below(90) as u32;
    s.left_pages = rng.below(u64::from(s.total_pages) + 2) as u32;
    s.quads_across = 4 + rng.below(6) as u32;
    s.quads_along = 6 + rng.below(6) as u32;
    s.cover = rng.below(2) as u32;
    if rng.chance(15) {
        s.precision = FOLIO_PRECISION_F32;
    }
    if rng.chance(15) {
        s.effects = rng.below(64) as u32;
    }
    match rng.below(12) {
        0 => s.page_width = rng.coordinate(),
        1 => s.time_step = rng.coordinate(),
        2 => s.precision = rng.below(100) as u32,
        3 => s.cover = rng.below(4) as u32,
        4 => s.quads_across = rng.below(3) as u32,
        _ => {}
    }
    s
}

#[test]
fn random_calls_never_panic_and_always_explain() {
    // `FOLIO_FUZZ_SEED=<n>` walks another path (a failure prints the seed it ran with).
    let seed = std::env::var("FOLIO_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse::<u64>().ok())
        .unwrap_or(0x00f0_110c_a91e_2024);
    eprintln!("seed {seed}");
    let mut rng = Rng(seed.max(1));
    let mut live: Vec<FolioBookHandle> = Vec::new();
    let mut dead: Vec<FolioBookHandle> = vec![FolioBookHandle::default()];
    let mut counts = [0usize; 13];
    for _ in 0..700 {
        let pick = |rng: &mut Rng, live: &[FolioBookHandle], dead: &[FolioBookHandle]| {
            if !live.is_empty() && rng.chance(85) {
                live[rng.below(live.len() as u64) as usize]
            } else if rng.chance(50) {
                dead[rng.below(dead.len() as u64) as usize]
            } else {
                FolioBookHandle { id: rng.next() }
            }
        };
        let h = pick(&mut rng, &live, &dead);
        // With no live book, mostly create one.
        let op = if live.is_empty() && rng.chance(60) {
            0
        } else {
            rng.below(12)
        };
        let status = match op {
            0 if live.len() < 3 => {
                let s = random_settings(&mut rng);
                let mut out = FolioBookHandle::default();
                let out_ptr = if rng.chance(5) {
                    ptr::null_mut()
                } else {
                    &mut out
                };
                // SAFETY: `s` is readable; `out_ptr` is NULL or valid.
                let status = checked("create", unsafe { folio_book_create(&s, out_ptr) });
                if status == FolioStatus::Ok {
                    live.push(out);
                }
                status
            }
            1 => {
                let status = checked("destroy", folio_book_destroy(h));
                if status == FolioStatus::Ok {
                    live.retain(|&x| x != h);
                    dead.push(h);
                }
                status
            }
            2 => {
                let side = rng.below(4) as u32;
                let (u, v) = (rng.coordinate(), rng.coordinate());
                let pages = rng.below(4) as u32;
                checked("grab", folio_book_grab(h, side, u.abs(), v.abs(), pages))
            }
            3 | 4 => {
                let p = [rng.coordinate(), rng.coordinate(), rng.coordinate()];
                checked("drag", folio_book_drag(h, p[0], p[1], p[2]))
            }
            5 => checked("release", folio_book_release(h)),
            6 | 7 => {
                let mut r = core::mem::MaybeUninit::<FolioStepReport>::uninit();
                let out = if rng.chance(5) {
                    ptr::null_mut()
                } else {
                    r.as_mut_ptr()
                };
                // SAFETY: `out` is NULL or valid for one write.
                let status = checked("step", unsafe { folio_book_step(h, out) });
                if status == FolioStatus::Ok {
                    // SAFETY: written by the successful call.
                    let r = unsafe { r.assume_init() };
                    for value in [
                        r.dog_residual,
                        r.stretch_max,
                        r.stretch_rms,
                        r.penetration,
                        r.constraint_residual,
                    ] {
                        assert!(value.is_finite(), "{r:?}");
                    }
                }
                status
            }
            8 => {
                let (mut v, mut t) = (0u32, 0u32);
                // SAFETY: valid out-pointers.
                let status = checked("mesh_size", unsafe {
                    folio_book_mesh_size(h, &mut v, &mut t)
                });
                let (v, t) = (v as usize, t as usize);
                let lens = [
                    rng.length(3 * v),
                    rng.length(3 * v),
                    rng.length(2 * v),
                    rng.length(3 * t),
                ];
                let mut positions = vec![0.0f32; lens[0]];
                let mut normals = vec![0.0f32; lens[1]];
                let mut uvs = vec![0.0f32; lens[2]];
                let mut indices = vec![0u32; lens[3]];
                // SAFETY: every pointer is valid for its length.
                let copied = checked("mesh_copy", unsafe {
                    folio_book_mesh_copy(
                        h,
                        positions.as_mut_ptr(),
                        lens[0],
                        normals.as_mut_ptr(),
                        lens[1],
                        uvs.as_mut_ptr(),
                        lens[2],
                        indices.as_mut_ptr(),
                        lens[3],
                    )
                });
                if copied == FolioStatus::Ok && status == FolioStatus::Ok {
                    assert!(
                        positions
                            .iter()
                            .chain(&normals)
                            .chain(&uvs)
                            .all(|x| x.is_finite())
                    );
                    assert!(indices[..3 * t].iter().all(|&i| (i as usize) < v));
                }
                copied
            }
            9 => {
                let n = rng.length(3 * 12 * 13);
                let mut xyz = vec![0.0f64; n];
                // SAFETY: `xyz` is valid for `n` doubles.
                let status = checked("page_positions", unsafe {
                    folio_book_page_positions(h, xyz.as_mut_ptr(), n)
                });
                if status == FolioStatus::Ok {
                    assert!(xyz.iter().all(|x| x.is_finite()));
                }
                status
            }
            10 => {
                let mut xyz = [0.0f64; 3];
                // SAFETY: `xyz` holds 3 doubles.
                checked("held_position", unsafe {
                    folio_book_held_position(h, xyz.as_mut_ptr())
                })
            }
            _ => {
                let len = rng.below(40) as usize;
                let mut buf = vec![0 as core::ffi::c_char; len];
                let mut needed = 0usize;
                // SAFETY: `buf` is valid for `len` bytes.
                let status =
                    unsafe { folio_last_error_message(buf.as_mut_ptr(), len, &mut needed) };
                assert!(matches!(
                    status,
                    FolioStatus::Ok | FolioStatus::BufferTooSmall
                ));
                if len > 0 {
                    assert!(buf.contains(&0), "always NUL-terminated");
                }
                status
            }
        };
        counts[status as usize] += 1;
    }
    for h in live {
        assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
    }
    eprintln!("statuses seen (by code): {counts:?}");
    assert!(counts[FolioStatus::Ok as usize] > 150, "{counts:?}");
    for status in [
        FolioStatus::StaleHandle,
        FolioStatus::InvalidArgument,
        FolioStatus::BufferTooSmall,
        FolioStatus::NotHeld,
    ] {
        assert!(
            counts[status as usize] > 0,
            "{status:?} never seen: {counts:?}"
        );
    }
}
