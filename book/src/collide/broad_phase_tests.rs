//! The broad phase of the page's collisions ([`crate::broad_phase`]) against the brute-force
//! pass it replaced: the same contacts, bit for bit, on hard cases, random positions and the
//! recorded page turn.

use crate::{Book, BookSettings, Script};
use folio_geometry::{BlockSide, Contacts, Wall};
use folio_kernels::splitmix::SplitMix64;
use folio_kernels::{Real, Vec3Ops};

/// An unsettled book of precision `T` holding one page taken from the right block.
fn held<T: Real>() -> Book<T> {
    let mut b = Book::new(BookSettings::<T> {
        settle_steps: 0,
        ..BookSettings::default()
    })
    .unwrap();
    b.grab_at(BlockSide::Right, [10.0, 4.0], 1).unwrap();
    assert!(b.active.is_some());
    b
}

/// The pass before the broad phase: the blocks' contacts, then every page wall and then
/// every corner against every free page node in node order.
fn brute_force<T: Real>(b: &mut Book<T>) -> Contacts<T> {
    let mut c = Contacts::default();
    if b.settings.effects.blocks {
        b.resolve_block_contacts(&mut c);
    }
    let n = b.terms.nodes;
    for w in 0..b.page_walls() {
        let Some(wall) = b.page_wall(w) else {
            continue;
        };
        for node in n.free_page_nodes() {
            c.record(b.push_node(node, &wall));
        }
    }
    for k in 0..b.page_corners() {
        let Some(corner) = b.page_corner(k) else {
            continue;
        };
        for node in n.free_page_nodes() {
            c.record(b.push_node(node, &corner));
        }
    }
    c
}

/// The bits of every position and velocity.
fn bits<T: Real>(b: &Book<T>) -> Vec<u64> {
    let s = &b.state;
    s.x.iter()
        .chain(&s.v)
        .flat_map(|p| [p.x(), p.y(), p.z()])
        .map(|v| v.to_f64().to_bits())
        .collect()
}

/// One detect/resolve round on a copy of `book` with the broad phase and on another
/// with [`brute_force`]; asserts that both end alike, bit for bit (positions,
/// velocities, pinned nodes, contact springs, contacts resolved and deepest); returns
/// the contacts of each.
fn compare<T: Real>(book: &Book<T>) -> [Contacts<T>; 2] {
    let (mut broad, mut brute) = (book.clone(), book.clone());
    let c = broad.resolve_contacts();
    let r = brute_force(&mut brute);
    assert_eq!(bits(&broad), bits(&brute));
    assert_eq!(broad.pushed, brute.pushed);
    assert_eq!(format!("{:?}", broad.terms), format!("{:?}", brute.terms));
    assert_eq!(c.resolved, r.resolved);
    assert_eq!(
        c.max_depth.to_f64().to_bits(),
        r.max_depth.to_f64().to_bits()
    );
    assert!(c.tested <= r.tested);
    [c, r]
}

/// The walls the page collides with (all non-degenerate in these tests).
fn walls<T: Real>(b: &Book<T>) -> Vec<Wall<T>> {
    (0..b.page_walls())
        .map(|w| b.page_wall(w).unwrap())
        .collect()
}

/// `a + s (b - a) + d n` of `wall`, at height `z`.
fn on<T: Real>(wall: &Wall<T>, s: T, d: T, z: T) -> T::Vec3 {
    let p = wall.a + wall.along * s + wall.normal * d;
    T::Vec3::new(p.x(), p.y(), z)
}

/// The free page nodes, column by column.
fn columns<T: Real>(b: &Book<T>) -> Vec<Vec<usize>> {
    let n = b.terms.nodes;
    (1..n.grid.nx)
        .map(|i| (0..n.grid.nz).map(|j| n.page(i, j)).collect())
        .collect()
}

