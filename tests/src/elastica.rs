//! The cantilever elastica under uniform self-weight: an independent reference for a page
//! clamped at the binding and left to sag (issue 21).
//!
//! A strip of length $L$, bending stiffness $B$ (N·m², the plate's $D$ times the strip's
//! width) and weight $q$ per unit length (N/m) is clamped horizontally at $s = 0$ and free at
//! $s = L$. With $\theta(s)$ the tangent's angle above the horizontal, the moment that the
//! part beyond $s$ exerts is $B\theta'(s) = -q\int_s^L (x(\sigma) - x(s))\,d\sigma$, and
//! differentiating once gives the inextensible elastica
//! $$B\,\theta''(s) = q\,(L - s)\cos\theta(s),\qquad \theta(0) = 0,\quad \theta'(L) = 0,$$
//! with $x' = \cos\theta$, $y' = \sin\theta$. In $t = s/L$ it depends on one number,
//! $\alpha = qL^3/B$ (for a page of areal density $\rho$, $q/B = \rho g/D$, so
//! $\alpha = \rho g L^3/D$): $\ddot\theta = \alpha(1 - t)\cos\theta$.
//!
//! It is solved by shooting on $\theta'(0)$. The bracket is exact: $\theta'(0) = 0$ ends with
//! $\theta'(1) > 0$, and $\theta'(0) = -\alpha/2$ (the small-deflection root moment) ends
//! with $\theta'(1) = -\alpha/2 + \alpha\int_0^1 (1 - t)\cos\theta \le 0$. Each trial
//! integrates the system with classical Runge–Kutta (fourth order) on a uniform grid, and
//! bisection closes the bracket to rounding. For small $\alpha$ the tip deflection tends to
//! the beam value $\alpha/8$ (in units of $L$).

/// The settled shape's tip, in units of the strip's length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sag {
    /// How far the tip hangs below the clamp, $-y(L)/L \ge 0$.
    pub tip_deflection: f64,
    /// The tip's horizontal reach, $x(L)/L \le 1$.
    pub tip_reach: f64,
    /// The tip's angle below the horizontal, $-\theta(L)$ (radians).
    pub tip_angle: f64,
    /// The root curvature $\theta'(0)\,L$ found by the shooting.
    pub root_curvature: f64,
}

/// State of the shooting system: $(\theta, \theta', x, y)$ in units of $L$.
type State = [f64; 4];

/// $\dot u$ of the elastica at $t$ for $\alpha$.
fn rate(alpha: f64, t: f64, u: State) -> State {
    let (sin, cos) = u[0].sin_cos();
    [u[1], alpha * (1.0 - t) * cos, cos, sin]
}

/// Integrates from $t = 0$ to 1 in `steps` classical Runge–Kutta steps, from
/// $\theta = 0$, $\theta' = $ `root_curvature`, at the origin. Stops early when $\theta$
/// leaves $[-\pi/2, 0]$, the hanging shape's range, with `Some(true)` if it passed the
/// vertical (over-bent) and `Some(false)` if it rose above the clamp (under-bent).
fn integrate(alpha: f64, root_curvature: f64, steps: usize) -> (State, Option<bool>) {
    let h = 1.0 / steps as f64;
    let mut u = [0.0, root_curvature, 0.0, 0.0];
    let along = |u: State, k: State, f: f64| -> State { core::array::from_fn(|i| u[i] + f * k[i]) };
    for i in 0..steps {
        let t = i as f64 * h;
        let k1 = rate(alpha, t, u);
        let k2 = rate(alpha, t + h / 2.0, along(u, k1, h / 2.0));
        let k3 = rate(alpha, t + h / 2.0, along(u, k2, h / 2.0));
        let k4 = rate(alpha, t + h, along(u, k3, h));
        u = core::array::from_fn(|j| u[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]));
        if u[0] > 0.0 || u[0] < -core::f64::consts::FRAC_PI_2 {
            return (u, Some(u[0] < 0.0));
        }
    }
    (u, None)
}

