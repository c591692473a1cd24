//! Shading: the translucent page BTDF of seed `000_…` Sec. 4.2 (eq. 15-17), plain Lambert
//! for the other surfaces, and the tone mapping to display values.
//!
//! The page (seed eq. 15) reflects, specularly reflects and transmits:
//! $$f = k_d f_{\text{Lambert}} + k_s f_{\text{CT}} + k_t f_{\text{Lambert,back}},$$
//! with (eq. 16, 17, and $k_s = F_{\text{Schlick}}$ from the text after eq. 17)
//! $$k_t = (1 - F_{\text{Schlick,back}})\thinspace e^{-\alpha t}, \qquad
//!   k_d = (1 - F_{\text{Schlick}})(1 - e^{-\alpha t}), \qquad k_s = F_{\text{Schlick}},$$
//! where $t$ is the page's thickness and $\alpha$ the paper's absorption ([`Paper`]).
//! Folio's choices where the seed names none:
//!
//! - $F_{\text{Schlick}}(\cos) = F_0 + (1 - F_0)(1 - \cos)^5$ (Schlick 1994), evaluated at
//!   $\cos = h \cdot v$ for $k_s$ and $k_d$ (light arriving on the side seen) and at
//!   $\cos = \lvert n \cdot l\rvert$ for $k_t$ (light arriving on the other side);
//! - $f_{\text{CT}} = D\thinspace G / (4 (n\cdot l)(n\cdot v))$ (the Fresnel factor is $k_s$) with
//!   the GGX / Trowbridge-Reitz distribution
//!   $D = a^2 / (\pi ((n\cdot h)^2 (a^2 - 1) + 1)^2)$, $a = r^2$ for roughness $r$, and the
//!   separable Smith masking $G = G_1(n\cdot l)\thinspace G_1(n\cdot v)$,
//!   $G_1(x) = 2x / (x + \sqrt{a^2 + (1 - a^2) x^2})$ (Walter et al. 2007);
//! - $f_{\text{Lambert}} = \rho / \pi$ with the albedo $\rho$ of the side seen, and
//!   $f_{\text{Lambert,back}} = \rho\thinspace \rho_{\text{back}} / \pi$: transmitted light crosses
//!   the print of both sides, so the back's print shows through, mirrored.
//!
//! With a point light of irradiance $E$ (normal incidence, shadowing included) from the unit
//! direction $l$, the outgoing radiance towards $v$ is $E\thinspace\lvert n\cdot l\rvert\thinspace f$: only
//! the first two terms for $n \cdot l > 0$, only the third for $n \cdot l < 0$. A constant
//! ambient radiance $A$ arrives from both sides, shaded with $F = F_0$:
//! $A\thinspace((1 - F_0)(1 - e^{-\alpha t})\thinspace\rho + (1 - F_0)\thinspace e^{-\alpha t} \rho\thinspace\rho_{\text{back}})$.
//! Energy: $k_d + k_s \le 1$ and $k_d + k_t \le 1$ for $F, F_{\text{back}} \in [0, 1]$.

use core::f32::consts::PI;

use glam::Vec3;

use super::vector::normalize_or;

/// Optical parameters of the paper (seed `000_…` eq. 15-17).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Paper {
    /// Thickness $t$ of one page (page units; the seed's 0.0075). The active page of a
    /// stack of $k$ pages is $k t$ thick ([`super::ContactSheet::add_frame`]).
    pub thickness: f32,
    /// Absorption $\alpha$ (1 / page unit), $\ge 0$: one page transmits $e^{-\alpha t}$.
    /// Default 200: $e^{-1.5} \approx 0.22$ for one page (thin printing paper lets through
    /// roughly a fifth of the light), $e^{-15} \approx 0$ for ten.
    pub absorption: f32,
    /// Roughness $r \in (0, 1]$ (GGX $a = r^2$). Default 0.65: matte uncoated paper.
    pub roughness: f32,
    /// Reflectance at normal incidence $F_0 \in [0, 1]$. Default 0.04 (refractive index
    /// about 1.5, cellulose).
    pub f0: f32,
}

impl Default for Paper {
    fn default() -> Self {
        Self {
            thickness: 0.0075,
            absorption: 200.0,
            roughness: 0.65,
            f0: 0.04,
        }
    }
}

impl Paper {
    /// The first field out of range, if any.
    #[must_use]
    pub fn invalid_field(&self) -> Option<&'static str> {
        let ok = |v: f32, lo: f32, hi: f32| v.is_finite() && (lo..=hi).contains(&v);
        if !ok(self.thickness, 0.0, 1e6) {
            Some("thickness")
        } else if !ok(self.absorption, 0.0, 1e9) {
            Some("absorption")
        } else if !(ok(self.roughness, 0.0, 1.0) && self.roughness > 0.0) {
            Some("roughness")
        } else if !ok(self.f0, 0.0, 1.0) {
            Some("f0")
        } else {
            None
        }
    }
}