fn a_page_landing_on_a_block<T: Real>() {
    let mut b = held::<T>();
    // The page sinks into the block, deeper towards its fore-edge, the far part
    // through it.
    let drop = T::from_f64(1.5) * b.block_thickness(BlockSide::Right);
    for (i, column) in columns(&b).iter().enumerate() {
        let sink = drop * T::from_f64(i as f64 / 4.0);
        for &node in column {
            b.state.x[node] -= T::Vec3::new(T::ZERO, sink, T::ZERO);
        }
    }
    let [c, r] = compare(&b);
    assert!(c.resolved > 0, "the page landed");
    // The left block's walls are out of reach.
    assert!(c.tested < r.tested, "{} of {}", c.tested, r.tested);
}

#[test]
fn a_page_landing_on_a_block_f64() {
    a_page_landing_on_a_block::<f64>();
}

#[test]
fn a_page_landing_on_a_block_f32() {
    a_page_landing_on_a_block::<f32>();
}

/// Columns at a block's binding end, its inner corners and its open end, each just
/// inside, on and just outside the span and the clearance: every pair of such a wall and
/// span, a column each, over as many books as it takes.
fn a_page_grazing_corners_and_open_ends<T: Real>() {
    let book = held::<T>();
    let walls = walls(&book);
    let segments = walls.len() / 2;
    let eps = T::from_f64(1e-4);
    let picks = [0, segments / 2, segments - 1, segments, walls.len() - 1];
    let spans = [-eps, T::ZERO, T::ONE, T::ONE + eps, T::from_f64(1.5)];
    let cases: Vec<(usize, T)> = picks
        .iter()
        .flat_map(|&w| spans.iter().map(move |&s| (w, s)))
        .collect();
    let mut resolved = 0;
    for chunk in cases.chunks(book.terms.nodes.grid.nx - 1) {
        let mut b = book.clone();
        for (column, &(w, s)) in columns(&b).iter().zip(chunk) {
            let wall = &walls[w];
            for (j, &node) in column.iter().enumerate() {
                let d = wall.clearance + T::from_f64(j as f64 % 3.0 - 1.0) * eps;
                b.state.x[node] = on(wall, s, d, b.state.x[node].z());
            }
        }
        resolved += compare(&b)[0].resolved;
    }
    assert!(resolved > 0);
}

#[test]
fn a_page_grazing_corners_and_open_ends_f64() {
    a_page_grazing_corners_and_open_ends::<f64>();
}

#[test]
fn a_page_grazing_corners_and_open_ends_f32() {
    a_page_grazing_corners_and_open_ends::<f32>();
}

/// The lowest height above `wall`'s middle at which a node is clear, and the next
/// representable height below it, where it is not (bisection to adjacent values).
fn clearance_edge<T: Real>(wall: &Wall<T>, z: T) -> [T::Vec3; 2] {
    let at = |d: T| on(wall, T::HALF, d, z);
    let (mut inside, mut clear) = (T::ZERO, wall.clearance * T::TWO);
    assert!(wall.penetration(at(inside)).is_some() && wall.penetration(at(clear)).is_none());
    loop {
        let mid = (inside + clear) * T::HALF;
        if mid == inside || mid == clear {
            break;
        }
        if wall.penetration(at(mid)).is_some() {
            inside = mid;
        } else {
            clear = mid;
        }
    }
    [at(clear), at(inside)]
}

fn nodes_exactly_at_the_clearance<T: Real>() {
    let mut b = held::<T>();
    let walls = walls(&b);
    let columns = columns(&b);
    let wall = walls[walls.len() / 2 + 2];
    for (i, column) in columns.iter().enumerate() {
        for (j, &node) in column.iter().enumerate() {
            let [clear, inside] = clearance_edge(&wall, b.state.x[node].z());
            // Column 0 all on the edge, column 1 with one node a step inside it.
            b.state.x[node] = if i == 1 && j == 2 { inside } else { clear };
        }
    }
    let [c, _] = compare(&b);
    let n = b.terms.nodes;
    let mut broad = b.clone();
    broad.resolve_contacts();
    // Only the node inside moved (off the page, only the blocks' contacts).
    let moved: Vec<usize> = n
        .free_page_nodes()
        .filter(|&k| broad.state.x[k] != b.state.x[k])
        .collect();
    assert_eq!(moved, [columns[1][2]], "{c:?}");
}

