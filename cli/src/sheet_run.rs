//! Running a sheet scene (`model = "sheet"`, seed `002_…`): before every frame the hands
//! place their fingers ([`folio_scene::hands`]), the sheet takes the frame's steps (physics,
//! cone remesh, tearing: `folio_tearing::sheet::TearingSheet::step`; a frame is 1/60 s,
//! [`folio_scene::clock`]), and the frame is measured; the run ends in
//! a [`Report`] whose summary gives the tears' lengths and whose [`TearingLog`] lists every
//! propagation and tear path.
//!
//! Edge stretch is $\lvert \ell / \ell_0 - 1 \rvert$ over the sheet's edges, $\ell$ in 3D
//! and $\ell_0$ in the pattern (every edge once): paper barely stretches, and a tear relieves
//! it.

use folio_geometry::SheetMesh;
use folio_geometry::sheet::NONE;
use folio_tearing::{Edit, Kind, Propagation};

use folio_scene::clock::steps_in_frame;
use folio_scene::scene::Scene;

use crate::error::{RunError, fail};
use crate::meter::Meter;
use crate::report::{FrameRecord, PropagationRecord, Report, TearRecord, TearingLog};
use crate::shape::Shape;

/// The name of a potential tearing point's kind in reports and scenes.
#[must_use]
pub fn kind_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Tip => "tip",
        Kind::Finger => "finger",
        Kind::Junction => "junction",
        Kind::InwardAngle => "inward-angle",
    }
}

fn edit_name(edit: Edit) -> &'static str {
    match edit {
        Edit::Moved => "moved",
        Edit::Split => "split",
        Edit::Separated => "separated",
        _ => "other",
    }
}

fn length(path: &[[f64; 2]]) -> f64 {
    path.windows(2)
        .map(|w| ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt())
        .sum()
}

/// The largest and the RMS edge stretch of `mesh` (module docs); zeros without an edge.
fn edge_stretch(mesh: &SheetMesh<f64>) -> (f64, f64) {
    let (mut max, mut sum, mut count) = (0.0f64, 0.0f64, 0usize);
    for (t, tri) in mesh.triangles().iter().enumerate() {
        for k in 0..3 {
            let h = (3 * t + k) as u32;
            let twin = mesh.twin(h);
            if twin != NONE && twin < h {
                continue;
            }
            let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
            let (p, q) = (mesh.pattern()[a], mesh.pattern()[b]);
            let rest = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
            if rest <= 0.0 {
                continue;
            }
            let now = (mesh.positions()[b] - mesh.positions()[a]).length();
            let stretch = (now / rest - 1.0).abs();
            max = max.max(stretch);
            sum += stretch * stretch;
            count += 1;
        }
    }
    (max, (sum / count.max(1) as f64).sqrt())
}

fn record(frame: u32, p: &Propagation<f64>) -> PropagationRecord {
    PropagationRecord {
        frame,
        tear: p.tear,
        kind: kind_name(p.kind),
        from: p.from,
        to: p.to,
        release_rate: p.release_rate,
        fracture_energy: p.fracture_energy,
        edit: edit_name(p.edit),
    }
}

/// Runs the checked sheet scene `scene`, calling `progress(frame, frames)` and
/// `observe(frame, frames, shape)` after every frame.
///
/// # Errors
/// A sheet the scene describes but that refuses to start, or a finger target it refuses.
pub fn run(
    scene: &Scene,
    mut progress: impl FnMut(u32, u32),
    mut observe: impl FnMut(u32, u32, Shape<'_>),
) -> Result<Report, RunError> {
    let (mut sheet, mut hands) = folio_scene::sheet::setup(scene).map_err(|e| fail(e.1))?;
    let n = folio_scene::sheet::frames(scene).map_err(|e| fail(e.1))?;
    let h = sheet.settings().time_step;
    let mut records = Vec::with_capacity(n as usize);
    let mut propagations = Vec::new();
    for frame in 0..n {
        // A finger target the sheet refuses is an input that did nothing: the run goes on.
        let inputs: Vec<String> = hands
            .apply(&mut sheet, frame)
            .err()
            .map(|e| format!("the hands' move at frame {frame} was refused ({e})"))
            .into_iter()
            .collect();
        let before = sheet.propagations().len();
        let (wanted, mut steps) = (steps_in_frame(frame, h), 0);
        let (mut propagated, mut refused, mut flips, mut bad_loads) = (0, 0, 0, 0);
        let meter = Meter::start();
        let mut step = sheet.step();
        loop {
            steps += 1;
            propagated += step.propagations;
            refused += step.refused;
            flips += step.flips;
            bad_loads += step.non_finite_loads;
            // A failed step ends the frame: the sheet kept its state.
            if steps >= wanted || !step.status.advanced() {
                break;
            }
            step = sheet.step();
        }
        let (step_ms, allocations) = meter.stop();
        propagations.extend(
            sheet.propagations()[before..]
                .iter()
                .map(|p| record(frame, p)),
        );
        let mesh = sheet.mesh();
        let (max, rmse) = edge_stretch(mesh);
        // A tearing point whose load was not finite is a non-finite state too.
        let finite = bad_loads == 0
            && mesh
                .positions()
                .iter()
                .chain(mesh.velocities())
                .all(|x| x.is_finite());
        records.push(FrameRecord {
            max_stretch: Some(max),
            rmse_stretch: Some(rmse),
            propagations: Some(propagated),
            refused: Some(refused),
            flips: Some(flips),
            triangles: Some(mesh.triangle_count()),
            inputs,
            allocations,
            ..FrameRecord::new(frame, steps, step_ms, String::new(), !finite).solver(step.status)
        });
        observe(frame, n, Shape::Sheet(&sheet));
        progress(frame + 1, n);
    }
    let tears: Vec<TearRecord> = sheet
        .tears()
        .tears()
        .iter()
        .map(|t| TearRecord {
            parent: t.parent,
            open: t.tip.is_some(),
            length: length(&t.path),
            path: t.path.clone(),
        })
        .collect();
    let mut report = Report::new(scene, records, None);
    let summary = &mut report.summary;
    summary.propagations_total = Some(propagations.len());
    summary.tear_lengths = Some(tears.iter().map(|t| t.length).collect());
    summary.tear_start = sheet
        .propagations()
        .first()
        .map(|p| kind_name(p.kind).into());
    let raster = sheet.tears().raster();
    report.tearing = Some(TearingLog {
        texture_size: [raster.width_px(), raster.height_px()],
        propagations,
        tears,
    });
    report.judge(&scene.expect);
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use folio_kernels::Vec3Ops;

    #[test]
    fn a_flat_sheet_is_unstretched_and_a_lengthened_one_is() {
        let mut mesh = SheetMesh::<f64>::rectangle(2.0, 1.0, 2, 1).unwrap();
        assert_eq!(edge_stretch(&mesh), (0.0, 0.0));
        for x in mesh.positions_mut() {
            *x = Vec3Ops::new(1.01 * x.x(), x.y(), x.z());
        }
        let (max, rmse) = edge_stretch(&mesh);
        assert!((max - 0.01).abs() < 1e-12, "{max}");
        assert!(rmse > 0.0 && rmse < max);
    }
}
