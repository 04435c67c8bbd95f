"""How narrow do overturning windows get below the first overturning acceleration? (issue 28)

For every column (configuration x omega_p/p) of the paper's Figures 7, 9 and 11 (the commands of the
README), runs a fine geometric grid ``y_u (1 + FINE)^k`` from the uplift threshold ``y_u`` up to the
minimum the search reports (or ``ap_max`` where it reports none), with the runs the search itself makes
(verdict-only, early stops), and keeps every verdict and peak ``theta_max/alpha``. Then:

1. the overturning windows found below the reported minimum (the ones a scan stepped over) and the
   width of every window that starts below 1.05 x the first overturning value: the narrowest widths;
2. an emulation on the stored fine grid of the scan with a coarse step (a multiple of the fine step,
   every alignment of the coarse grid) with and without the refinement rule "scan finely between two
   safe coarse values when the larger of their peaks is above THRESHOLD": the columns whose first
   overturning value is stepped over, and the runs the refinement adds.

Prints a table (no assertions). ``--save FILE.npz`` keeps the raw grids, ``--load`` reuses them.

    PYTHONPATH=$PWD python benchmarks/bench_min_windows.py --fine 0.001 --figures 7,9,11
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

L = "linear:TbTp={r},xi=0.05,gamma=0.01"
FIGURES = {
    "7": [(a, sh, iso) for a in (10.0, 20.0) for sh in ("ricker-sym", "ricker-anti")
          for iso in ("none", L.format(r=2), L.format(r=3), L.format(r=4))],
    "9": [(16.0, "ricker-sym", iso) for iso in ("none", L.format(r=2), "scss:TbTp=2,mu=0.05,gamma=0.01")],
    "11": [(16.0, "ricker-sym", iso) for iso in
           ("dcss:TbTp=2,mu1=0.03,mu2=0.07,r=1", "dcss:TbTp=2,mu1=0.03,mu2=0.06,r=2", "scss:TbTp=2,mu=0.05",
            "dcss:TbTp=3,mu1=0.03,mu2=0.07,r=1", "dcss:TbTp=3,mu1=0.03,mu2=0.06,r=2", "scss:TbTp=3,mu=0.05")],
}


def measure(configs, xs, fine, ap_max, chunk_runs=40_000):
    from rockcli.spectra import Family, Runner, parse_isolation
    from rockcli.spectra.minimum import search_min_overturning

    families = [Family(math.radians(a), sh, parse_isolation(iso)) for a, sh, iso in configs]
    fam = np.repeat(np.arange(len(families)), xs.size)
    x = np.tile(xs, len(families))
    runner = Runner()
    t0 = time.perf_counter()
    res = search_min_overturning(families, fam, x, ap_max=ap_max, runner=runner)
    t_search = time.perf_counter() - t0
    print(f"  search: {res.runs} runs, {t_search:.0f} s", flush=True)
    top = np.where(np.isfinite(res.ap_min), res.ap_min * (1 + 2 * fine), ap_max)
    y_u = res.ap_uplift
    cols = np.flatnonzero(np.isfinite(y_u))
    n_k = np.zeros(fam.size, np.int64)
    n_k[cols] = np.floor(np.log(top[cols] / y_u[cols]) / math.log1p(fine)).astype(np.int64) + 1
    over = [None] * fam.size
    peak = [None] * fam.size
    final = [None] * fam.size
    t0 = time.perf_counter()
    runs = 0
    start = 0
    while start < cols.size:  # chunks of whole columns
        stop = start
        total = 0
        while stop < cols.size and (total == 0 or total + n_k[cols[stop]] <= chunk_runs):
            total += n_k[cols[stop]]
            stop += 1
        cc = cols[start:stop]
        ci = np.repeat(cc, n_k[cc])
        kk = np.concatenate([np.arange(1, n_k[c] + 1) for c in cc])
        yv = y_u[ci] * (1 + fine) ** kk
        out = runner(families, fam[ci], x[ci], yv, early=True)
        runs += ci.size
        pos = 0
        for c in cc:
            n = n_k[c]
            over[c] = out.overturned[pos:pos + n]
            peak[c] = out.theta_max_over_alpha[pos:pos + n]
            final[c] = out.peak_final[pos:pos + n]
            pos += n
        start = stop
        print(f"  {runs} runs, {time.perf_counter() - t0:.0f} s", flush=True)
    return dict(y_u=y_u, ap_min=res.ap_min, ap_safe=res.ap_safe, fam=fam, x=x, runs=runs, t_search=t_search,
                t_fine=time.perf_counter() - t0, search_runs=res.runs, over=over, peak=peak, final=final)


def windows(o):
    """(start, stop) index pairs of the runs of True in o (stop exclusive)."""
    d = np.diff(np.concatenate([[0], o.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1)))


def emulate(o, m, band, mf):
    """The search on the stored fine grid: the scan on every m-th value (offset j = 0..m-1) up to its
    first overturning value F, then (``band`` not None) every mf-th value from F / (1 + band) up to F,
    then a bisection on the fine grid below the first overturning value found. Returns (worst index
    found - true first index over the alignments, runs of the rescan in the worst alignment)."""
    o = np.concatenate([o, np.ones(2 * m, bool)])  # the grid ends at the reported minimum: overturns above it
    true_first = int(np.flatnonzero(o)[0])
    worst_miss, worst_extra = 0, 0
    for j in range(m):
        ks = np.arange(j, o.size, m)
        hit = np.flatnonzero(o[ks])
        if not hit.size:
            worst_miss = max(worst_miss, o.size - true_first)
            continue
        first = int(ks[hit[0]])
        scanned = ks[:hit[0] + 1]
        extra = 0
        if band is not None:
            lo_k = max(0, first - int(round(math.log1p(band) / math.log1p(FINE_STEP[0]))))
            fine = np.arange(lo_k, first, mf)
            extra = fine.size
            scanned = np.union1d(scanned, fine)
        first = int(scanned[np.flatnonzero(o[scanned])[0]])
        below = scanned[scanned < first]
        prev = int(below[-1]) if below.size else -1
        lo, hi = prev, first  # bisection on the fine grid
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if o[mid]:
                hi = mid
            else:
                lo = mid
        worst_miss = max(worst_miss, hi - true_first)
        worst_extra = max(worst_extra, extra)
    return worst_miss, worst_extra


FINE_STEP = [0.001]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--figures", default="7,9,11")
    ap.add_argument("--fine", type=float, default=0.001)
    ap.add_argument("--wp-p", default="0.5:12:93")
    ap.add_argument("--every", type=int, default=1, help="keep every n-th omega_p/p value of --wp-p")
    ap.add_argument("--ap-max", type=float, default=20.0)
    ap.add_argument("--save", default=None)
    ap.add_argument("--load", default=None)
    ap.add_argument("--coarse", default="10", help="coarse steps as multiples of the fine step")
    ap.add_argument("--rescans", default="1/0.02,1/0.05,2/0.05,1/0.1,2/0.1,2/0.2",
                    help="rescan steps (in fine steps) / bands below the first overturning scanned value")
    args = ap.parse_args()
    a, b, c = args.wp_p.split(":")
    xs = np.linspace(float(a), float(b), int(c))[::args.every]
    configs = []
    for f in args.figures.split(","):
        for cfg in FIGURES[f.strip()]:
            if cfg not in configs:
                configs.append(cfg)
    if args.load:
        z = np.load(args.load, allow_pickle=True)
        d = {k: z[k] for k in z.files}
        d = {k: (v.item() if v.shape == () else v) for k, v in d.items()}
        configs = [tuple(c) for c in d["configs"]]
        configs = [(float(c[0]), c[1], c[2]) for c in configs]
    else:
        d = measure(configs, xs, args.fine, args.ap_max)
        d["configs"] = np.array(configs, dtype=object)
        if args.save:
            np.savez(args.save, **{k: (np.array(v, dtype=object) if isinstance(v, list) else v)
                                   for k, v in d.items()})
    fine = args.fine
    print(f"search (step 1 %): {d['search_runs']} runs in {d['t_search']:.1f} s; fine grid ({fine:g}): "
          f"{d['runs']} runs in {d['t_fine']:.1f} s")
    nx = len(d["x"]) // len(configs)
    widths_missed, widths_all = [], []
    print("\nwindows below the reported minimum (stepped over by the 1 % scan):")
    for i in range(len(d["x"])):
        o = d["over"][i]
        if o is None or not o.any():
            continue
        cfg = configs[i // nx]
        y = d["y_u"][i] * (1 + fine) ** np.arange(1, o.size + 1)
        ws = windows(o)
        first_y = y[ws[0][0]]
        for s, e in ws:
            if y[s] > 1.05 * first_y or e == o.size:  # far above, or cut by the end of the grid
                break
            w_rel = (1 + fine) ** (e - s) - 1  # at most this wide (+1 fine step at most)
            widths_all.append(w_rel)
        rep = d["ap_min"][i]
        if np.isnan(rep) or first_y < d["ap_safe"][i] * (1 - 1e-9):
            s, e = ws[0]
            pk_lo = d["peak"][i][max(0, s - 10):s]
            pk_hi = d["peak"][i][e:e + 10]
            widths_missed.append((e - s) * fine)
            print(f"  {cfg[0]:g} deg {cfg[1]} {cfg[2]} wp/p={d['x'][i]:.4g}: first overturning {first_y:.4f} "
                  f"({e - s} fine values), reported {rep:.4f}; peaks of the 10 below {np.round(pk_lo, 3)}, "
                  f"above {np.round(pk_hi, 3)}")
    wa = np.array(widths_all)
    print(f"\n{wa.size} windows starting within 5 % of the first overturning value; widths (relative, <= "
          f"count x {fine:g}): smallest {np.sort(wa)[:12].round(4)}")
    for lim in (0.002, 0.005, 0.01, 0.02):
        print(f"  narrower than {lim:.1%}: {int((wa < lim - 1e-12).sum())}")
    print("\nemulated searches (worst alignment of the coarse grid per column; a miss: more than one fine step "
          "above the first overturning value of the fine grid):")
    print("  coarse   rescan step  band    columns missed  worst miss [fine steps]  rescan runs (sum of worst)")
    FINE_STEP[0] = fine
    for m in (int(v) for v in args.coarse.split(",")):
        for mf, band in [(None, None)] + [(int(a), float(b)) for a, b in
                                          (t.split("/") for t in args.rescans.split(","))]:
            miss_cols, worst, extra = 0, 0, 0
            for i in range(len(d["x"])):
                o = d["over"][i]
                if o is None:
                    continue
                mi, ex = emulate(o, m, band, mf)
                miss_cols += mi > 1
                worst = max(worst, mi)
                extra += ex
            print(f"  {m * fine:6.4f}  {'-' if mf is None else f'{mf * fine:.4f}':>11}  "
                  f"{'-' if band is None else f'{band:.2f}':>5}  {miss_cols:14d}  {worst:23d}  {extra:10d}")

if __name__ == "__main__":
    main()
