#!/usr/bin/python3
"""An independent numpy reference for linearly transformed cosines (LTC) and GGX (issue 33).

Written from the papers, sharing no code with brdfbake's kernels or with ltc_code:
  [HDHN16] Heitz, Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
           Transformed Cosines", ACM TOG 35(4).
  [H14]    Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs".
  [H18]    Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4).
  [WMLT07] Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction".

Conventions (docs/ltc_presets.md, the LTC contract): normal +z, viewer at
wo = (sin theta_o, 0, cos theta_o), M[row][col] with w = M w_c / |M w_c|.

What it computes:
  ggx_fcos            f(wo, wi) cos theta_i of GGX with Smith height-correlated G2 and F = 1
  ltc_density         D(w) of an LTC M [HDHN16 eq. 1-2, with the Jacobian]
  lobe_terms          E (albedo), the Schlick split's fresnel term, by VNDF-mapped midpoint rule
  l1_distance         integral over the upper hemisphere of |p - D|, p = f cos / E
  ltc_polygon_integral  integral of D over a polygon [HDHN16 sec. 3.3, 4: transform, clip, Lambert]
  quad_fcos_integral  brute-force integral of f cos over a planar quad (composite Gauss-Legendre)

Run `/usr/bin/python3 tests/ltc_reference.py --check` for the self-checks (exit 0 when all pass).
"""
import math
import sys

import numpy as np

# ---------------------------------------------------------------- GGX with Smith G2 (correlated)


def ggx_lambda(z, alpha):
    """Smith Lambda of GGX for a direction of cosine z > 0 [H14 eq. 86]:
    Lambda = (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2."""
    z = np.asarray(z, dtype=float)
    zz = np.clip(z, 1e-300, 1.0)
    tan2 = np.maximum(1.0 - zz * zz, 0.0) / (zz * zz)
    return 0.5 * (-1.0 + np.sqrt(1.0 + alpha * alpha * tan2))


def ggx_ndf(h, alpha):
    """GGX normal distribution D(h) = alpha^2 / (pi (cos^2 (alpha^2 - 1) + 1)^2) [WMLT07 eq. 33],
    the bracket written sin^2 + alpha^2 cos^2 so that alpha = 1e-4 keeps its digits."""
    hz2 = h[..., 2] ** 2
    sin2 = h[..., 0] ** 2 + h[..., 1] ** 2
    den = sin2 + alpha * alpha * hz2
    return alpha * alpha / (math.pi * den * den)


def ggx_fcos(wo, wi, alpha):
    """f(wo, wi) cos theta_i = D(h) G2(wo, wi) / (4 cos theta_o), F = 1 [WMLT07 eq. 20], with the
    height-correlated G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) [H14 eq. 99]: brdfbake's `ggx`
    (shadowing=correlated, its default) and ltc_code's fit/brdf_ggx.h use this same G2.
    Zero where either direction is at or below the horizon."""
    wo = np.broadcast_to(wo, wi.shape)
    h = wo + wi
    h = h / np.linalg.norm(h, axis=-1, keepdims=True)
    ok = (wo[..., 2] > 0) & (wi[..., 2] > 0)
    g2 = 1.0 / (1.0 + ggx_lambda(wo[..., 2], alpha) + ggx_lambda(wi[..., 2], alpha))
    val = ggx_ndf(h, alpha) * g2 / (4.0 * np.where(ok, wo[..., 2], 1.0))
    return np.where(ok, val, 0.0)


def vndf_sample(wo, alpha, u1, u2):
    """Heitz 2018's visible-normal sampling [H18 listing 1], isotropic alpha, reflected about the
    sampled normal. Returns (wi, h). The pdf of wi is G1(wo) D(h) / (4 cos theta_o)."""
    vh = np.array([alpha * wo[0], alpha * wo[1], wo[2]])
    vh /= np.linalg.norm(vh)
    lensq = vh[0] ** 2 + vh[1] ** 2
    t1v = np.array([-vh[1], vh[0], 0.0]) / math.sqrt(lensq) if lensq > 0 else np.array([1.0, 0.0, 0.0])
    t2v = np.cross(vh, t1v)
    r = np.sqrt(u1)
    phi = 2.0 * math.pi * u2
    t1 = r * np.cos(phi)
    t2 = r * np.sin(phi)
    s = 0.5 * (1.0 + vh[2])
    t2 = (1.0 - s) * np.sqrt(np.maximum(1.0 - t1 * t1, 0.0)) + s * t2
    t3 = np.sqrt(np.maximum(1.0 - t1 * t1 - t2 * t2, 0.0))
    nh = t1[..., None] * t1v + t2[..., None] * t2v + t3[..., None] * vh
    ne = np.stack([alpha * nh[..., 0], alpha * nh[..., 1], np.maximum(nh[..., 2], 0.0)], axis=-1)
    ne /= np.linalg.norm(ne, axis=-1, keepdims=True)
    wi = 2.0 * (ne @ wo)[..., None] * ne - wo
    return wi, ne


def vndf_pdf(wo, h, alpha):
    """pdf of vndf_sample's wi: D_v(h) / (4 wo.h) = G1(wo) D(h) / (4 cos theta_o) [H18 eq. 17]."""
    g1o = 1.0 / (1.0 + ggx_lambda(wo[2], alpha))
    return g1o * ggx_ndf(h, alpha) / (4.0 * wo[2])


def view(mu):
    """The contract's viewer: (sin theta_o, 0, cos theta_o) with cos theta_o = mu."""
    return np.array([math.sqrt(max(0.0, 1.0 - mu * mu)), 0.0, mu])


def midpoint_grid(n):
    """The n x n midpoint rule on the unit square: (u1, u2) flattened, weight 1/n^2 each."""
    u = (np.arange(n) + 0.5) / n
    u1, u2 = np.meshgrid(u, u, indexing="ij")
    return u1.ravel(), u2.ravel()


# The VNDF map sends GGX's tail (slopes beyond 1, where wi nears the horizon) to u1 within about
# alpha^2 of 1: a plain midpoint rule leaves that strip unresolved for alpha < 0.1 (E did not
# converge at n = 2048 for alpha = 0.057). u1 = 1 - (1 - s)^GRADE with s on the midpoint rule puts
# that strip at 1 - s ~ alpha^(2/GRADE), and each node weighs the measure of its cell.
GRADE = 4


