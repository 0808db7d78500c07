#!/usr/bin/python3
"""Brute-force finite-difference reference for the steady 3D lid-driven cubic cavity.

Unit cube [0,1]^3, lid y = 1 moving with u = (1,0,0), other faces no-slip at rest, Re = 1/nu.
Staggered (MAC) grid, second-order central differences (conservative advection), explicit
Adams-Bashforth 2 for advection + diffusion, exact projection (Neumann Poisson solved by
diagonalising the 1D cell-centred Neumann Laplacian along each axis). Marched in time to steady
state; the steady state of this scheme is exactly the steady discrete Navier-Stokes solution
(nothing dt-dependent survives when u^{n+1} = u^n).

usage:
  run:      cavity3d_reference.py --n 64 --re 400 --out re400_n64.csv [--ref albensoeder.csv]
  compare:  cavity3d_reference.py --compare a_n32.csv b_n48.csv c_n64.csv   (grid convergence)
  merge:    cavity3d_reference.py --merge Re100=f.csv Re400=g.csv --out PREFIX
            (a file list "c.csv,f.csv" instead of one file gives Richardson extrapolation, p = 2;
            writes the case's tables PREFIX_u_vertical_centreline.csv, PREFIX_v_horizontal_centreline.csv)

Reference tables (--ref PREFIX, and what --merge writes) are the case's own format: a '#' comment
line, then y,u_Re<re>,... in PREFIX_u_vertical_centreline.csv and x,v_Re<re>,... in
PREFIX_v_horizontal_centreline.csv (cases/lid_driven_cavity/data/).

Per-run CSV columns: profile,coordinate,value,n,re,t,residual. profile 'u' is u(0.5, y, 0.5)
(coordinate = y), 'v' is v(x, 0.5, 0.5) (coordinate = x); values per unit lid speed.
"""
import argparse
import csv
import math
import sys
import time

import numpy as np

# Points of the 19-point table (k/20) and of the Albensoeder & Kuhlmann (2005) Re 1000 table
# mapped to our coordinates (these coincide with Ghia et al.'s 2D points).
TABLE_PTS = np.arange(1, 20) / 20.0
AK_Y = np.array([0.0547, 0.0625, 0.0703, 0.1016, 0.1719, 0.2813, 0.4531, 0.5, 0.6172, 0.7344,
                 0.8516, 0.9531, 0.9609, 0.9688, 0.9766])
AK_X = np.array([0.0625, 0.0703, 0.0781, 0.0938, 0.1563, 0.2266, 0.2344, 0.5, 0.8047, 0.8594,
                 0.9063, 0.9453, 0.9531, 0.9609, 0.9688])


def sl(ax, s, nd=3):
    """Index tuple applying slice s along axis ax only."""
    idx = [slice(None)] * nd
    idx[ax] = s
    return tuple(idx)


