#!/usr/bin/python3
"""Finite-difference check of Ghia, Ghia & Shin (1982) for the 2D lid-driven cavity.

Unit square, lid y = 1 moving with u = 1, other walls no-slip, Re = 1/nu. Staggered (MAC) grid,
second-order central differences (conservative advection), Adams-Bashforth 2, exact projection
(the cell-centred Neumann Laplacian diagonalised along each axis), marched to the steady state of
the discrete equations (max |u^{n+1} - u^n| / dt < 1e-6). Prints the RMS and largest difference of
u(0.5, y) and v(x, 0.5) from Ghia's tables at their interior points, and v point by point: the SPH
cavity's errors are measured against Ghia, so this tells how much of them is the table's.

With --runs, the SPH runs' profiles at Ghia's points (each run folder's centreline_ghia.csv) are
compared with this solution as well as with Ghia's table: the SPH error without the table's own
(about 0.5 % of U in v at Re 100), for convergence studies in h; and each profile's strength s, the
least-squares fit sph ~ (1 + s) fd (s < 0: the vortex too weak), with the RMS left once it is scaled.

usage: cavity2d_reference.py --n 64 [--re 100] [--cfl 0.1] [--save|--load F.npz] [--runs RUN_DIR... [--averaged]]
       (--cfl 0.05 from
       n 128: AB2 and the lid corner are unstable at 0.1 there)
"""
import argparse
import os
import sys

import numpy as np

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases", "lid_driven_cavity", "data")


def steady_state(n, re, cfl):
    h, nu = 1.0 / n, 1.0 / re
    u, v = np.zeros((n + 1, n)), np.zeros((n, n + 1))  # u on vertical faces, v on horizontal ones
    lap1 = np.diag(-2.0 * np.ones(n)) + np.diag(np.ones(n - 1), 1) + np.diag(np.ones(n - 1), -1)
    lap1[0, 0] = lap1[-1, -1] = -1.0  # Neumann
    lam, q = np.linalg.eigh(lap1 / h**2)
    den = lam[:, None] + lam[None, :]
    den[np.abs(den) < 1e-9] = np.inf  # the constant mode

    def rhs(u, v):
        ug = np.zeros((n + 1, n + 2)); ug[:, 1:-1] = u; ug[:, 0] = -u[:, 0]; ug[:, -1] = 2.0 - u[:, -1]
        vg = np.zeros((n + 2, n + 1)); vg[1:-1, :] = v; vg[0, :] = -v[0, :]; vg[-1, :] = -v[-1, :]
        uv = 0.25 * (ug[:, 1:] + ug[:, :-1]) * (vg[1:, :] + vg[:-1, :])  # at the cell corners
        uc, vc = 0.5 * (u[1:, :] + u[:-1, :]), 0.5 * (v[:, 1:] + v[:, :-1])  # at the cell centres
        fu, fv = np.zeros_like(u), np.zeros_like(v)
        fu[1:-1, :] = (-(uc[1:, :]**2 - uc[:-1, :]**2) - (uv[1:-1, 1:] - uv[1:-1, :-1])) / h + nu * (
            ug[2:, 1:-1] + ug[:-2, 1:-1] + ug[1:-1, 2:] + ug[1:-1, :-2] - 4 * ug[1:-1, 1:-1]) / h**2
        fv[:, 1:-1] = (-(vc[:, 1:]**2 - vc[:, :-1]**2) - (uv[1:, 1:-1] - uv[:-1, 1:-1])) / h + nu * (
            vg[2:, 1:-1] + vg[:-2, 1:-1] + vg[1:-1, 2:] + vg[1:-1, :-2] - 4 * vg[1:-1, 1:-1]) / h**2
        return fu, fv

    dt, t, previous = min(0.15 * h * h / nu, cfl * h), 0.0, None
    while True:
        fu, fv = rhs(u, v)
        au, av = (fu, fv) if previous is None else (1.5 * fu - 0.5 * previous[0], 1.5 * fv - 0.5 * previous[1])
        previous = (fu, fv)
        us, vs = u + dt * au, v + dt * av
        div = (us[1:, :] - us[:-1, :] + vs[:, 1:] - vs[:, :-1]) / h
        phi = q @ ((q.T @ (div / dt) @ q) / den) @ q.T
        us[1:-1, :] -= dt * (phi[1:, :] - phi[:-1, :]) / h
        vs[:, 1:-1] -= dt * (phi[:, 1:] - phi[:, :-1]) / h
        change = max(np.abs(us - u).max(), np.abs(vs - v).max()) / dt
        u, v, t = us, vs, t + dt
        if not np.isfinite(change):
            sys.exit(f"blew up at t = {t:.3f}: try a smaller --cfl")
        if change < 1e-6 and t > 5.0:
            return u, v, t