def graded_grid(n):
    """(u1, u2, weight) of the n x n midpoint rule graded towards u1 = 1 (GRADE)."""
    s, u2 = midpoint_grid(n)
    u1 = 1.0 - (1.0 - s) ** GRADE
    # each node weighs its cell's exact measure in u1, (1 - s_lo)^GRADE - (1 - s_hi)^GRADE, so
    # that constants are integrated exactly (the midpoint value of GRADE (1 - s)^(GRADE - 1)
    # is not: it left 1 - E = 3e-5 at n = 128 for a mirror-like lobe)
    lo = np.clip(s - 0.5 / n, 0.0, 1.0)
    hi = np.clip(s + 0.5 / n, 0.0, 1.0)
    return u1, u2, ((1.0 - lo) ** GRADE - (1.0 - hi) ** GRADE) / n


def lobe_terms(mu, alpha, n=512):
    """E = integral of f cos dwi and the Schlick split's fresnel term, integral of
    f cos (1 - wo.h)^5 dwi, by the midpoint rule on the VNDF map: f cos / pdf = G2 / G1(wo),
    a bounded smooth weight. Returns (E, fresnel)."""
    wo = view(mu)
    u1, u2, qw = graded_grid(n)
    wi, h = vndf_sample(wo, alpha, u1, u2)
    up = wi[:, 2] > 0
    lo = ggx_lambda(wo[2], alpha)
    li = ggx_lambda(np.where(up, wi[:, 2], 1.0), alpha)
    w = np.where(up, (1.0 + lo) / (1.0 + lo + li), 0.0) * qw
    schlick = (1.0 - np.clip(h @ wo, 0.0, 1.0)) ** 5
    return float(w.sum()), float((w * schlick).sum())


# ------------------------------------------------------------------------ LTC distribution


def ltc_density(m, w):
    """D(w) = Do(w_o) |det M^-1| / |M^-1 w|^3, w_o = M^-1 w / |M^-1 w|, Do = max(0, z)/pi
    [HDHN16 eq. 1 and 2: the Jacobian d w_o / d w = |M^-1| / |M^-1 w|^3]."""
    minv = np.linalg.inv(m)
    x = w @ minv.T
    r = np.linalg.norm(x, axis=-1)
    do = np.maximum(x[..., 2] / r, 0.0) / math.pi
    return do * abs(np.linalg.det(minv)) / r ** 3


def ltc_sample(m, u1, u2):
    """w = M w_c / |M w_c| with w_c cosine-distributed (Malley's disk map): pdf(w) = D(w)."""
    r = np.sqrt(u1)
    phi = 2.0 * math.pi * u2
    wc = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(np.maximum(1.0 - u1, 0.0))], axis=-1)
    w = wc @ m.T
    return w / np.linalg.norm(w, axis=-1, keepdims=True)


def ltc_upper_mass(m):
    """integral of D over the upper hemisphere in closed form: w.z > 0 iff (M^T e_z).w_c > 0, a
    half-space of normal n = (m20, m21, m22)/|.| in the cosine's domain, whose clamped-cosine
    mass is (1 + n_z)/2 (the tilted-plane sky factor)."""
    n = m[2, :] / np.linalg.norm(m[2, :])
    return 0.5 * (1.0 + n[2])


def matrix_from_channels(m00, m02, m11, m20, m22):
    """M with the contract's five non-zero entries (row-major: M[row][col])."""
    return np.array([[m00, 0.0, m02], [0.0, m11, 0.0], [m20, 0.0, m22]], dtype=float)


def l1_distance(mu, alpha, m, n=256, e=None):
    """integral over the upper hemisphere of |p - D|, p = f cos / E, D the LTC of M.

    Written |p - D| = (D - p) + 2 max(p - D, 0), so the distance is
    c - 1 + 2 integral of max(p - D, 0), with c = integral of D over the upper hemisphere in closed
    form (ltc_upper_mass) and integral of p = 1. max(p - D, 0) is continuous (p -> 0 at the
    horizon), so the midpoint rule converges at second order despite D's cut at the horizon. That
    integral is taken with both maps under the balance heuristic (Veach 1997): VNDF (pdf q) and the
    LTC's own (pdf D), each an n x n midpoint rule (graded for VNDF) of g / (q + D) <= max(1, 1/E).
    Returns (distance, E)."""
    wo = view(mu)
    if e is None:
        e = lobe_terms(mu, alpha, max(2 * n, 1024))[0]
    total = 0.0
    for sampler in ("vndf", "ltc"):
        u1, u2, qw = graded_grid(n)
        if sampler == "vndf":
            w, _ = vndf_sample(wo, alpha, u1, u2)
        else:
            w = ltc_sample(m, u1, u2)
        up = w[:, 2] > 0
        w = np.where(up[:, None], w, np.array([0.0, 0.0, 1.0]))
        h = wo + w
        h /= np.linalg.norm(h, axis=-1, keepdims=True)
        q = vndf_pdf(wo, h, alpha)
        p = ggx_fcos(wo, w, alpha) / e
        d = ltc_density(m, w)
        g = np.where(up, np.maximum(p - d, 0.0) / (q + d), 0.0)
        total += float(np.sum(g * qw))
    return ltc_upper_mass(m) - 1.0 + 2.0 * total, e


def l1_distance_converged(mu, alpha, m, n=256, tol=1e-3, n_max=1024):
    """l1_distance with its quadrature error estimate |L(n) - L(2n)| (second order: the error of
    L(2n) is about a third of that), n doubled while that exceeds tol and 2n <= n_max (grazing,
    mirror-like lobes). Returns (L(2n), |L(n) - L(2n)|, E)."""
    e = lobe_terms(mu, alpha, max(2 * n, 1024))[0]
    a, _ = l1_distance(mu, alpha, m, n, e)
    b, _ = l1_distance(mu, alpha, m, 2 * n, e)
    while abs(a - b) > tol and 4 * n <= n_max:
        n *= 2
        a, b = b, l1_distance(mu, alpha, m, 2 * n, e)[0]
    return b, abs(a - b), e