class Cavity:
    def __init__(self, n, re):
        if n % 2:
            sys.exit("--n must be even (the centreline planes are then grid planes)")
        self.n, self.h, self.nu = n, 1.0 / n, 1.0 / re
        # vel[c] is the velocity component along axis c; it lives on the faces normal to c:
        # shape n+1 along c (the two wall faces carry 0 = no penetration), n along the others.
        self.vel = [np.zeros(tuple(n + 1 if a == c else n for a in range(3))) for c in range(3)]
        # Tangential wall velocity of component c on the low/high wall normal to axis a.
        # Only the lid (high y wall, a = 1) moves, with u (c = 0) = 1.
        self.wall = {(c, a): (0.0, 1.0 if (c == 0 and a == 1) else 0.0)
                     for c in range(3) for a in range(3) if a != c}
        # Pressure: 1D cell-centred Laplacian with homogeneous Neumann ends, A = Q diag(lam) Q^T.
        A = (np.diag(-2.0 * np.ones(n)) + np.diag(np.ones(n - 1), 1) + np.diag(np.ones(n - 1), -1))
        A[0, 0] = A[-1, -1] = -1.0
        lam, self.Q = np.linalg.eigh(A / self.h**2)
        self.Qt = np.ascontiguousarray(self.Q.T)  # contiguous copy: tensordot is ~5x slower on a view
        lam[np.abs(lam) < 1e-9 / self.h**2] = 0.0  # the constant mode (round-off only)
        L = lam[:, None, None] + lam[None, :, None] + lam[None, None, :]
        with np.errstate(divide="ignore"):
            self.inv_L = np.where(L == 0.0, 0.0, 1.0 / L)  # zero mode dropped: p defined up to a constant
        self.t, self.rhs_old = 0.0, None

    def padded(self, c, q=None):
        """Component c with one ghost layer on each transverse wall (linear extrapolation through
        the wall value: ghost = 2*wall - interior), so central differences see the wall velocity."""
        q = self.vel[c] if q is None else q
        for a in range(3):
            if a == c:
                continue
            lo, hi = self.wall[(c, a)]
            g_lo = 2.0 * lo - q[sl(a, slice(0, 1))]
            g_hi = 2.0 * hi - q[sl(a, slice(-1, None))]
            q = np.concatenate([g_lo, q, g_hi], axis=a)
        return q

    def init_from(self, path):
        """Start from a saved field (--save) of any grid: trilinear interpolation of each staggered
        component (ghosts included, so walls are respected), then a projection. Only shortens the
        transient; the steady state reached does not depend on it."""
        data = np.load(path)
        for c, name in enumerate("uvw"):
            q = data[name]
            nc = q.shape[(c + 1) % 3]                      # coarse cells per side
            q = self.padded(c, q)
            for a in range(3):
                if a == c:
                    xo, xn = np.linspace(0, 1, nc + 1), np.linspace(0, 1, self.n + 1)
                else:
                    xo, xn = (np.arange(-1, nc + 1) + 0.5) / nc, (np.arange(self.n) + 0.5) * self.h
                i = np.clip(np.searchsorted(xo, xn) - 1, 0, len(xo) - 2)
                wgt = ((xn - xo[i]) / (xo[i + 1] - xo[i])).reshape([-1 if b == a else 1 for b in range(3)])
                q = np.take(q, i, axis=a) * (1 - wgt) + np.take(q, i + 1, axis=a) * wgt
            # The ghost layers hold 2*wall - q, which on the wall faces of c (q = 0) is 2 at the
            # lid: interpolation along y leaks it onto those faces. They must stay exactly 0
            # (no penetration; the time step never updates them), so reset them.
            q[sl(c, 0)] = 0.0
            q[sl(c, -1)] = 0.0
            self.vel[c][...] = q
        self.project(1.0)
        print(f"initialised from {path} (N={nc}), max|div| {np.abs(self.divergence()).max():.1e}")

    def rhs(self):
        """-div(u u_c) + nu lap(u_c) at the interior faces of every component c (0 on wall faces)."""
        h, out = self.h, []
        for c in range(3):
            q, P = self.vel[c], self.padded(c)
            inner = sl(c, slice(1, -1))          # interior faces along c
            r = np.zeros_like(q)
            # d(q q)/dc: q averaged to cell centres, squared, differenced back onto faces.
            qc = 0.5 * (q[sl(c, slice(1, None))] + q[sl(c, slice(None, -1))])
            qq = qc * qc
            conv = (qq[sl(c, slice(1, None))] - qq[sl(c, slice(None, -1))]) / h
            lap = (q[sl(c, slice(2, None))] - 2.0 * q[inner] + q[sl(c, slice(None, -2))]) / h**2
            for d in range(3):
                if d == c:
                    continue
                e = 3 - c - d                   # the third axis
                # Edge flux q*vel_d at (c-face, d-face): q averaged along d (ghosts give the wall
                # value at the wall), vel_d averaged along c; strip ghosts along e.
                Pe = P[sl(e, slice(1, -1))]
                q_d = 0.5 * (Pe[sl(d, slice(1, None))] + Pe[sl(d, slice(None, -1))])[inner]
                vd = self.vel[d]
                vd_c = 0.5 * (vd[sl(c, slice(1, None))] + vd[sl(c, slice(None, -1))])
                f = q_d * vd_c
                conv = conv + (f[sl(d, slice(1, None))] - f[sl(d, slice(None, -1))]) / h
                # Second difference along d on the padded field.
                Pi = Pe[inner]
                lap = lap + (Pi[sl(d, slice(2, None))] - 2.0 * Pi[sl(d, slice(1, -1))]
                             + Pi[sl(d, slice(None, -2))]) / h**2
            r[inner] = -conv + self.nu * lap
            out.append(r)
        return out

    def divergence(self):
        h = self.h
        return sum((q[sl(c, slice(1, None))] - q[sl(c, slice(None, -1))]) / h
                   for c, q in enumerate(self.vel))

    def poisson(self, f):
        """Solve lap(phi) = f with homogeneous Neumann walls: transform to eigenmodes along each
        axis (tensordot on axis 0 appends the new axis last, so three passes restore the order),
        divide by the eigenvalue sum, transform back."""
        for _ in range(3):
            f = np.tensordot(f, self.Q, axes=(0, 0))   # f_hat = Q^T f along axis 0
        f *= self.inv_L
        for _ in range(3):
            f = np.tensordot(f, self.Qt, axes=(0, 0))  # f = Q f_hat along axis 0
        return f

    def project(self, dt):
        # Wall-face normal velocities are fixed at 0, so div(grad) over interior faces is exactly
        # the Neumann Laplacian diagonalised above: the projected field is divergence-free to round-off.
        phi = self.poisson(self.divergence() / dt)
        for c, q in enumerate(self.vel):
            q[sl(c, slice(1, -1))] -= dt * (phi[sl(c, slice(1, None))] - phi[sl(c, slice(None, -1))]) / self.h

    def step(self, dt):
        """One AB2 step (Euler on the first) followed by the projection; returns max|du|/dt."""
        r = self.rhs()
        if self.rhs_old is None:
            inc = [dt * a for a in r]
        else:
            inc = [dt * (1.5 * a - 0.5 * b) for a, b in zip(r, self.rhs_old)]
        self.rhs_old = r
        old = [q.copy() for q in self.vel]
        for q, d in zip(self.vel, inc):
            q += d
        self.project(dt)
        self.t += dt
        return max(np.abs(q - o).max() for q, o in zip(self.vel, old)) / dt

    # ----- centreline profiles -------------------------------------------------------------
    def _mid(self, a, axis):
        """Value at the mid-plane (coordinate 0.5) along a cell-centred axis: 4-point, 4th-order
        symmetric interpolation (-1, 9, 9, -1)/16 of the four centres around it."""
        m = self.n // 2
        s = lambda k: a[sl(axis, m + k, a.ndim)]
        return (-s(-2) + 9.0 * s(-1) + 9.0 * s(0) - s(1)) / 16.0

    def profiles(self, pts_u, pts_v):
        """u(0.5, y, 0.5) at y = pts_u and v(x, 0.5, 0.5) at x = pts_v. u lives on the x = 0.5 face
        plane, cell-centred in y and z; v on the y = 0.5 plane, cell-centred in x and z. Interpolate
        to z = 0.5 (4th order), then along the line through the cell centres plus the wall values
        with cubic Lagrange interpolation."""
        m, h = self.n // 2, self.h
        centres = (np.arange(self.n) + 0.5) * h
        u_line = self._mid(self.vel[0][m], axis=1)            # u[m, :, :] -> function of y
        v_line = self._mid(self.vel[1][:, m, :], axis=1)      # v[:, m, :] -> function of x
        xs = np.concatenate([[0.0], centres, [1.0]])
        u_line = np.concatenate([[0.0], u_line, [1.0]])       # bottom wall at rest, lid u = 1
        v_line = np.concatenate([[0.0], v_line, [0.0]])
        return lagrange(xs, u_line, pts_u), lagrange(xs, v_line, pts_v)