def at(xs, ys, points):
    """Cubic Lagrange interpolation through the four nearest samples."""
    out = []
    for p in points:
        lo = max(0, min(len(xs) - 4, np.searchsorted(xs, p) - 2))
        x, y = xs[lo:lo + 4], ys[lo:lo + 4]
        out.append(sum(y[a] * np.prod([(p - x[b]) / (x[a] - x[b]) for b in range(4) if b != a]) for a in range(4)))
    return np.array(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=64, help="cells per side (even)")
    ap.add_argument("--re", type=int, default=100, choices=[100, 400, 1000])
    ap.add_argument("--cfl", type=float, default=0.1, help="advective dt = cfl h (lid speed 1)")
    ap.add_argument("--runs", nargs="*", default=[], metavar="RUN_DIR",
                    help="SPH cavity runs at the same Re: their RMS against this solution and against Ghia")
    ap.add_argument("--averaged", action="store_true",
                    help="compare the runs' time-averaged profiles (-profile_average_from) instead of their last ones")
    ap.add_argument("--save", metavar="FILE.npz", help="keep the steady solution in FILE.npz (n 128 at Re 1000 takes 25 minutes)")
    ap.add_argument("--load", metavar="FILE.npz", help="read a solution kept by --save instead of solving")
    a = ap.parse_args()
    if a.load:
        kept = np.load(a.load)
        if int(kept["n"]) != a.n or int(kept["re"]) != a.re:
            sys.exit(f"{a.load} holds n {int(kept['n'])} Re {int(kept['re'])}, not n {a.n} Re {a.re}: give the same --n and --re")
        u, v, t = kept["u"], kept["v"], float(kept["t"])
    else:
        u, v, t = steady_state(a.n, a.re, a.cfl)
    if a.save:
        np.savez(a.save, u=u, v=v, t=t, n=a.n, re=a.re)
    centres = np.concatenate([[0.0], (np.arange(a.n) + 0.5) / a.n, [1.0]])
    u_line = np.concatenate([[0.0], u[a.n // 2, :], [1.0]])  # u(0.5, y) with the wall values
    v_line = np.concatenate([[0.0], v[:, a.n // 2], [0.0]])  # v(x, 0.5)
    column = {100: 1, 400: 2, 1000: 3}[a.re]
    for name, line in (("u", u_line), ("v", v_line)):
        path = os.path.join(DATA, "ghia1982_u_vertical_centreline.csv" if name == "u" else "ghia1982_v_horizontal_centreline.csv")
        table = np.array([[float(c) for c in line.split(",")] for line in open(path) if line[0].isdigit()])
        inner = (table[:, 0] > 0) & (table[:, 0] < 1)
        if name == "v" and a.re == 400:
            inner &= table[:, 0] != 0.9063  # the misprint the table's header names
        diff = at(centres, line, table[inner, 0]) - table[inner, column]
        print(f"n {a.n} Re {a.re} t {t:.1f}: {name} against Ghia, RMS {np.sqrt((diff**2).mean()):.2e}, largest {np.abs(diff).max():.2e}")
        if name == "v":
            print("  x:        " + " ".join(f"{x:7.4f}" for x in table[inner, 0]))
            print("  fd-Ghia:  " + " ".join(f"{d:+7.4f}" for d in diff))
        for run in a.runs:
            compare_run(run, name, centres, line, table[inner, 0], table[inner, column], a.averaged)


def compare_run(run, name, centres, line, points, ghia, averaged):
    """RMS of one SPH run's profile against this solution and against Ghia, at Ghia's interior points."""
    path = os.path.join(run, "centreline_ghia.csv")
    lines = open(path).read().split("\n")
    header = lines[0].split(",")
    value = header.index("sph_averaged") if averaged and "sph_averaged" in header else None
    if averaged and value is None:
        sys.exit(f"{path}: no time-averaged profile: was the run made with -profile_average_from?")
    rows = [r.split(",") for r in lines[1:] if r.startswith(name + ",")]
    if averaged and any(not r[value] for r in rows):
        sys.exit(f"{path}: the run ended before its profile average began")
    sph = {round(float(r[1]), 6): float(r[value if averaged else 2]) for r in rows}
    missing = [p for p in points if round(p, 6) not in sph]
    if missing:
        sys.exit(f"{path}: no {name} at {missing}: is it a cavity run at this Re?")
    values = np.array([sph[round(p, 6)] for p in points])
    fd = at(centres, line, points)
    rms = lambda d: 100.0 * np.sqrt((d**2).mean())
    # The profile's strength against this solution, values ~ (1 + s) fd by least squares: s < 0 is a
    # vortex too weak (under-resolved boundary layers), s > 0 one driven too hard.
    s = (values - fd) @ fd / (fd @ fd)
    print(f"  {run}: {name} RMS against this solution {rms(values - fd):.3f} %, against Ghia {rms(values - ghia):.3f} % "
          f"of U; strength {100 * s:+.2f} %, RMS after scaling by it {rms(values - (1 + s) * fd):.3f} %")


if __name__ == "__main__":
    main()