def l1_densities(p_fn, d_fn, grid=400):
    """integral over the upper hemisphere of |p - d| for two density functions of direction, on
    a (cos theta, phi) midpoint grid (uniform in solid angle): for smooth lobes and self-checks."""
    z, phi = midpoint_grid(grid)
    s = np.sqrt(1.0 - z * z)
    w = np.stack([s * np.cos(2 * math.pi * phi), s * np.sin(2 * math.pi * phi), z], axis=-1)
    return float(np.abs(p_fn(w) - d_fn(w)).mean() * 2.0 * math.pi)


# ------------------------------------------------------------------ polygon integrals of LTCs


def clip_to_upper(poly):
    """Sutherland-Hodgman clip of a polygon (k x 3 points about the shading point) to z >= 0."""
    out = []
    k = len(poly)
    for i in range(k):
        a, b = poly[i], poly[(i + 1) % k]
        if a[2] >= 0:
            out.append(a)
        if (a[2] >= 0) != (b[2] >= 0):
            t = a[2] / (a[2] - b[2])
            out.append(a + t * (b - a))
    return np.array(out)


def clamped_cosine_polygon(poly):
    """integral over the spherical polygon of max(0, z)/pi: clip to the upper hemisphere, then
    Lambert's formula 1/(2 pi) sum_i acos(v_i.v_j) (v_i x v_j / |v_i x v_j|).z [HDHN16 eq. 11;
    Arvo 1995]. Orientation-free (absolute value): simple polygons."""
    poly = clip_to_upper(np.asarray(poly, dtype=float))
    if len(poly) < 3:
        return 0.0
    v = poly / np.linalg.norm(poly, axis=1, keepdims=True)
    total = 0.0
    for i in range(len(v)):
        a, b = v[i], v[(i + 1) % len(v)]
        c = np.cross(a, b)
        cn = np.linalg.norm(c)
        if cn == 0.0:
            continue
        total += math.acos(max(-1.0, min(1.0, float(a @ b)))) * c[2] / cn
    return abs(total) / (2.0 * math.pi)


def ltc_polygon_integral(m, poly):
    """integral of D over the polygon = the clamped-cosine integral over M^-1 P [HDHN16 sec. 3.3:
    integrals of D over P equal those of Do over the transformed polygon, which they clip to the
    horizon, sec. 4.2]."""
    minv = np.linalg.inv(m)
    return clamped_cosine_polygon(np.asarray(poly, dtype=float) @ minv.T)


