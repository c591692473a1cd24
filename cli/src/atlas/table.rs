//! `atlas.md`: the atlas as a table, with the reference and its proof of convergence.

use core::fmt::Write as _;

use super::{Atlas, PROOF_FRACTION, Row};

/// `v` as a percentage with two decimals, or `-`.
fn percent(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{:.2}", 100.0 * v))
}

/// `v` in scientific notation, or `-`.
fn sci(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{v:.1e}"))
}

/// `v` in milliseconds with three decimals, or `-`.
fn ms(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{v:.3}"))
}

/// `v` in millions with two decimals, or `-`.
fn mega(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{:.2}", v / 1e6))
}

/// One table line of `row`.
fn line(row: &Row) -> String {
    let e = row.errors;
    let c = row.costs;
    let pages = row
        .final_pages
        .map_or_else(|| "-".into(), |[l, r, h]| format!("{l}/{r}/{h}"));
    let verdict = match (&row.refused, row.good) {
        (Some(_), _) => "refused",
        (None, true) => "good",
        (None, false) => "bad",
    };
    format!(
        "| {}{} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
        row.label,
        if row.pareto { " **(P)**" } else { "" },
        ms(c.map(|c| c.frame_ms_mean)),
        ms(c.map(|c| c.frame_ms_median)),
        ms(c.map(|c| c.frame_ms_p99)),
        c.map_or_else(|| "-".into(), |c| format!("{:.1}", c.allocations_per_step)),
        mega(c.and_then(|c| c.instructions_per_frame)),
        percent(e.map(|e| e.rms_mean)),
        percent(e.map(|e| e.rms_worst)),
        percent(e.map(|e| e.max_worst)),
        percent(e.map(|e| e.tip_rms)),
        percent(row.stretch_max),
        percent(row.stretch_rms_mean),
        sci(row.dog_residual_max),
        sci(row.penetration_max),
        pages,
        if row.bad_frames > 0 {
            format!("{verdict} ({} bad frames)", row.bad_frames)
        } else {
            verdict.to_string()
        }
    )
}

/// The atlas as Markdown (module docs).
#[must_use]
pub fn markdown(atlas: &Atlas) -> String {
    let mut out = String::new();
    let p = &atlas.proof;
    let _ = writeln!(out, "# Accuracy atlas: {}\n", atlas.scene);
    let _ = writeln!(
        out,
        "{} frames (1/60 s each), {} material points a frame. Errors are against the reference, as % of the page width ({}). Costs are the compute time of a 1/60 s frame (mean, median, p99) and heap allocations per step, measured two variants at a time on two cores.\n",
        atlas.frames, atlas.samples, atlas.page_width
    );
    let knobs = |k: &alloc::collections::BTreeMap<String, toml::Value>| {
        k.iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let _ = writeln!(
        out,
        "**Reference:** the DOG book, {} ({} ms a frame, mean).",
        knobs(&p.reference),
        ms(Some(p.costs.frame_ms_mean))
    );
    match p.refinement {
        Some(e) => {
            let _ = writeln!(
                out,
                "**Refined once more** ({}) it moves by {} % of the page width (mean RMS; worst frame {} %), against {} % for the smallest error below: {}.\n",
                knobs(&p.refined),
                percent(Some(e.rms_mean)),
                percent(Some(e.rms_worst)),
                percent(Some(p.smallest_error)),
                if p.converged {
                    format!("converged (less than {PROOF_FRACTION} of it)")
                } else {
                    format!(
                        "**not proven converged** (it must be less than {PROOF_FRACTION} of it): read the errors below as distances from a page that is itself still moving with resolution"
                    )
                }
            );
        }
        None => {
            let _ = writeln!(
                out,
                "The reference was not refined: it is not proven converged.\n"
            );
        }
    }
    out.push_str("| variant | frame ms mean | median | p99 | allocs/step | M instr/frame | RMS err mean % | RMS err worst % | max err worst % | tip err RMS % | stretch max % | stretch RMS mean % | DOG residual | penetration | pages L/R/held | run |\n");
    out.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for row in &atlas.variants {
        out.push_str(&line(row));
        out.push('\n');
    }
    out.push_str("\n(P): on the Pareto front of error against mean frame time.\n");
    if let Some(c) = &atlas.convergence {
        let grids: Vec<String> = c.grids.iter().map(|[a, b]| format!("{a}x{b}")).collect();
        let moves: Vec<String> = c
            .differences
            .iter()
            .map(|e| format!("{} %", percent(Some(e.rms_mean))))
            .collect();
        let _ = writeln!(
            out,
            "\n**Resolution:** the scene's model on the grids {} (each twice as fine) moves by {} of the page width (mean RMS, each grid against the next): observed order {:.2}.",
            grids.join(", "),
            moves.join(", then "),
            c.order
        );
    }
    out
}