def lagrange(xs, ys, pts, k=4):
    """Piecewise cubic Lagrange interpolation using the k nodes nearest each target point."""
    out = np.empty(len(pts))
    for i, p in enumerate(pts):
        j = int(np.clip(np.searchsorted(xs, p) - k // 2, 0, len(xs) - k))
        x, y = xs[j:j + k], ys[j:j + k]
        w = [np.prod([(p - x[b]) / (x[a] - x[b]) for b in range(k) if b != a]) for a in range(k)]
        out[i] = np.dot(w, y)
    return out


# ----- CSV helpers -------------------------------------------------------------------------
def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def profile_dict(path, table_only=False):
    """{(profile, coordinate): value} from a per-run or reference CSV."""
    d = {}
    for r in read_rows(path):
        key = (r["profile"], round(float(r["coordinate"]), 4))
        if table_only and not np.any(np.isclose(key[1], TABLE_PTS)):
            continue
        d[key] = float(r["value"])
    return d


def diff_stats(a, b, keys):
    e = np.array([a[k] - b[k] for k in keys])
    return math.sqrt(np.mean(e**2)), np.abs(e).max()


def read_reference(prefix, re):
    """{(profile, coordinate): value} from the case's two tables PREFIX_{u_vertical,v_horizontal}_centreline.csv."""
    d = {}
    for prof, coord, name in (("u", "y", "u_vertical"), ("v", "x", "v_horizontal")):
        with open(f"{prefix}_{name}_centreline.csv") as f:
            for r in csv.DictReader(line for line in f if not line.startswith("#")):
                d[(prof, round(float(r[coord]), 4))] = float(r[f"{prof}_Re{re:g}"])
    return d


def compare(ref_prefix, re, run):
    """RMS / max difference of run (dict) against a reference table over its interior points."""
    ref = read_reference(ref_prefix, re)
    msg = []
    for prof in ("u", "v", None):
        keys = [k for k in ref if 0.0 < k[1] < 1.0 and (prof is None or k[0] == prof)]
        keys = [k for k in keys if k in run]
        rms, mx = diff_stats(run, ref, keys)
        msg.append(f"{prof or 'all'}: rms {rms:.5f} max {mx:.5f} ({len(keys)} pts)")
    return "; ".join(msg)


def run_main(args):
    cav = Cavity(args.n, args.re)
    h = cav.h
    if args.init:
        cav.init_from(args.init)
    # Stability of explicit AB2: diffusion needs dt*nu*12/h^2 <= 1 (AB2 reaches -1 on the real
    # axis; 12/h^2 bounds the 3D Laplacian), advection a CFL below ~0.5 for central differences.
    dt = args.dt or min(args.cfl * h, 0.8 * h * h / (12.0 * cav.nu))
    print(f"N={args.n} Re={args.re} dt={dt:.3e} tol={args.tol} t_end={args.t_end}", flush=True)
    t0, res, it = time.time(), np.inf, 0
    while cav.t < args.t_end - 1e-12:
        res = cav.step(dt)
        it += 1
        if not np.isfinite(res):
            sys.exit(f"diverged at t={cav.t:.3f}; lower --cfl or --dt")
        done = res < args.tol
        if it % args.print_every == 0 or done or cav.t >= args.t_end - 1e-12:
            div = cav.divergence()
            print(f"step {it:6d} t={cav.t:8.3f} res={res:.3e} |div|max={np.abs(div).max():.2e} "
                  f"|div|rms={math.sqrt(np.mean(div**2)):.2e} wall={time.time() - t0:.0f}s", flush=True)
        if done:
            break
    status = "converged" if res < args.tol else "NOT converged (t_end reached)"
    print(f"{status}: t={cav.t:.3f} steps={it} residual={res:.3e} wall={time.time() - t0:.0f}s")
    pts_u = np.unique(np.round(np.concatenate([TABLE_PTS, AK_Y]), 4))
    pts_v = np.unique(np.round(np.concatenate([TABLE_PTS, AK_X]), 4))
    pu, pv = cav.profiles(pts_u, pts_v)
    if args.out:
        with open(args.out, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["profile", "coordinate", "value", "n", "re", "t", "residual"])
            for prof, pts, vals in (("u", pts_u, pu), ("v", pts_v, pv)):
                for p, val in zip(pts, vals):
                    w.writerow([prof, f"{p:.4f}", f"{val:.6f}", args.n, args.re, f"{cav.t:.3f}", f"{res:.3e}"])
        print(f"wrote {args.out}")
    run = {("u", round(p, 4)): val for p, val in zip(pts_u, pu)}
    run.update({("v", round(p, 4)): val for p, val in zip(pts_v, pv)})
    if args.ref:
        print(f"vs {args.ref}: {compare(args.ref, args.re, run)}")
    if args.save:
        np.savez(args.save, u=cav.vel[0], v=cav.vel[1], w=cav.vel[2], t=cav.t)


def compare_main(paths):
    """Grid-to-grid differences over the 19 table points; observed order from three grids."""
    runs = [profile_dict(p, table_only=True) for p in paths]
    ns = [int(read_rows(p)[0]["n"]) for p in paths]
    keys = sorted(runs[0])
    for i in range(len(runs) - 1):
        rms, mx = diff_stats(runs[i + 1], runs[i], keys)
        print(f"N={ns[i]} -> N={ns[i + 1]}: rms {rms:.5f} max {mx:.5f}")
    for i in range(len(runs) - 2):
        if len({ns[i], ns[i + 1], ns[i + 2]}) < 3:
            continue                      # same grid twice (e.g. two runs of one N): no order
        a, b, c = (np.array([r[k] for k in keys]) for r in runs[i:i + 3])
        d1, d2 = b - a, c - b
        # Uniform-ratio formula does not apply to 32/48/64 (ratios 1.5, 1.33): solve for p in
        # d1/d2 = (h1^p - h2^p)/(h2^p - h3^p) by bisection, per point, where the sign is monotone.
        h1, h2, h3 = (1.0 / ns[i + j] for j in range(3))
        g = lambda p, r: (h1**p - h2**p) / (h2**p - h3**p) - r
        orders = []
        for x, y in zip(d1, d2):
            if abs(y) < 1e-6 or x * y <= 0:
                continue
            lo, hi = 0.2, 8.0
            if g(lo, x / y) * g(hi, x / y) > 0:
                continue
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if g(lo, x / y) * g(mid, x / y) > 0 else (lo, mid)
            orders.append(0.5 * (lo + hi))
        mono = np.mean(d1 * d2 > 0)
        print(f"N={ns[i]},{ns[i + 1]},{ns[i + 2]}: monotone at {mono * 100:.0f}% of points; "
              f"observed order median {np.median(orders) if orders else float('nan'):.2f} "
              f"(quartiles {np.percentile(orders, 25) if orders else 0:.2f}..{np.percentile(orders, 75) if orders else 0:.2f}, "
              f"{len(orders)} pts); global p from rms: "
              f"{math.log(np.sqrt(np.mean(d1**2)) / np.sqrt(np.mean(d2**2))) / math.log(ns[i + 1] / ns[i]) :.2f} (naive)")


def merge_main(specs, out):
    """Write the 19-point table: profile,coordinate,<label>,... ; 'a.csv,b.csv' -> Richardson (p=2)."""
    cols, labels = [], []
    for spec in specs:
        label, files = spec.split("=", 1)
        files = files.split(",")
        d = [profile_dict(f, table_only=True) for f in files]
        if len(d) == 1:
            cols.append(d[0])
        else:
            n1, n2 = (int(read_rows(f)[0]["n"]) for f in files)
            r2 = (n2 / n1) ** 2
            cols.append({k: d[1][k] + (d[1][k] - d[0][k]) / (r2 - 1.0) for k in d[1]})
        labels.append(label)
    how = "Richardson-extrapolated (p = 2) from two grids" if any("," in s for s in specs) else "one grid"
    for prof, coord, name in (("u", "y", "u_vertical"), ("v", "x", "v_horizontal")):
        path = f"{out}_{name}_centreline.csv"
        line = "x = z = 0.5" if prof == "u" else "y = z = 0.5"
        with open(path, "w", newline="") as f:
            f.write(f"# Cubic cavity, finite-difference reference (scripts/cavity3d_reference.py, {how}; "
                    f"see README.md in this folder): {prof} along {line}, lid u = 1 at y = 1\n")
            w = csv.writer(f)
            w.writerow([coord] + [f"{prof}_{label}" for label in labels])
            for k in sorted(k for k in cols[0] if k[0] == prof):
                w.writerow([f"{k[1]:.2f}"] + [f"{c[k]:.5f}" for c in cols])
        print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--n", type=int, default=32, help="cells per side (even)")
    ap.add_argument("--re", type=float, default=100.0)
    ap.add_argument("--t-end", type=float, default=200.0)
    ap.add_argument("--tol", type=float, default=1e-5, help="stop when max|u^{n+1}-u^n|/dt < tol")
    ap.add_argument("--cfl", type=float, default=0.3, help="advective dt = cfl*h (lid speed 1)")
    ap.add_argument("--dt", type=float, default=None, help="override the time step")
    ap.add_argument("--print-every", type=int, default=500)
    ap.add_argument("--out", help="CSV of the centreline profiles (with --merge: the tables' PREFIX)")
    ap.add_argument("--ref", help="reference tables' PREFIX (e.g. .../data/albensoeder2005) to report RMS/max differences")
    ap.add_argument("--save", help="npz file for the final velocity field")
    ap.add_argument("--init", help="npz from --save (any N) to start from instead of rest")
    ap.add_argument("--compare", nargs="+", metavar="CSV", help="grid convergence of runs, coarse to fine")
    ap.add_argument("--merge", nargs="+", metavar="LABEL=CSV[,CSV]", help="merge runs into one table")
    args = ap.parse_args()
    if args.compare:
        compare_main(args.compare)
    elif args.merge:
        merge_main(args.merge, args.out)
    else:
        run_main(args)


if __name__ == "__main__":
    main()