def gauss_legendre_panels(panels, order=8):
    """nodes and weights of a composite Gauss-Legendre rule on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(0.0, 1.0, panels + 1)
    mid = 0.5 * (edges[1:] + edges[:-1])
    half = 0.5 * (edges[1:] - edges[:-1])
    nodes = (mid[:, None] + half[:, None] * x[None, :]).ravel()
    weights = (half[:, None] * w[None, :]).ravel()
    return nodes, weights


def quad_integral(corner, e1, e2, fn, panels=32, order=8):
    """integral over the solid angle of the parallelogram corner + s e1 + t e2 (s, t in [0, 1]) of
    fn(w): dw = |n.x| / |x|^3 ds dt with n = e1 x e2 (composite Gauss-Legendre in s and t)."""
    s, ws = gauss_legendre_panels(panels, order)
    ss, tt = np.meshgrid(s, s, indexing="ij")
    wgt = np.outer(ws, ws).ravel()
    x = corner + ss.ravel()[:, None] * e1 + tt.ravel()[:, None] * e2
    r = np.linalg.norm(x, axis=1)
    n = np.cross(e1, e2)
    jac = np.abs(x @ n) / r ** 3
    return float(np.sum(wgt * jac * fn(x / r[:, None])))


def quad_fcos_integral(mu, alpha, corner, e1, e2, panels=None):
    """brute force integral of f cos over the quad; panels default from the lobe width (about
    alpha) against the quad's angular size. Returns (value, |value(panels) - value(panels/2)|)."""
    if panels is None:
        size = max(np.linalg.norm(e1), np.linalg.norm(e2)) / max(np.linalg.norm(corner), 1e-9)
        panels = int(min(256, max(16, math.ceil(4.0 * size / max(alpha, 1e-3)))))
    wo = view(mu)
    fn = lambda w: ggx_fcos(wo, w, alpha)  # noqa: E731
    fine = quad_integral(corner, e1, e2, fn, panels)
    coarse = quad_integral(corner, e1, e2, fn, max(1, panels // 2))
    return fine, abs(fine - coarse)


def random_quad_light(rng):
    """(corner, e1, e2) of a parallelogram light wholly above the horizon, facing the shading
    point: centre at elevation 15-75 degrees, distance 1-3, sides 0.3-1.5 (the quad-light study of
    docs/accuracy.md and its CI test draw the same way)."""
    while True:
        el, az = math.radians(rng.uniform(15, 75)), rng.uniform(0, 2 * math.pi)
        c = rng.uniform(1, 3) * np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
        n = -c / np.linalg.norm(c)
        t = np.cross(n, [0.0, 0.0, 1.0])
        t /= np.linalg.norm(t)
        b = np.cross(n, t)
        e1, e2 = rng.uniform(0.3, 1.5) * t, rng.uniform(0.3, 1.5) * b
        corner = c - 0.5 * e1 - 0.5 * e2
        if min(corner[2], (corner + e1)[2], (corner + e2)[2], (corner + e1 + e2)[2]) > 0:
            return corner, e1, e2


# ------------------------------------------------------------------ the published fit's file


def read_ltc_inc(path):
    """ltc_code's fit/results/ltc.inc: `tabM[size*size]`, 3x3 matrices written column by column
    (glm's m[col][row]: entries c*3 + r), texel index a + t*size with x = a (roughness = a/(N-1),
    alpha = max(roughness^2, 1e-4)) and y = t (the view angle, theta = min(1.57, t/(N-1) * 1.57079)
    in the versions with linear theta). Returns (size, mats[t, a, 3, 3] row-major, amplitude or
    None)."""
    text = open(path).read()
    size = int(text.split("size =")[1].split(";")[0])
    body = text.split("tabM[size*size]")[1].split("};")[0]
    nums = np.array([float(v.strip().rstrip("f")) for v in
                     body.replace("{", " ").replace("}", " ").replace("=", " ").split(",") if v.strip()])
    mats = nums[: size * size * 9].reshape(size, size, 3, 3).transpose(0, 1, 3, 2)
    amp = None
    if "tabAmplitude" in text:
        ab = text.split("tabAmplitude[size*size]")[1].split("};")[0].replace("{", " ").replace("=", " ")
        amp = np.array([float(v.strip().rstrip("f")) for v in ab.split(",") if v.strip()]).reshape(size, size)
    return size, mats, amp


def ltc_code_view_angle(t, size, parametrisation="theta"):
    """the view angle of ltc_code's row t: 'theta' (linear theta, the ltc.inc versions with
    tabM/tabAmplitude) or 'sqrt' (x = sqrt(1 - cos theta), the later fit three.js ships)."""
    x = t / float(size - 1)
    if parametrisation == "sqrt":
        return min(1.57, math.acos(1.0 - x * x))
    return min(1.57, x * 1.57079)


def ltc_code_alpha(a, size, parametrisation="theta"):
    """alpha of ltc_code's column a: roughness a/(N-1) squared, floored at MIN_ALPHA: 1e-4 in the
    linear-theta ltc.inc versions, 1e-5 in the later sqrt(1 - cos theta) fit (its data start at
    m11/m22 = 2e-05 where ltc.inc's start at 2e-4, twice the floor either way)."""
    r = a / float(size - 1)
    return max(r * r, 1e-5 if parametrisation == "sqrt" else 1e-4)


# ------------------------------------------------- batched over texels (the 64 x 64 comparison)
# The same quadratures as lobe_terms / l1_distance, evaluated for B texels at once (arrays
# [B, N, 3]): one numpy pass per texel batch instead of one per texel (the per-texel loop cost
# ~14 min per 512 texels under load). The VNDF points, p and q of a texel are shared by every
# matrix compared at it.


def vndf_sample_batch(wo, alpha, u1, u2):
    """vndf_sample for B viewers wo[B, 3] and alphas alpha[B] at the same (u1, u2)[N]:
    (wi[B, N, 3], h[B, N, 3])."""
    a = alpha[:, None]
    vh = np.stack([alpha * wo[:, 0], alpha * wo[:, 1], wo[:, 2]], axis=-1)
    vh /= np.linalg.norm(vh, axis=-1, keepdims=True)
    lensq = vh[:, 0] ** 2 + vh[:, 1] ** 2
    safe = np.sqrt(np.where(lensq > 0, lensq, 1.0))
    t1v = np.where((lensq > 0)[:, None], np.stack([-vh[:, 1], vh[:, 0], np.zeros_like(lensq)], -1) / safe[:, None],
                   np.array([1.0, 0.0, 0.0]))
    t2v = np.cross(vh, t1v)
    r = np.sqrt(u1)
    phi = 2.0 * math.pi * u2
    t1 = (r * np.cos(phi))[None, :]
    s = 0.5 * (1.0 + vh[:, 2:3])
    t2 = (1.0 - s) * np.sqrt(np.maximum(1.0 - t1 * t1, 0.0)) + s * (r * np.sin(phi))[None, :]
    t3 = np.sqrt(np.maximum(1.0 - t1 * t1 - t2 * t2, 0.0))
    nh = t1[..., None] * t1v[:, None, :] + t2[..., None] * t2v[:, None, :] + t3[..., None] * vh[:, None, :]
    ne = np.stack([a * nh[..., 0], a * nh[..., 1], np.maximum(nh[..., 2], 0.0)], axis=-1)
    ne /= np.linalg.norm(ne, axis=-1, keepdims=True)
    wi = 2.0 * np.einsum("bnk,bk->bn", ne, wo)[..., None] * ne - wo[:, None, :]
    return wi, ne


def _fcos_q_batch(wo, alpha, w):
    """(f cos [B, N], the VNDF pdf q [B, N]) at directions w[B, N, 3] below-horizon-safe (w.z > 0)."""
    a = alpha[:, None]
    h = wo[:, None, :] + w
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    d = ggx_ndf(h, a)
    lo = ggx_lambda(wo[:, 2], alpha)[:, None]
    li = ggx_lambda(w[..., 2], a)
    fcos = d / (1.0 + lo + li) / (4.0 * wo[:, 2:3])
    q = d / (1.0 + lo) / (4.0 * wo[:, 2:3])
    return fcos, q


def lobe_albedo_batch(mu, alpha, n):
    """E of lobe_terms for texels (mu[B], alpha[B]) on the graded n x n rule: E[B]."""
    wo = np.stack([np.sqrt(np.maximum(0.0, 1.0 - mu * mu)), np.zeros_like(mu), mu], axis=-1)
    u1, u2, qw = graded_grid(n)
    wi, _ = vndf_sample_batch(wo, alpha, u1, u2)
    up = wi[..., 2] > 0
    lo = ggx_lambda(wo[:, 2], alpha)[:, None]
    li = ggx_lambda(np.where(up, wi[..., 2], 1.0), alpha[:, None])
    return np.sum(np.where(up, (1.0 + lo) / (1.0 + lo + li), 0.0) * qw, axis=1)


def _ltc_density_batch(minv, det, w):
    x = np.einsum("bij,bnj->bni", minv, w)
    r = np.linalg.norm(x, axis=-1)
    return np.maximum(x[..., 2] / r, 0.0) / math.pi * det[:, None] / r ** 3


def l1_distance_batch(mu, alpha, mats, n, e):
    """l1_distance for texels (mu[B], alpha[B], E e[B]) and K matrices per texel mats[K, B, 3, 3]:
    distances[K, B] by the same balance-heuristic midpoint rules (n x n, VNDF graded)."""
    wo = np.stack([np.sqrt(np.maximum(0.0, 1.0 - mu * mu)), np.zeros_like(mu), mu], axis=-1)
    u1, u2, qw = graded_grid(n)
    minv = np.linalg.inv(mats)
    det = np.abs(np.linalg.det(minv))
    upper = 0.5 * (1.0 + mats[:, :, 2, 2] / np.linalg.norm(mats[:, :, 2, :], axis=-1))
    zenith = np.array([0.0, 0.0, 1.0])

    def part(w, k_only=None):
        up = w[..., 2] > 0
        w = np.where(up[..., None], w, zenith)
        fcos, q = _fcos_q_batch(wo, alpha, w)
        p = fcos / e[:, None]
        ks = range(len(mats)) if k_only is None else [k_only]
        return [np.sum(np.where(up, np.maximum(p - dk, 0.0) / (q + dk), 0.0) * qw, axis=1)
                for dk in (_ltc_density_batch(minv[k], det[k], w) for k in ks)]

    wv, _ = vndf_sample_batch(wo, alpha, u1, u2)
    total = np.array(part(wv))
    r = np.sqrt(u1)
    phi = 2.0 * math.pi * u2
    wc = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(np.maximum(1.0 - u1, 0.0))], axis=-1)
    for k in range(len(mats)):
        w = np.einsum("bij,nj->bni", mats[k], wc)
        w /= np.linalg.norm(w, axis=-1, keepdims=True)
        total[k] += part(w, k)[0]
    return upper - 1.0 + 2.0 * total


