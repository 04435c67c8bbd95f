"""A body on a free plinth: the compiled driver against the slow reference on random scenes, and its cost.

    python benchmarks/bench_plinth.py --scenes 1000            # kernel vs reference (about 1 h of CPU)
    python benchmarks/bench_plinth.py --scenes 50 --restitution # with random restitutions
    python benchmarks/bench_plinth.py --timing                  # CPU per run: stack against the single block
    python benchmarks/bench_plinth.py --drums                   # a column of N drums in the slow reference
    python benchmarks/bench_plinth.py --p2s 5000                # the end-of-run proof P2S against the runs
                                                                # followed 30 s on (kernel only)
    python benchmarks/bench_plinth.py --linear 100              # on linear bearings, reference only: its limits
                                                                # on random scenes
    python benchmarks/bench_plinth.py --kernel-sliding --scenes 200  # sliding/lead-rubber bearings, kernel vs
                                                                # the reference (Radau)

Random scenes (fixed seed): a body 0.4-2.5 m tall, 0.15-0.8 m wide, on a plinth 0.1-1.5 m tall, 1-3 times as
wide, mass ratio 0.2-5, under a symmetric or antisymmetric Ricker or a one-sine pulse (0.1-0.6 g, 0.3-1.5 s, either
sign), followed 1 s after the pulse in both codes (the reference at rtol 1e-9, ``--ref-rtol``; both with the rest
threshold 1e-5, ``--rest-tol``, which shortens the trains of impacts down to rest that dominate the reference's
cost, one ``solve_ivp`` call per impact, while keeping the two codes on the same rule). Reported: verdict agreement (and which block topples), the
largest differences of the two peaks over their slenderness, the impact counts, the friction demands below 2
(above, a normal force falls to 0: both must exceed 2; runs where a block topples are left out, its normal force
tending to 0 as it falls), and where they disagree.

``--linear N``: random scenes on linear bearings (``T_b`` 0.5-3 s, ``xi`` 0.02-0.3, ``gamma`` 0.05-0.7, pulses
0.3-1.5 g) in the reference, which is all that runs the stack there; checked on each: the energy (base included)
never rises at an impact and the total horizontal momentum is kept; the scenes where the plinth never moved against
the single block on the bearings with ``gamma/(1 + m2)``, those where the body never left its plinth against
``as_block()`` with ``gamma R_asm/R_e`` and ``E = eta_asm`` (both plastic; the single block's reference at the
same rtol and horizon): verdicts, peaks and impact counts; with ``--mirror`` also the flipped pulse.

``--kernel-sliding``: random scenes on single concave, lead-rubber or double concave bearings (``T_b`` 1-4 s,
friction 0.03-0.12, lead-rubber ``Q`` 0.03-0.1 and ``u_y`` 5-25 mm, ``gamma`` 0.05-0.7, pulses 0.3-1.5 g), the kernel
against the reference (Radau at ``--ref-rtol``), as ``--kernel-linear``.

``--timing``: the statue (1.79 m x 0.5 m) on its own and on two plinths under the catalogue's Table II records
found in ROCKCLI_RECORDS, at scale 1, CPU per run (median of 5 rounds), verdict-only.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from rockcli.models import Block, Plinth, Stack
from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric
from rockcli.io.units import G


def random_scene(rng):
    h1, w1 = rng.uniform(0.4, 2.5), rng.uniform(0.15, 0.8)
    h2, w2 = rng.uniform(0.1, 1.5), w1 * rng.uniform(1.0, 3.0)
    stack = Stack(Block.from_dimensions(h1, w1), Plinth(h2, w2, mass_ratio=float(rng.uniform(0.2, 5.0))))
    shape = (RickerSymmetric, RickerAntisymmetric, OneSine)[int(rng.integers(3))]
    pulse = shape(float(rng.uniform(0.1, 0.6)) * G * rng.choice([-1, 1]), float(rng.uniform(0.3, 1.5)))
    return stack, pulse


def differential(n, seed, with_restitution, ref_rtol=1e-9, rest_tol=1e-5, linear=False, sliding=False):
    from rockcli.reference.stack import reference_plinth
    from rockcli.solve import simulate_stack

    rng = np.random.default_rng(seed)
    agree = rocked = toppled = 0
    worst = {"body": 0.0, "plinth": 0.0, "demand": 0.0}
    where = {}
    imp_mismatch = demand_mismatch = 0
    bad = []
    cpu_k = cpu_r = 0.0
    worst["base"] = 0.0
    for i in range(n):
        iso = None
        if sliding:
            stack, iso, pulse = random_sliding_scene(rng)
        elif linear:
            stack, iso, pulse = random_linear_scene(rng)
        else:
            stack, pulse = random_scene(rng)
        E = float(rng.uniform(0.5, 1.0)) if with_restitution else None
        t0 = time.process_time()
        a = simulate_stack(stack, pulse, horizon=1.0, tail=1.0, restitution=E, rest_tol=rest_tol, isolation=iso)
        t1 = time.process_time()
        r = reference_plinth(stack, pulse, horizon=1.0, restitution=E, rtol=ref_rtol, rest_tol=rest_tol,
                             isolation=iso)
        t2 = time.process_time()
        cpu_k += t1 - t0
        cpu_r += t2 - t1
        ref_top = {-1: None, 0: "plinth", 1: "body"}[r.toppled]
        same = a.verdict == r.verdict and a.toppled == ref_top
        agree += same
        rocked += a.verdict == "rocked"
        toppled += a.verdict == "overturned"
        if not same:
            bad.append((i, a.verdict, a.toppled, r.verdict, ref_top, r.peak[1] / stack.body.alpha,
                        r.peak[0] / stack.alpha_asm))
            continue
        db = abs(a.body.theta_max - r.peak[1]) / stack.body.alpha
        dp = abs(a.plinth.theta_max - r.peak[0]) / stack.alpha_asm
        if db > worst["body"]:
            where["body"] = (i, a.body.theta_max_over_alpha, r.peak[1] / stack.body.alpha)
        if dp > worst["plinth"]:
            where["plinth"] = (i, a.plinth.theta_max / stack.alpha_asm, r.peak[0] / stack.alpha_asm)
        worst["body"] = max(worst["body"], db)
        worst["plinth"] = max(worst["plinth"], dp)
        if (linear or sliding) and a.verdict != "overturned":  # the base's peak (after a fall, it rides on without the block)
            du = abs(a.base_disp_max / r.base_disp_max - 1)
            if du > worst["base"]:
                where["base"] = (i, a.base_disp_max, r.base_disp_max)
            worst["base"] = max(worst["base"], du)
        if [a.plinth.n_impacts, a.body.n_impacts] != r.n_impacts:
            imp_mismatch += 1
            print(f"  impacts differ in scene {i}: kernel {[a.plinth.n_impacts, a.body.n_impacts]}, reference "
                  f"{r.n_impacts}", flush=True)
        for mine, ref in ((a.friction_base, r.friction[0]), (a.friction_joint, r.friction[1])):
            if a.verdict == "overturned":  # near the fall a normal force tends to 0: no finite peak to compare
                continue
            if min(mine, ref) < 2.0:
                d = abs(mine / ref - 1) if ref > 0 else abs(mine)
                if d > worst["demand"]:
                    where["demand"] = (i, mine, ref)
                worst["demand"] = max(worst["demand"], d)
            elif not (mine > 2.0 and ref > 2.0):
                demand_mismatch += 1
        if (i + 1) % 25 == 0:
            print(f"  {i + 1} scenes: {agree} verdicts agree; worst peak differences body {worst['body']:.2e}, "
                  f"plinth {worst['plinth']:.2e} alpha", flush=True)
    print(f"{n} random scenes{' on linear bearings' if linear else ''}{' on sliding bearings' if sliding else ''}{' with restitution' if with_restitution else ''}"
          f" (seed {seed}): {agree} verdicts agree "
          f"({rocked} rock, {toppled} topple in the kernel, the rest do not lift)")
    print(f"largest peak differences: body {worst['body']:.3e} alpha1, plinth {worst['plinth']:.3e} alpha_asm; "
          f"impact counts differ in {imp_mismatch}; friction demand below 2: largest relative difference "
          f"{worst['demand']:.2e}, {demand_mismatch} disagreeing above 2 (the runs where a block topples left out)"
          + (f"; base peak: largest relative difference {worst['base']:.2e} (runs that topple left out)"
             if linear or sliding else ""))
    print(f"CPU: kernel {cpu_k:.1f} s ({1e3 * cpu_k / n:.2f} ms a scene), reference {cpu_r:.1f} s")
    print(f"where (scene, kernel, reference): {where}")
    for b in bad:
        print("  disagree:", b)


def random_linear_scene(rng):
    from rockcli.models import LinearIsolation

    stack, _ = random_scene(rng)
    iso = LinearIsolation(float(rng.uniform(0.5, 3.0)), float(rng.uniform(0.02, 0.3)), float(rng.uniform(0.05, 0.7)))
    shape = (RickerSymmetric, RickerAntisymmetric, OneSine)[int(rng.integers(3))]
    pulse = shape(float(rng.uniform(0.3, 1.5)) * G * rng.choice([-1, 1]), float(rng.uniform(0.3, 1.5)))
    return stack, iso, pulse


def random_sliding_scene(rng):
    """A random stack on single concave, lead-rubber or double concave bearings (``T_b`` 1-4 s, friction 0.03-0.12,
    ``Q`` 0.03-0.1 with ``u_y`` 5-25 mm, ``gamma`` 0.05-0.7) under a pulse of 0.3-1.5 g, 0.3-1.5 s."""
    from rockcli.models import DoubleConcaveSliding, LeadRubber, SingleConcaveSliding

    stack, _ = random_scene(rng)
    kind = int(rng.integers(3))
    Tb, gamma = float(rng.uniform(1.0, 4.0)), float(rng.uniform(0.05, 0.7))
    if kind == 0:
        iso = SingleConcaveSliding(Tb, float(rng.uniform(0.03, 0.12)), gamma=gamma)
    elif kind == 1:
        iso = LeadRubber(Tb, float(rng.uniform(0.03, 0.1)), float(rng.uniform(0.005, 0.025)), gamma=gamma)
    else:
        iso = DoubleConcaveSliding.from_period(Tb, float(rng.uniform(0.03, 0.12)), float(rng.uniform(0.03, 0.12)),
                                               ratio=float(rng.uniform(0.5, 2.0)), gamma=gamma)
    shape = (RickerSymmetric, RickerAntisymmetric, OneSine)[int(rng.integers(3))]
    pulse = shape(float(rng.uniform(0.3, 1.5)) * G * rng.choice([-1, 1]), float(rng.uniform(0.3, 1.5)))
    return stack, iso, pulse


def linear_limits(n, seed, rtol=1e-10, horizon=1.0, rest_tol=1e-5, mirror=False):
    """The reference on linear bearings over random scenes: its own invariants, and the limits it must meet."""
    from rockcli.models import LinearIsolation
    from rockcli.reference import reference_simulate
    from rockcli.reference.stack import reference_plinth, stack_base, stack_blocks
    from rockcli.reference.stack_mechanics import StackModel

    rng = np.random.default_rng(seed)
    counts = dict(rocked=0, toppled=0, still=0, impacts=0, b_cases=0, b_agree=0, p_cases=0, p_agree=0,
                  mirror_agree=0)
    worst = dict(energy=0.0, momentum=0.0, b_peak=0.0, p_peak=0.0, mirror=0.0)
    bad = []
    cpu = 0.0
    for i in range(n):
        stack, iso, pulse = random_linear_scene(rng)
        t0 = time.process_time()
        r = reference_plinth(stack, pulse, isolation=iso, horizon=horizon, rtol=rtol, rest_tol=rest_tol,
                             record_impacts=True)
        cpu += time.process_time() - t0
        counts["rocked"] += r.verdict == "rocked"
        counts["toppled"] += r.verdict == "overturned"
        counts["still"] += r.verdict == "no_uplift"
        model = StackModel(stack_blocks(stack), stack_base(stack, iso))
        for d in r.impacts:
            counts["impacts"] += 1
            worst["energy"] = max(worst["energy"], d["ke_plus"] / d["ke_minus"] - 1)
            px = [float(np.dot(model.Mdiag[[0, 3, 6]], v[[0, 3, 6]])) for v in (d["v_minus"], d["v_plus"])]
            worst["momentum"] = max(worst["momentum"], abs(px[1] - px[0]) / (abs(px[0]) + 1e-300))
        kw = dict(atol=None, horizon=horizon, rtol=rtol, rest_tol=rest_tol)
        if r.verdict != "no_uplift" and r.peak[0] == 0.0:  # the plinth never moved: B only
            counts["b_cases"] += 1
            s = reference_simulate(stack.body, LinearIsolation(iso.T_b, iso.xi, iso.gamma / (1 + stack.m2)), pulse,
                                   **kw)
            d = abs(s.theta_max - r.peak[1]) / stack.body.alpha
            same = s.verdict == r.verdict and s.n_impacts == r.n_impacts[1]
            counts["b_agree"] += same
            worst["b_peak"] = max(worst["b_peak"], d)
            if not same:
                bad.append(("B", i, r.verdict, s.verdict, r.n_impacts, s.n_impacts))
        if r.verdict != "no_uplift" and r.peak[1] == 0.0:  # the body never left its plinth: P only
            e = stack.as_block()
            ge = iso.gamma * stack.R_asm / e.R
            if ge < 1:
                counts["p_cases"] += 1
                s = reference_simulate(e, LinearIsolation(iso.T_b, iso.xi, ge), pulse, restitution=stack.eta_asm, **kw)
                d = abs(s.theta_max - r.peak[0]) / stack.alpha_asm
                same = s.verdict == r.verdict and s.n_impacts == r.n_impacts[0]
                counts["p_agree"] += same
                worst["p_peak"] = max(worst["p_peak"], d)
                if not same:
                    bad.append(("P", i, r.verdict, s.verdict, r.n_impacts, s.n_impacts))
        if mirror:
            flipped = type(pulse)(-pulse.a_p, pulse.T_p)
            m = reference_plinth(stack, flipped, isolation=iso, horizon=horizon, rtol=rtol, rest_tol=rest_tol)
            same = m.verdict == r.verdict and m.n_impacts == r.n_impacts
            counts["mirror_agree"] += same
            worst["mirror"] = max(worst["mirror"], max(abs(a - b) for a, b in zip(m.peak, r.peak)),
                                  abs(m.base_disp_max - r.base_disp_max) / r.base_disp_max)
            if not same:
                bad.append(("mirror", i, r.verdict, m.verdict, r.n_impacts, m.n_impacts))
        if (i + 1) % 10 == 0:
            print(f"  {i + 1} scenes: {counts} worst {worst}", flush=True)
    print(f"{n} random scenes on linear bearings (seed {seed}): {counts['rocked']} rock, {counts['toppled']} topple, "
          f"{counts['still']} do not lift; {counts['impacts']} impacts: energy rises by at most "
          f"{worst['energy']:.1e} (relative), horizontal momentum kept to {worst['momentum']:.1e}")
    print(f"plinth never moved: {counts['b_agree']} of {counts['b_cases']} agree with the single block with "
          f"gamma/(1 + m2) (verdict, impacts), peaks within {worst['b_peak']:.1e} alpha1; body never left its plinth: "
          f"{counts['p_agree']} of {counts['p_cases']} agree with as_block(), peaks within {worst['p_peak']:.1e} "
          f"alpha_asm" + (f"; mirror: {counts['mirror_agree']} of {n} agree, peaks within {worst['mirror']:.1e}"
                          if mirror else ""))
    print(f"CPU: reference {cpu:.1f} s ({cpu / n:.2f} s a scene)")
    for b in bad:
        print("  disagree:", b)


def drums(counts=(1, 2, 3, 4, 6, 8)):
    """The Bassae column (5.95 m x 1.11 m) cut into N equal drums, in the reference (any number of blocks): what
    the same mechanics give and cost as N grows (the kernel is written for two blocks)."""
    from rockcli.reference import ReferenceTimeout, reference_simulate
    from rockcli.reference.stack import reference_stack

    H, D = 5.95, 1.11
    for pulse in (RickerSymmetric(0.3 * G, 1.0), OneSine(0.25 * G, 1.5), RickerSymmetric(1.0 * G, 0.25)):
        print(f"{type(pulse).__name__} a_p = {pulse.a_p / G:g} g, T_p = {pulse.T_p:g} s")
        mono = reference_simulate(Block.from_dimensions(H, D), None, pulse, horizon=2.0, atol=None)
        print(f"  monolith (single-block reference): {mono.verdict}, peak {mono.theta_max:.5f} rad, "
              f"{mono.n_impacts} impacts")
        for n in counts:
            blocks = [(D / 2, H / (2 * n), 1.0)] * n
            t0 = time.process_time()
            try:
                r = reference_stack(blocks, pulse, horizon=2.0, record_impacts=True, deadline_s=600)
            except ReferenceTimeout:
                print(f"  N = {n}: over the 600 s wall budget ({time.process_time() - t0:.0f} s CPU)", flush=True)
                continue
            cpu = time.process_time() - t0
            zeros = [sum(1 for x in d["q"] if x == 0.0) for d in r.impacts]
            cands = [3 ** z if d["j"] is not None else 0 for z, d in zip(zeros, r.impacts)]
            pats = len({p for _, p in r.patterns})
            top = "none" if r.toppled < 0 else f"interface {r.toppled}"
            print(f"  N = {n}: {r.verdict:10s} topples at {top:12s} top drum's tilt {r.theta_peak[-1]:.5f} rad, "
                  f"{len(r.patterns) - 1} pattern changes ({pats} of the 3^{n} = {3 ** n} patterns visited), "
                  f"{sum(r.n_impacts)} impacts, candidates per impact up to {max(cands, default=0)}, "
                  f"{r.n_inconsistent} inconsistent, {r.n_jumps} jumps, {r.steps} steps, {cpu:.1f} s CPU",
                  flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", type=int, default=200)
    ap.add_argument("--seed", type=int, default=36)
    ap.add_argument("--restitution", action="store_true")
    ap.add_argument("--timing", action="store_true")
    ap.add_argument("--drums", action="store_true")
    ap.add_argument("--p2s", type=int, default=0)
    ap.add_argument("--ref-rtol", type=float, default=1e-9)
    ap.add_argument("--rest-tol", type=float, default=1e-5)
    ap.add_argument("--linear", type=int, default=0)
    ap.add_argument("--mirror", action="store_true")
    ap.add_argument("--kernel-linear", action="store_true", help="--scenes on linear bearings, kernel vs reference")
    ap.add_argument("--kernel-sliding", action="store_true",
                    help="--scenes on sliding and lead-rubber bearings, kernel vs reference (Radau)")
    ap.add_argument("--isolation", default=None, help="--timing on these bearings, e.g. linear:Tb=2,xi=0.1,gamma=0.5")
    args = ap.parse_args(argv)
    if args.linear:
        linear_limits(args.linear, args.seed, rest_tol=args.rest_tol, mirror=args.mirror)
        return 0
    if args.p2s:
        sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1] / "tests"))
        from test_plinth_kernel import p2s_mismatches

        t0 = time.process_time()
        hits, bad = p2s_mismatches(args.p2s, args.seed)
        print(f"{args.p2s} random scenes (seed {args.seed}): {hits} ended by P2S, {bad} mismatches against the runs "
              f"followed 30 s on ({time.process_time() - t0:.1f} s CPU)")
        return 0
    if args.timing:
        iso = None
        if args.isolation:
            from rockcli.models import parse_isolation_spec

            iso = parse_isolation_spec(args.isolation)
        return run_timing(isolation=iso)
    if args.drums:
        drums()
        return 0
    differential(args.scenes, args.seed, args.restitution, args.ref_rtol, args.rest_tol, args.kernel_linear,
                 args.kernel_sliding)
    return 0


def run_timing(rounds=5, isolation=None):
    """CPU per verdict-only run of the statue alone and on two plinths under the ten Table II records (on a rigid
    foundation, or on ``isolation``)."""
    from rockcli.assess.excitations import resolve_excitations
    from rockcli.solve import simulate, simulate_stack

    statue = Block.from_dimensions(1.79, 0.5, "statue")
    recs = [e.motion for e in resolve_excitations(None, "record")[0] if not e.error]
    cases = [("statue alone", None), ("on plinth 0.2 x 4 (cannot lift)", Plinth(0.2, 4.0)),
             ("on plinth 1.0 x 0.6", Plinth(1.0, 0.6))]
    simulate(statue, isolation, recs[0])  # compiled / loaded before the clock
    simulate_stack(Stack(statue, Plinth(1.0, 0.6)), recs[0], isolation=isolation)
    base = None
    for name, plinth in cases:
        times, steps, verdicts = [], 0, []
        for _ in range(rounds):
            t0 = time.process_time()
            for rec in recs:
                if plinth is None:
                    r = simulate(statue, isolation, rec)
                    steps += r.steps if _ == 0 else 0
                    verdicts += [r.verdict] if _ == 0 else []
                else:
                    r = simulate_stack(Stack(statue, plinth), rec, isolation=isolation)
                    steps += r.steps if _ == 0 else 0
                    verdicts += [r.toppled or r.verdict] if _ == 0 else []
            times.append(time.process_time() - t0)
        per = float(np.median(times)) / len(recs)
        base = per if base is None else base
        print(f"{name:34s} {1e3 * per:7.2f} ms CPU a run ({per / base:.2f} x the single block), {steps} steps over "
              f"{len(recs)} records; verdicts {verdicts}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