#[test]
fn nodes_exactly_at_the_clearance_f64() {
    nodes_exactly_at_the_clearance::<f64>();
}

#[test]
fn nodes_exactly_at_the_clearance_f32() {
    nodes_exactly_at_the_clearance::<f32>();
}

/// Uniform in `[lo, hi)`, in precision `T`.
fn uniform<T: Real>(r: &mut SplitMix64, lo: f64, hi: f64) -> T {
    T::from_f64(r.uniform(lo, hi))
}

/// Random blocks (midline nodes moved) and random page nodes around random walls, in
/// tight or scattered columns, some exactly at a wall's clearance.
fn random_positions<T: Real>(seeds: u64) {
    let base = held::<T>();
    let (mut tested, mut brute) = (0, 0);
    for seed in 0..seeds {
        let mut r = SplitMix64::new(seed);
        let mut b = base.clone();
        let m = b.terms.nodes.midline;
        for k in 1..2 * m {
            let bend = T::Vec3::new(
                uniform::<T>(&mut r, -0.2, 0.2),
                uniform::<T>(&mut r, -0.6, 0.6),
                T::ZERO,
            );
            b.state.x[k] += bend;
        }
        let walls: Vec<Wall<T>> = (0..b.page_walls()).filter_map(|w| b.page_wall(w)).collect();
        let spread = uniform::<T>(&mut r, 0.0, 1.0) * uniform::<T>(&mut r, 0.0, 1.0) * T::TWO;
        for column in columns(&b) {
            let w = (r.next_u64() % walls.len() as u64) as usize;
            let wall = &walls[w];
            let (s, d) = (
                uniform::<T>(&mut r, -0.3, 1.6),
                uniform::<T>(&mut r, -1.0, 2.0) * wall.clearance,
            );
            for &node in &column {
                let z = b.state.x[node].z();
                let jitter = T::Vec3::new(
                    uniform::<T>(&mut r, -1.0, 1.0),
                    uniform::<T>(&mut r, -1.0, 1.0),
                    T::ZERO,
                ) * spread;
                b.state.x[node] = if r.next_u64() % 8 == 0 {
                    on(wall, uniform::<T>(&mut r, 0.0, 1.0), wall.clearance, z)
                } else {
                    on(wall, s, d, z) + jitter
                };
            }
        }
        let [c, f] = compare(&b);
        tested += c.tested;
        brute += f.tested;
    }
    // The broad phase skips a share of the pairs.
    assert!(tested < brute, "{tested} of {brute}");
}

#[test]
fn random_positions_f64() {
    random_positions::<f64>(300);
}

#[test]
fn random_positions_f32() {
    random_positions::<f32>(300);
}

/// The recorded page turn with the broad phase and with every column kept: the same
/// state after every step, bit for bit, with fewer point tests.
#[test]
fn the_page_turn_is_unchanged() {
    let script = Script::parse(include_str!("../../../tests/fixtures/page_turn.input")).unwrap();
    let mut broad = Book::<f64>::new(BookSettings::default()).unwrap();
    let mut brute = broad.clone();
    brute.broad.exhaustive = true;
    let (mut tested, mut boxes, mut all) = (0, 0, 0);
    for frame in 0..script.frames {
        for book in [&mut broad, &mut brute] {
            for e in script.events_at(frame) {
                book.apply(script.camera, script.forward, e.action).unwrap();
            }
        }
        let (c, r) = (broad.step().unwrap(), brute.step().unwrap());
        assert_eq!(bits(&broad), bits(&brute), "frame {frame}");
        assert_eq!(c.contacts.resolved, r.contacts.resolved);
        assert_eq!(
            c.contacts.max_depth.to_bits(),
            r.contacts.max_depth.to_bits()
        );
        tested += c.contacts.tested;
        boxes += c.contacts.bounds_tested;
        all += r.contacts.tested;
    }
    eprintln!(
        "page turn, {} frames: {tested} point tests and {boxes} box tests, against {all} \
         point tests without the broad phase",
        script.frames
    );
    assert!(tested < all / 2, "{tested} of {all}");
}