def l1_distance_converged_batch(mu, alpha, mats, n=128, tol=1e-3, n_max=1024, e_n=256, batch_points=1 << 21):
    """l1_distance_converged for many texels: (distance[K, B] = L(2n), error[K, B], E[B]); the
    error is |L(n) - L(2n)| plus E's share 2 |E(e_n/2) - E(e_n)| / E (p scales as 1/E, and the
    distance moves by at most twice p's relative change); texels whose quadrature error exceeds
    tol are redone at doubled n up to n_max, as the scalar version does. E on the graded e_n x e_n
    rule: at e_n = 256 it is within 1.5e-5 of e_n = 1024 (lobe_terms' default) for alpha 1e-3..1,
    on 256^2 + 128^2 points, a thirteenth of the 1024^2 that were most of the per-texel time."""
    mu, alpha = np.asarray(mu, float), np.asarray(alpha, float)
    mats = np.asarray(mats, float)
    b = len(mu)
    e, e_half = np.empty(b), np.empty(b)
    step = max(1, batch_points // (e_n * e_n))
    for i in range(0, b, step):
        e[i:i + step] = lobe_albedo_batch(mu[i:i + step], alpha[i:i + step], e_n)
        e_half[i:i + step] = lobe_albedo_batch(mu[i:i + step], alpha[i:i + step], e_n // 2)
    e_share = 2.0 * np.abs(e - e_half) / e
    dist = np.empty((len(mats), b))
    err = np.empty((len(mats), b))
    todo, level = np.arange(b), n
    while len(todo):
        step = max(1, batch_points // (4 * level * level * (1 + len(mats))))
        for i in range(0, len(todo), step):
            idx = todo[i:i + step]
            lo = l1_distance_batch(mu[idx], alpha[idx], mats[:, idx], level, e[idx])
            hi = l1_distance_batch(mu[idx], alpha[idx], mats[:, idx], 2 * level, e[idx])
            dist[:, idx], err[:, idx] = hi, np.abs(lo - hi)
        if 4 * level > n_max:
            break
        todo = todo[np.any(err[:, todo] > tol, axis=0)]
        level *= 2
    return dist, err + e_share[None, :], e


# ------------------------------------------------------------------------------ self-checks


def random_ltc(rng):
    """a random LTC matrix of the contract's shape, well conditioned, lobes of any tilt."""
    return matrix_from_channels(rng.uniform(0.2, 1.5), rng.uniform(-0.6, 0.6), rng.uniform(0.2, 1.5),
                                rng.uniform(-0.6, 0.6), rng.uniform(0.5, 1.5))


def rect_form_factor_parallel(a, b, c):
    """the differential-area to parallel-rectangle view factor, one rectangle corner above the
    point, sides a, b at height c (Howell's catalogue, configuration B-3):
    F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))]."""
    x, y = a / c, b / c
    sx, sy = math.sqrt(1 + x * x), math.sqrt(1 + y * y)
    return (x / sx * math.atan(y / sx) + y / sy * math.atan(x / sy)) / (2 * math.pi)


def self_checks(verbose=True):
    rng = np.random.default_rng(33)
    failures = []

    def check(name, ok, detail):
        if verbose:
            print(("ok   " if ok else "FAIL ") + name + ": " + detail)
        if not ok:
            failures.append(name)

    # 1. D integrates to 1 over the sphere for random M (the Jacobian), on a (z, phi) grid.
    for i in range(4):
        m = random_ltc(rng)
        z, phi = midpoint_grid(800)
        z = 2 * z - 1
        s = np.sqrt(1 - z * z)
        w = np.stack([s * np.cos(2 * math.pi * phi), s * np.sin(2 * math.pi * phi), z], axis=-1)
        total = float(ltc_density(m, w).mean() * 4 * math.pi)
        check("D integrates to 1 (M #%d)" % i, abs(total - 1) < 2e-3, "%.6f" % total)
        # ... and the closed-form upper-hemisphere mass agrees with the same grid
        up = float(np.where(w[:, 2] > 0, ltc_density(m, w), 0).mean() * 4 * math.pi)
        check("upper mass closed form (M #%d)" % i, abs(up - ltc_upper_mass(m)) < 2e-3,
              "%.6f vs %.6f" % (up, ltc_upper_mass(m)))
    # 2. The identity LTC over a parallel rectangle equals the closed-form view factor; a sheared
    #    M moves the same integral (D of M over M P equals the cosine over P).
    for a, b, c in ((1.0, 2.0, 1.0), (0.3, 0.5, 2.0), (4.0, 0.7, 0.5)):
        quad = np.array([[0, 0, c], [a, 0, c], [a, b, c], [0, b, c]], dtype=float)
        got = ltc_polygon_integral(np.eye(3), quad)
        want = rect_form_factor_parallel(a, b, c)
        check("identity LTC over a %gx%g rectangle at %g" % (a, b, c), abs(got - want) < 1e-12,
              "%.12f vs %.12f" % (got, want))
        m = random_ltc(rng)
        got = ltc_polygon_integral(m, quad @ m.T)
        check("LTC of M over M P = cosine over P", abs(got - want) < 1e-12, "%.12f" % got)
    # 3. Horizon clipping, and the Jacobian through the polygon: the polygon integral of D for
    #    random M and quads straddling the horizon against brute-force quadrature of D itself.
    for i in range(4):
        m = random_ltc(rng)
        corner = np.array([rng.uniform(-1, 0), rng.uniform(-1, 0), rng.uniform(-0.6, -0.1)])
        e1 = np.array([rng.uniform(0.8, 1.6), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)])
        e2 = np.array([rng.uniform(-0.2, 0.2), rng.uniform(0.8, 1.6), 0.0]) + np.array([0, 0, rng.uniform(0.5, 1.5)])
        quad = np.array([corner, corner + e1, corner + e1 + e2, corner + e2])
        got = ltc_polygon_integral(m, quad)
        brute_n = quad_integral(corner, e1, e2, lambda w: np.where(w[:, 2] > 0, ltc_density(m, w), 0.0), 64)
        # D below the horizon of the shading point stays in the brute force: compare against the
        # polygon clipped in the transformed domain only, as HDHN16 do.
        brute = quad_integral(corner, e1, e2, lambda w: ltc_density(m, w), 64)
        check("polygon integral vs brute force (quad #%d)" % i, abs(got - brute) < 1e-5,
              "%.7f vs %.7f (upper part only: %.7f)" % (got, brute, brute_n))
    # 4. The L1 distance: 0 for p with itself; 2 for disjoint lobes; the VNDF/MIS estimate agrees
    #    with a plain solid-angle grid for a smooth lobe.
    zero = l1_densities(lambda w: np.maximum(w[:, 2], 0) / math.pi, lambda w: np.maximum(w[:, 2], 0) / math.pi)
    check("L1(p, p) = 0", zero == 0.0, "%g" % zero)
    cap1 = lambda w: np.where(w[:, 0] > 0.5, 1.0, 0.0)  # noqa: E731
    cap2 = lambda w: np.where(w[:, 0] < -0.5, 1.0, 0.0)  # noqa: E731
    area = 2 * math.pi * 0.5 / 2  # the cap x > 0.5 on the upper hemisphere: half of 2 pi (1 - 0.5)
    two = l1_densities(lambda w: cap1(w) / area, lambda w: cap2(w) / area, 1000)
    check("L1 of disjoint lobes = 2", abs(two - 2) < 5e-3, "%.5f" % two)
    mu, alpha = 0.6, 0.7
    m = matrix_from_channels(0.9, 0.1, 0.95, -0.15, 1.0)
    d_mis, err, e = l1_distance_converged(mu, alpha, m, 256)
    wo = view(mu)
    d_grid = l1_densities(lambda w: ggx_fcos(wo, w, alpha) / e, lambda w: ltc_density(m, w), 1500)
    check("L1 by VNDF/MIS = L1 on a solid-angle grid", abs(d_mis - d_grid) < 2e-3 + err,
          "%.6f vs %.6f (MIS error %.1e)" % (d_mis, d_grid, err))
    # 5. GGX: E at normal incidence for alpha -> small is 1 (no energy loss of a mirror); the
    #    lobe integrated on a plain grid matches the VNDF estimate at a rough texel.
    e_small = lobe_terms(1.0, 1e-4, 128)[0]
    check("E(mu=1, alpha=1e-4) = 1", abs(e_small - 1) < 1e-6, "%.9f" % e_small)
    e_vndf = lobe_terms(0.5, 0.8, 512)[0]
    e_grid = l1_densities(lambda w: ggx_fcos(view(0.5), w, 0.8), lambda w: 0 * w[:, 0], 1500)
    check("E by VNDF = E on a grid (mu 0.5, alpha 0.8)", abs(e_vndf - e_grid) < 1e-4, "%.6f vs %.6f" % (e_vndf, e_grid))
    # 6. The fitted-lobe distance of a near-mirror lobe against itself as an LTC (M = the
    #    mirror-aligned scaling) is small and converged at alpha = 1e-4: the quadrature resolves it.
    a = 1e-4
    th = math.acos(0.8)
    rot = np.array([[math.cos(th), 0, -math.sin(th)], [0, 1, 0], [math.sin(th), 0, math.cos(th)]])
    m = rot @ np.diag([a, a, 1.0])
    d, err, _ = l1_distance_converged(0.8, a, m, 128)
    check("L1 converged at alpha 1e-4", err < 1e-3 and 0 <= d < 1.0, "%.5f +- %.1e" % (d, err))
    # 7. The batched quadratures (the 64 x 64 comparison) are the per-texel ones, texel by texel.
    mus, alphas = np.array([0.9, 0.35, 0.05]), np.array([0.3, 0.05, 0.6])
    mats = np.array([[random_ltc(rng) for _ in mus] for _ in range(2)])
    e_b = lobe_albedo_batch(mus, alphas, 64)
    d_b = l1_distance_batch(mus, alphas, mats, 32, e_b)
    for i in range(len(mus)):
        e_s = lobe_terms(mus[i], alphas[i], 64)[0]
        d_s = [l1_distance(mus[i], alphas[i], mats[k, i], 32, e_s)[0] for k in range(2)]
        check("batched = per-texel (texel #%d)" % i,
              abs(e_b[i] - e_s) < 1e-12 and max(abs(d_b[k, i] - d_s[k]) for k in range(2)) < 1e-12,
              "E %.12f vs %.12f, L1 %.9f vs %.9f" % (e_b[i], e_s, d_b[0, i], d_s[0]))
    return failures



# ------------------------------------------- the isotropic models without alpha (issue 33 item 1)
# Closed forms written from the papers, not from brdfbake's headers:
#   [ON94]  Oren, Nayar 1994, "Generalization of Lambert's Reflectance Model", eq. 30 (the
#           qualitative model), in angles: f = rho/pi (A + B max(0, cos(phi_i - phi_o)) sin a tan b).
#   [L94]   Lewis 1994, "Making Shaders More Physically Plausible": the reciprocal Phong lobe
#           ks max(0, R(wo).wi)^n, normalised by (n + 2)/(2 pi).
#   [B77]   Blinn 1977: the half-vector lobe ks (n.h)^n, its normalisation (n + 2)/(2 pi) [WMLT07 eq. 30].
# A table's alpha sets the key (docs/ltc_presets.md, "Models without alpha"): oren-nayar's
# sigma = alpha (radians), the Phong lobes' n = 2/alpha^2 - 2 [WMLT07 sec. 5.2].


def model_key_of_alpha(model, alpha):
    """the key value a table's alpha stands for: sigma = alpha, or n = 2/alpha^2 - 2."""
    return alpha if model == "oren-nayar" else max(0.0, 2.0 / (alpha * alpha) - 2.0)


def oren_nayar_fcos(wo, wi, sigma, rho=1.0):
    """f cos theta_i of [ON94] eq. 30 written with the angles themselves (theta, phi by arctan2)."""
    wo = np.broadcast_to(wo, wi.shape)
    ti = np.arccos(np.clip(wi[..., 2], -1.0, 1.0))
    to = np.arccos(np.clip(wo[..., 2], -1.0, 1.0))
    dphi = np.arctan2(wi[..., 1], wi[..., 0]) - np.arctan2(wo[..., 1], wo[..., 0])
    s2 = sigma * sigma
    a = 1.0 - 0.5 * s2 / (s2 + 0.33)
    b = 0.45 * s2 / (s2 + 0.09)
    big, small = np.maximum(ti, to), np.minimum(ti, to)
    ok = (wo[..., 2] > 0) & (wi[..., 2] > 0)
    f = rho / math.pi * (a + b * np.maximum(0.0, np.cos(dphi)) * np.sin(big) * np.tan(np.where(ok, small, 0.0)))
    return np.where(ok, f * wi[..., 2], 0.0)


def phong_fcos(wo, wi, n, ks=1.0, normalized=True):
    """f cos theta_i of [L94]'s reciprocal Phong lobe, R(wo) the mirror direction of wo."""
    r = np.array([-wo[0], -wo[1], wo[2]])
    k = ks * ((n + 2.0) / (2.0 * math.pi) if normalized else 1.0)
    c = np.maximum(wi @ r, 0.0)
    ok = (wo[2] > 0) & (wi[..., 2] > 0)
    return np.where(ok, k * c ** n * wi[..., 2], 0.0)


def blinn_phong_fcos(wo, wi, n, ks=1.0, normalized=True):
    """f cos theta_i of [B77]'s half-vector lobe ks (n.h)^n, normalised by (n + 2)/(2 pi)."""
    h = wo + wi
    h = h / np.maximum(np.linalg.norm(h, axis=-1, keepdims=True), 1e-300)
    k = ks * ((n + 2.0) / (2.0 * math.pi) if normalized else 1.0)
    ok = (wo[2] > 0) & (wi[..., 2] > 0) & (h[..., 2] > 0)
    return np.where(ok, k * np.maximum(h[..., 2], 0.0) ** n * wi[..., 2], 0.0)


def _frame_around(axis, local):
    """local directions (z = axis) turned into the world frame of a unit axis."""
    t = np.cross([0.0, 1.0, 0.0], axis) if abs(axis[1]) < 0.99 else np.cross([1.0, 0.0, 0.0], axis)
    t /= np.linalg.norm(t)
    b = np.cross(axis, t)
    return local[..., :1] * t + local[..., 1:2] * b + local[..., 2:] * axis


def _cos_power(n, u1, u2):
    """directions about +z with density (n + 1)/(2 pi) cos^n, and that density."""
    z = (1.0 - u1) ** (1.0 / (n + 1.0))
    s = np.sqrt(np.maximum(1.0 - z * z, 0.0))
    phi = 2.0 * math.pi * u2
    return np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=-1), (n + 1.0) / (2.0 * math.pi) * z ** n


class ModelLobe:
    """one texel's lobe of oren-nayar, phong or blinn-phong (keys as the table's `model` line), with
    a sampler for the quadratures: the cosine ([ON94]), cos^n about the mirror direction ([L94]) or
    cos^n half vectors reflected about wo ([B77]); `pdf(w)` the sampler's density of w."""

    def __init__(self, model, mu, alpha, ks=1.0, normalized=True, rho=1.0):
        self.model, self.wo = model, view(mu)
        self.k = model_key_of_alpha(model, alpha)
        self.ks, self.normalized, self.rho = ks, normalized, rho

    def fcos(self, w):
        if self.model == "oren-nayar":
            return oren_nayar_fcos(self.wo, w, self.k, self.rho)
        if self.model == "phong":
            return phong_fcos(self.wo, w, self.k, self.ks, self.normalized)
        return blinn_phong_fcos(self.wo, w, self.k, self.ks, self.normalized)

    def sample(self, u1, u2):
        wo = self.wo
        if self.model == "oren-nayar":
            return ltc_sample(np.eye(3), u1, u2)
        local, _ = _cos_power(self.k, u1, u2)
        if self.model == "phong":
            return _frame_around(np.array([-wo[0], -wo[1], wo[2]]), local)
        return 2.0 * (local @ wo)[..., None] * local - wo

    def pdf(self, w):
        wo = self.wo
        if self.model == "oren-nayar":
            return np.maximum(w[..., 2], 0.0) / math.pi
        if self.model == "phong":
            c = np.maximum(w @ np.array([-wo[0], -wo[1], wo[2]]), 0.0)
            return (self.k + 1.0) / (2.0 * math.pi) * c ** self.k
        h = wo + w
        h = h / np.maximum(np.linalg.norm(h, axis=-1, keepdims=True), 1e-300)
        c = np.maximum(h[..., 2], 0.0)
        return np.where(h @ wo > 0, (self.k + 1.0) / (2.0 * math.pi) * c ** self.k / (4.0 * np.maximum(h @ wo, 1e-300)), 0.0)


def model_albedo(lobe, n=512):
    """E = integral of f cos by the lobe's sampler on the graded n x n midpoint rule, with its error
    |E(n) - E(n/2)|."""
    def at(k):
        u1, u2, qw = graded_grid(k)
        w = lobe.sample(u1, u2)
        q = lobe.pdf(w)
        g = np.where((w[:, 2] > 0) & (q > 0), lobe.fcos(w) / np.where(q > 0, q, 1.0), 0.0)
        return float(np.sum(g * qw))
    fine = at(n)
    return fine, abs(fine - at(n // 2))


def model_l1_distance(lobe, m, e, n=256):
    """integral over the upper hemisphere of |p - D|, p = f cos / E, as l1_distance writes it
    (c - 1 + 2 integral of max(p - D, 0)) with the balance heuristic over the lobe's sampler and
    the LTC's; returns (distance, |L(n) - L(n/2)|)."""
    def at(k):
        total = 0.0
        for sampler in ("lobe", "ltc"):
            u1, u2, qw = graded_grid(k)
            w = lobe.sample(u1, u2) if sampler == "lobe" else ltc_sample(m, u1, u2)
            up = w[:, 2] > 0
            w = np.where(up[:, None], w, np.array([0.0, 0.0, 1.0]))
            p = lobe.fcos(w) / e
            d = ltc_density(m, w)
            q = lobe.pdf(w)
            g = np.where(up, np.maximum(p - d, 0.0) / np.maximum(q + d, 1e-300), 0.0)
            total += float(np.sum(g * qw))
        return ltc_upper_mass(m) - 1.0 + 2.0 * total
    fine = at(n)
    return fine, abs(fine - at(n // 2))


def model_spec_keys(canonical):
    """(name, {key: value}) of a canonical spec such as `phong:ks=1,normalized=0`."""
    name, _, rest = canonical.partition(":")
    return name, dict(kv.split("=") for kv in rest.split(",") if kv)


def check_model_table(path, verbose=True):
    """`brdfbake lut ltc --model oren-nayar|phong|blinn-phong` CSV against the closed forms above:
    per texel the magnitude within the file's error plus the reference's (and 1e-4), the fresnel
    channel equal to it (no Fresnel term), and the distance of the stored M recomputed here within
    the file's distance_error plus the reference's quadrature error (and 2e-3). Returns the
    failures (empty: all agree)."""
    rows, attributes = [], {}
    header = None
    for line in open(path):
        if line.startswith("#"):
            key, _, value = line[1:].partition(":")
            attributes[key.strip()] = value.strip()
        elif header is None:
            header = line.strip().split(",")
        else:
            rows.append(dict(zip(header, map(float, line.strip().split(",")))))
    name, keys = model_spec_keys(attributes["model"])
    failures = []
    check = _checker(verbose, failures)
    for r in rows:
        lobe = ModelLobe(name, r["mu"], r["alpha"], float(keys.get("ks", 1)), keys.get("normalized", "1") == "1",
                         float(keys.get("rho", 1)))
        e, e_err = model_albedo(lobe)
        m = matrix_from_channels(r["m00"], r["m02"], r["m11"], r["m20"], r["m22"])
        d, d_err = model_l1_distance(lobe, m, e)
        ok_e = abs(r["magnitude"] - e) <= r["error"] + e_err + 1e-4
        ok_f = r["fresnel"] == r["magnitude"]
        ok_d = abs(r["distance"] - d) <= r["distance_error"] + d_err + 2e-3
        check("%s mu %.4f alpha %.4f" % (name, r["mu"], r["alpha"]), ok_e and ok_f and ok_d,
              "E %.6f vs %.6f (+-%.1e), distance %.5f vs %.5f (+-%.1e, %.1e)" % (
                  r["magnitude"], e, e_err, r["distance"], d, r["distance_error"], d_err))
    return failures


def _checker(verbose, failures):
    """check(name, ok, detail): prints `ok`/`FAIL` lines when verbose, appends failed names."""
    def check(name, ok, detail):
        if verbose:
            print(("ok   " if ok else "FAIL ") + name + ": " + detail)
        if not ok:
            failures.append(name)
    return check


def model_self_checks(verbose=True):
    """the closed forms above against known values: Oren-Nayar at sigma = 0 is Lambert (E = 1);
    the normalised Phong lobe at normal incidence integrates to 1 ([L94]); the sampler-based E
    and L1 agree with a plain solid-angle grid for a smooth lobe of each model."""
    failures = []
    check = _checker(verbose, failures)
    for mu in (0.2, 0.7, 1.0):
        e = model_albedo(ModelLobe("oren-nayar", mu, 0.0))[0]
        check("oren-nayar sigma 0 is Lambert (mu %g)" % mu, abs(e - 1) < 1e-9, "%.12f" % e)
    e = model_albedo(ModelLobe("phong", 1.0, 0.3))[0]
    check("normalised phong at normal incidence", abs(e - 1) < 1e-6, "%.9f" % e)
    m = matrix_from_channels(0.8, 0.1, 0.85, -0.2, 1.0)
    for name, alpha in (("oren-nayar", 0.9), ("phong", 0.6), ("blinn-phong", 0.6)):
        lobe = ModelLobe(name, 0.5, alpha)
        e = model_albedo(lobe)[0]
        e_grid = l1_densities(lobe.fcos, lambda w: 0 * w[:, 0], 800)
        check("%s E by its sampler = E on a grid" % name, abs(e - e_grid) < 2e-4, "%.6f vs %.6f" % (e, e_grid))
        d = model_l1_distance(lobe, m, e)[0]
        d_grid = l1_densities(lambda w: lobe.fcos(w) / e, lambda w: ltc_density(m, w), 800)
        check("%s L1 by MIS = L1 on a grid" % name, abs(d - d_grid) < 2e-3, "%.5f vs %.5f" % (d, d_grid))
    return failures


if __name__ == "__main__":
    if "--check" in sys.argv:
        bad = self_checks()
        print("%d failure(s)" % len(bad))
        sys.exit(1 if bad else 0)
    print(__doc__)