/// Schlick's Fresnel approximation $F_0 + (1 - F_0)(1 - c)^5$, $c$ clamped to $[0, 1]$.
#[inline]
#[must_use]
pub fn schlick(f0: f32, cos: f32) -> f32 {
    let m = 1.0 - cos.clamp(0.0, 1.0);
    let m2 = m * m;
    f0 + (1.0 - f0) * m2 * m2 * m
}

/// The coefficients $(k_d, k_s, k_t)$ of eq. 15-17 for a page `thickness` thick, with
/// Fresnel factors `fresnel` (the side seen) and `fresnel_back` (the other side).
#[inline]
#[must_use]
pub fn coefficients(paper: &Paper, thickness: f32, fresnel: f32, fresnel_back: f32) -> [f32; 3] {
    let transmitted = (-paper.absorption * thickness.max(0.0)).exp();
    [
        (1.0 - fresnel) * (1.0 - transmitted),
        fresnel,
        (1.0 - fresnel_back) * transmitted,
    ]
}

/// $f_{\text{CT}}$ without its Fresnel factor (module docs), for unit $n, v, l$ with
/// $n \cdot l > 0$; 0 when $n \cdot v \le 0$.
#[must_use]
pub fn cook_torrance(n: Vec3, v: Vec3, l: Vec3, roughness: f32) -> f32 {
    let (nl, nv) = (n.dot(l), n.dot(v));
    if !(nl > 0.0 && nv > 0.0) {
        return 0.0;
    }
    let h = normalize_or(l + v, n);
    let nh = n.dot(h).clamp(0.0, 1.0);
    let a = (roughness * roughness).max(1e-3);
    let a2 = a * a;
    let q = nh * nh * (a2 - 1.0) + 1.0;
    let d = a2 / (PI * q * q);
    let g1 = |x: f32| 2.0 * x / (x + (a2 + (1.0 - a2) * x * x).sqrt());
    d * g1(nl) * g1(nv) / (4.0 * nl * nv)
}

/// What the page shader needs at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PagePoint {
    /// Unit normal of the side seen.
    pub normal: Vec3,
    /// Unit direction to the eye.
    pub view: Vec3,
    /// Unit direction to the light.
    pub light: Vec3,
    /// Irradiance $E$ at normal incidence (shadowing included).
    pub irradiance: f32,
    /// Ambient radiance $A$.
    pub ambient: f32,
    /// Albedo $\rho$ of the side seen.
    pub albedo: [f32; 3],
    /// Albedo $\rho_{\text{back}}$ of the other side at the same point.
    pub albedo_back: [f32; 3],
    /// Page thickness $t$ (page units).
    pub thickness: f32,
}

/// Outgoing radiance of a page point (module docs: eq. 15-17 plus ambient).
#[must_use]
pub fn page_radiance(paper: &Paper, p: &PagePoint) -> [f32; 3] {
    let nl = p.normal.dot(p.light);
    let [kd_a, _, kt_a] = coefficients(paper, p.thickness, paper.f0, paper.f0);
    let mut out = [0, 1, 2].map(|c| p.ambient * p.albedo[c] * (kd_a + kt_a * p.albedo_back[c]));
    if nl > 0.0 {
        let h = normalize_or(p.light + p.view, p.normal);
        let fresnel = schlick(paper.f0, h.dot(p.view));
        let [kd, ks, _] = coefficients(paper, p.thickness, fresnel, paper.f0);
        let specular = ks * cook_torrance(p.normal, p.view, p.light, paper.roughness);
        for (o, a) in out.iter_mut().zip(p.albedo) {
            *o += p.irradiance * nl * (kd * a / PI + specular);
        }
    } else if nl < 0.0 {
        let fresnel_back = schlick(paper.f0, -nl);
        let [_, _, kt] = coefficients(paper, p.thickness, paper.f0, fresnel_back);
        for ((o, a), b) in out.iter_mut().zip(p.albedo).zip(p.albedo_back) {
            *o += p.irradiance * -nl * kt * a * b / PI;
        }
    }
    out
}

/// Outgoing radiance of an opaque Lambertian point: $E \max(n\cdot l, 0)\thinspace\rho/\pi + A\rho$.
#[must_use]
pub fn lambert_radiance(
    albedo: [f32; 3],
    normal: Vec3,
    light: Vec3,
    irradiance: f32,
    ambient: f32,
) -> [f32; 3] {
    let nl = normal.dot(light).max(0.0);
    albedo.map(|a| a * (irradiance * nl / PI + ambient))
}

/// Display value of a radiance: exponential tone mapping $1 - e^{-k L}$ (exposure $k$),
/// then the sRGB transfer function; NaN and negative radiances give 0. Always in $[0, 1]$.
#[must_use]
pub fn tone_map(radiance: f32, exposure: f32) -> f32 {
    let linear = if radiance > 0.0 {
        1.0 - (-exposure * radiance).exp()
    } else {
        0.0
    };
    srgb(linear)
}

