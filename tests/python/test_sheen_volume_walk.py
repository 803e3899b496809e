"""The volumetric sheen layer's albedo (`brdfbake albedo --model sheen-volume:roughness=R`, Zeltner, Burley and
Chiang 2022) against an independent numpy random walk of the same layer: a slab of unit optical thickness of
fiber-like specular SGGX microflakes (S = diag(1, 1, s^2), s = R^2, albedo 1; Heitz et al. 2015 eq. 8, 9, 13),
lit from the top. The numpy walk draws its visible normals in its own way, not by the program's ellipsoid
mapping: the normal's cosine from a tabulated inverse CDF of D's marginal on the sphere, its azimuth uniform,
then rejection with probability <v, m>+ (the visible-normal density <v, m>+ D(m) / sigma(v)); reflection about m.
R (top exits), T (bottom exits) and the first order R1 agree within the combined error (3 standard errors each);
T without scattering equals Beer-Lambert's exp(-sigma(wo) / mu).
Numpy and the executable only (BRDFBAKE_EXE); run by CTest's `python` test."""
import json
import os
import subprocess

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.environ.get("BRDFBAKE_EXE", os.path.join(ROOT, "build", "brdfbake"))


def normal_cosine_sampler(s):
    """Inverse CDF of m.z for normals distributed as D(m) on the sphere (dm = d(m.z) dphi): D depends on m.z
    only, D proportional to 1 / (1 - z^2 + z^2 / s^2)^2 [HDCD15 eq. 8]."""
    z = np.linspace(-1.0, 1.0, 200001)
    d = 1.0 / (1.0 - z * z + z * z / (s * s)) ** 2
    cdf = np.concatenate([[0.0], np.cumsum(0.5 * (d[1:] + d[:-1]) * np.diff(z))])
    cdf /= cdf[-1]
    return lambda u: np.interp(u, cdf, z)


def visible_normals(v, s, sample_z, rng):
    """One normal per row of v with density <v, m>+ D(m) / sigma(v), by rejection from D."""
    m = np.empty_like(v)
    todo = np.arange(len(v))
    while todo.size:
        z = sample_z(rng.random(todo.size))
        phi = 2 * np.pi * rng.random(todo.size)
        r = np.sqrt(np.maximum(0.0, 1 - z * z))
        c = np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)
        ok = rng.random(todo.size) < np.einsum("ij,ij->i", c, v[todo])
        m[todo[ok]] = c[ok]
        todo = todo[~ok]
    return m


def numpy_walk(mu, roughness, n, seed, bounces=1000):
    """R, T and R1 with 3 standard errors of the binomial shares, n walks from wo = (sqrt(1 - mu^2), 0, mu)."""
    rng = np.random.default_rng(seed)
    s = roughness * roughness
    sample_z = normal_cosine_sampler(s)
    w = np.tile([-np.sqrt(1 - mu * mu), 0.0, -mu], (n, 1))  # travelling into the layer
    t = np.zeros(n)  # depth: 0 at the top, 1 at the bottom
    scat = np.zeros(n, dtype=int)
    alive = np.ones(n, dtype=bool)
    top = np.zeros(n, dtype=bool)
    bottom = np.zeros(n, dtype=bool)
    for _ in range(bounces + 1):
        i = np.flatnonzero(alive)
        if i.size == 0:
            break
        sigma = np.sqrt(w[i, 0] ** 2 + w[i, 1] ** 2 + s * s * w[i, 2] ** 2)
        t[i] -= rng.exponential(size=i.size) / sigma * w[i, 2]
        out_top, out_bottom = t[i] < 0, t[i] > 1
        top[i[out_top]] = True
        bottom[i[out_bottom]] = True
        alive[i[out_top | out_bottom]] = False
        j = i[~(out_top | out_bottom)]
        v = -w[j]
        m = visible_normals(v, s, sample_z, rng)
        w[j] = 2 * np.einsum("ij,ij->i", v, m)[:, None] * m - v
        w[j] /= np.linalg.norm(w[j], axis=1)[:, None]
        scat[j] += 1

    def share(mask):
        p = mask.mean()
        return p, 3 * np.sqrt(p * (1 - p) / n)

    return share(top), share(bottom), share(top & (scat == 1))


def brdfbake_albedo(roughness, mus):
    out = subprocess.run([EXE, "albedo", "--model", f"sheen-volume:roughness={roughness}", "--mu",
                          ",".join(str(m) for m in mus), "--samples", str(1 << 18), "--format", "json"],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)["results"]


def test_sheen_volume_albedo_matches_an_independent_numpy_walk():
    checked = 0
    for roughness, mus in ((0.5, (0.25, 0.8)), (1.0, (0.5,))):
        results = brdfbake_albedo(roughness, mus)
        for k, (mu, res) in enumerate(zip(mus, results)):
            (r, r_err), (t, t_err), (r1, r1_err) = numpy_walk(mu, roughness, 40000, seed=17 + k)
            msg = f"roughness {roughness} mu {mu}: brdfbake R {res['albedo']} +- {res['error']}, numpy {r} +- {r_err}"
            assert abs(res["albedo"] - r) <= res["error"] + r_err, msg
            assert abs(res["reflected"] - r) <= res["reflected_error"] + r_err, msg
            assert abs(res["transmitted"] - t) <= res["transmitted_error"] + t_err, msg
            assert abs(res["single_scattering"] - r1) <= res["single_scattering_error"] + r1_err, msg
            # T without scattering: Beer-Lambert along the view, exp(-sigma(wo) / mu), sigma(w) = sqrt(w^T S w)
            s = roughness * roughness
            t0 = np.exp(-np.sqrt(1 - mu * mu + s * s * mu * mu) / mu)
            assert abs(res["unscattered_transmitted"] - t0) <= res["unscattered_transmitted_error"] + 1e-6, msg
            assert r_err < 0.15 * r, msg  # the comparison has teeth
            checked += 1
    assert checked == 3