/// Whether the trial from `root_curvature` bends too far. The hanging shape keeps
/// $-\pi/2 \le \theta \le 0$; a trial that first leaves that range below is over-bent, one
/// that first leaves it above is under-bent, and one that stays in it is over-bent when it
/// ends curving down ($\theta'(1) < 0$). Without the range test, heavy strips
/// ($\alpha \gtrsim 200$) have spurious roots whose shape swings back above the clamp.
fn overbent(alpha: f64, root_curvature: f64, steps: usize) -> bool {
    match integrate(alpha, root_curvature, steps) {
        (_, Some(over)) => over,
        (end, None) => end[1] < 0.0,
    }
}

/// The clamped strip's settled shape for $\alpha = qL^3/B$ (module docs), integrated on
/// `steps` Runge–Kutta steps (2000 gives about 1e-12 relative; the tests check it).
///
/// # Panics
/// If `alpha` is not in $(0, 300]$ or `steps` is 0 (a test helper: bad input is a bug in the
/// test). Above about 300 the strip hangs vertically in a boundary layer at the clamp, the
/// range test cannot tell rounding from passing the vertical, and the shooting loses its
/// bracket (1000 gave a tip deflection that moved by 4 % between 2000 and 8000 steps).
#[must_use]
pub fn cantilever(alpha: f64, steps: usize) -> Sag {
    assert!(
        alpha.is_finite() && alpha > 0.0 && steps > 0,
        "alpha {alpha}, steps {steps}"
    );
    let (mut low, mut high) = (-alpha / 2.0, 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if mid <= low || mid >= high {
            break;
        }
        if !overbent(alpha, mid, steps) {
            high = mid;
        } else {
            low = mid;
        }
    }
    let root_curvature = 0.5 * (low + high);
    let (u, _) = integrate(alpha, root_curvature, steps);
    Sag {
        tip_deflection: -u[3],
        tip_reach: u[2],
        tip_angle: -u[0],
        root_curvature,
    }
}

#[cfg(test)]
mod tests {
    use super::cantilever;

    /// Small loads tend to the Euler–Bernoulli cantilever: tip deflection $qL^4/(8B)$, tip
    /// slope $qL^3/(6B)$, root moment $qL^2/2$.
    #[test]
    fn small_loads_match_the_linear_beam() {
        let alpha = 1e-3;
        let sag = cantilever(alpha, 2000);
        assert!(
            (sag.tip_deflection / (alpha / 8.0) - 1.0).abs() < 1e-3,
            "{sag:?}"
        );
        assert!(
            (sag.tip_angle / (alpha / 6.0) - 1.0).abs() < 1e-3,
            "{sag:?}"
        );
        assert!(
            (sag.root_curvature / (-alpha / 2.0) - 1.0).abs() < 1e-3,
            "{sag:?}"
        );
    }

    /// The integration has converged: halving the step moves the tip by less than 1e-10.
    #[test]
    fn the_grid_is_converged() {
        for alpha in [0.5, 5.0, 50.0, 300.0] {
            let (a, b) = (cantilever(alpha, 1000), cantilever(alpha, 2000));
            assert!(
                (a.tip_deflection - b.tip_deflection).abs() < 1e-10,
                "{a:?} {b:?}"
            );
        }
    }

    /// Large loads stay inextensible and bounded: the tip's position lies on or inside the
    /// unit circle (arc length 1), hangs more with more load, and never past vertical.
    #[test]
    fn heavy_strips_hang_but_keep_their_length() {
        let mut last = 0.0;
        for alpha in [1.0, 10.0, 100.0, 300.0] {
            let sag = cantilever(alpha, 2000);
            let chord = sag.tip_deflection.hypot(sag.tip_reach);
            assert!(chord <= 1.0 + 1e-12 && sag.tip_deflection > last, "{sag:?}");
            assert!(
                sag.tip_angle < core::f64::consts::FRAC_PI_2 + 1e-9,
                "{sag:?}"
            );
            last = sag.tip_deflection;
        }
    }
}