/// The sRGB transfer function of a linear value, clamped to $[0, 1]$ (NaN gives 0).
#[must_use]
pub fn srgb(linear: f32) -> f32 {
    let linear = if linear.is_finite() {
        linear.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let encoded = if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    };
    encoded.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::vector::normalize_or;

    /// Eq. 16-17 conserve energy: $k_d + k_t \le 1$, $k_d + k_s \le 1$, all in $[0, 1]$,
    /// over thicknesses and angles; one page transmits $e^{-\alpha t}$ at $F = 0$.
    #[test]
    fn coefficients_conserve_energy() {
        let paper = Paper::default();
        for &t in &[0.0, 0.0075, 0.05, 1.0, 1e9] {
            for i in 0..=20 {
                let cos = i as f32 / 20.0;
                let f = schlick(paper.f0, cos);
                assert!((paper.f0..=1.0).contains(&f));
                let [kd, ks, kt] = coefficients(&paper, t, f, schlick(paper.f0, 1.0 - cos));
                for k in [kd, ks, kt] {
                    assert!((0.0..=1.0).contains(&k), "{kd} {ks} {kt}");
                }
                assert!(kd + kt <= 1.0 + 1e-6 && kd + ks <= 1.0 + 1e-6);
            }
        }
        let ideal = Paper { f0: 0.0, ..paper };
        let [kd, _, kt] = coefficients(&ideal, ideal.thickness, 0.0, 0.0);
        assert!((kt - (-1.5f32).exp()).abs() < 1e-6 && (kd + kt - 1.0).abs() < 1e-6);
    }

    /// The GGX lobe with Smith masking reflects at most what arrives (white furnace bound
    /// for the specular part: $\int f_{\text{CT}} F \cos\theta_l \thinspace d\omega \le 1$).
    #[test]
    fn cook_torrance_is_bounded() {
        let n = Vec3::Y;
        for &r in &[0.2, 0.65, 1.0] {
            for &view_angle in &[0.0f32, 0.6, 1.2] {
                let v = Vec3::new(view_angle.sin(), view_angle.cos(), 0.0);
                let mut sum = 0.0;
                let steps = 200;
                for i in 0..steps {
                    for j in 0..steps {
                        let theta = (i as f32 + 0.5) / steps as f32 * PI / 2.0;
                        let phi = (j as f32 + 0.5) / steps as f32 * 2.0 * PI;
                        let l = Vec3::new(
                            theta.sin() * phi.cos(),
                            theta.cos(),
                            theta.sin() * phi.sin(),
                        );
                        let d_omega =
                            theta.sin() * (PI / 2.0 / steps as f32) * (2.0 * PI / steps as f32);
                        sum += cook_torrance(n, v, l, r) * theta.cos() * d_omega;
                    }
                }
                assert!(
                    sum.is_finite() && sum <= 1.05,
                    "r {r} angle {view_angle}: {sum}"
                );
            }
        }
    }

    /// Lit from the front, the page shows its own print; lit from behind, it glows with
    /// both prints, dimmer; every radiance is finite and tone-maps into [0, 1].
    #[test]
    fn page_radiance_front_and_back_lighting() {
        let paper = Paper::default();
        let white = [0.9; 3];
        let ink = [0.2; 3];
        let point = |light: [f32; 3], back: [f32; 3]| PagePoint {
            normal: Vec3::Y,
            view: normalize_or(Vec3::new(0.3, 1.0, 0.2), Vec3::Y),
            light: normalize_or(light.into(), Vec3::Y),
            irradiance: 3.0,
            ambient: 0.0,
            albedo: white,
            albedo_back: back,
            thickness: paper.thickness,
        };
        let front = page_radiance(&paper, &point([0.2, 1.0, 0.1], white));
        let behind = page_radiance(&paper, &point([0.2, -1.0, 0.1], white));
        let behind_ink = page_radiance(&paper, &point([0.2, -1.0, 0.1], ink));
        assert!(front[0] > behind[0] && behind[0] > behind_ink[0] && behind_ink[0] > 0.0);
        // A thick stack transmits nothing.
        let mut thick = point([0.2, -1.0, 0.1], white);
        thick.thickness = 1.0;
        assert!(page_radiance(&paper, &thick)[0] < 1e-20);
        for l in [front, behind, behind_ink] {
            for c in l {
                let d = tone_map(c, 1.5);
                assert!(c.is_finite() && (0.0..=1.0).contains(&d));
            }
        }
        for x in [f32::NAN, f32::INFINITY, -1.0, 0.0, 1e30] {
            assert!((0.0..=1.0).contains(&tone_map(x, 1.5)));
        }
    }
}
