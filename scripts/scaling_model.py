#!/usr/bin/python3
"""Project the step time of a distributed run from `fdem decompose` counts (issue #15, spec
parallel-and-python.md §4.4; docs/parallel.md "Projected scaling").

Usage:
  fdem decompose SCENARIO --parts 2,4,...,1024 --csv counts.csv
  scripts/scaling_model.py counts.csv --t1 SECONDS_PER_SERIAL_STEP [--png scaling.png]

Model, per part r and step (no overlap of communication and computation):
  W_r = t1 * ( f_el * tris_run_r / T  +  (f_node + f_broad) * nodes_r / N
               +  f_pair * pairs_r / pairs
               +  f_apply * (contact_records_r + contact_received_r) / records  +  f_repl )
  C_r = (recv_from_r + send_to_r + 2 * contact_neighbours_r) * alpha
        + (ghost_bytes_in_r + ghost_bytes_out_r + contact_bytes_in_r + contact_bytes_out_r) / beta
        + n_coll * alpha_c * ceil(log2 P) + gathered_bytes_all / beta
  t_P = max_r (W_r + C_r),  speed-up t1 / t_P,  efficiency speed-up / P
f_el, f_node, f_pair, f_broad, f_apply: the shares of the serial step that the processes split
(element pass, node update, narrow phase of the owned targets, the broad phase's queries of the
owned targets — local since 2026-11-28, split like the owned nodes —, and the application of
the pairs in contact: each process its own and the records it receives, since the local apply
of 2026-11-28); f_repl: what every process does whole in the current implementation (the broad
phase's circles and grid over every sub-triangle on rebuild steps). Defaults: callgrind of
example 04 (docs/parallel.md: 2.11, 0.46, 0.88 and 0.72 + 0.17 G of 4.34 G instructions; the
0.17 G "rest" is the apply), the broad phase's 0.72 G split 84 % queries / 16 % circles and grid
as measured on the 10^4-grain raster (docs/performance.md "Local broad phase");
--f-apply 0 --f-repl 0.066 gives the projection of the code before the local apply (every
process applied every pair), --f-broad 0 --f-repl 0.205 the one before the local queries.
alpha, beta, alpha_c: assumed cluster values (spec §4.4), not measured.
"""
import argparse
import csv
import math
import sys
from collections import defaultdict


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", help="rows of fdem decompose --csv (one or several part counts)")
    ap.add_argument("--t1", type=float, required=True, help="serial step time [s]")
    ap.add_argument("--f-el", type=float, default=2.11 / 4.34)
    ap.add_argument("--f-node", type=float, default=0.46 / 4.34)
    ap.add_argument("--f-pair", type=float, default=0.88 / 4.34)
    ap.add_argument("--f-broad", type=float, default=0.84 * 0.72 / 4.34)
    ap.add_argument("--f-apply", type=float, default=0.17 / 4.34)
    ap.add_argument("--f-repl", type=float, default=0.16 * 0.72 / 4.34)
    ap.add_argument("--alpha", type=float, default=2e-6, help="latency per message [s]")
    ap.add_argument("--beta", type=float, default=10e9, help="bandwidth [B/s]")
    ap.add_argument("--alpha-c", type=float, default=1.5e-6, help="latency per collective stage [s]")
    ap.add_argument("--collectives", type=float, default=2 + 1 / 16,
                    help="collectives per step (the fused min, the exact sums with the contact "
                         "sums, the stop check every 16th step)")
    ap.add_argument("--png", help="plot speed-up and efficiency against P")
    a = ap.parse_args()

    by_p = defaultdict(list)
    with open(a.csv) as f:
        for row in csv.DictReader(f):
            by_p[int(row["parts"])].append({k: int(v) for k, v in row.items()})
    if not by_p:
        sys.exit(f"{a.csv}: no rows")
    # totals from any decomposition: every node owned once, every chunk counted once
    any_rows = next(iter(by_p.values()))
    N = sum(r["nodes"] for r in any_rows)
    T = sum(r["tris_counted"] for r in any_rows)
    pairs = sum(r["candidate_pairs"] for r in any_rows)
    records = sum(r["contact_records"] for r in any_rows)
    print(f"model: N = {N} nodes, T = {T} triangles (of movable bodies), {pairs} candidate pairs, "
          f"{records} in contact; "
          f"t1 = {a.t1:.4g} s/step; shares el {a.f_el:.3f}, node {a.f_node:.3f}, broad-phase "
          f"queries {a.f_broad:.3f}, pairs {a.f_pair:.3f}, apply {a.f_apply:.3f}, replicated {a.f_repl:.3f}; alpha {a.alpha:.3g} s, beta {a.beta:.3g} "
          f"B/s, alpha_c {a.alpha_c:.3g} s x {a.collectives:.3g} collectives")
    print(f"{'P':>6} {'work max [s]':>12} {'comm max [s]':>12} {'step [s]':>10} {'speed-up':>9} "
          f"{'eff.':>6} {'ghost B/step max':>16} {'msgs max':>8} {'redundant el.':>13} "
          f"{'eff. no repl.':>13}")
    out = []
    for P in sorted(by_p):
        rows = by_p[P]
        gathered = sum(r["gathered_bytes"] for r in rows)
        log2p = math.ceil(math.log2(P)) if P > 1 else 0
        worst = 0.0
        worst_w = worst_c = 0.0
        worst_norepl = 0.0
        for r in rows:
            w = a.t1 * (a.f_el * r["tris_run"] / max(T, 1)
                        + (a.f_node + a.f_broad) * r["nodes"] / max(N, 1)
                        + a.f_pair * r["candidate_pairs"] / max(pairs, 1)
                        + a.f_apply * (r["contact_records"] + r["contact_received"])
                        / max(records, 1))
            c = 0.0
            if P > 1:
                c = ((r["recv_from"] + r["send_to"] + 2 * r["contact_neighbours"]) * a.alpha
                     + (r["ghost_bytes_in"] + r["ghost_bytes_out"] + r["contact_bytes_in"]
                        + r["contact_bytes_out"]) / a.beta
                     + a.collectives * a.alpha_c * log2p + gathered / a.beta)
            t = w + a.t1 * a.f_repl + c
            if t > worst:
                worst, worst_w, worst_c = t, w + a.t1 * a.f_repl, c
            worst_norepl = max(worst_norepl, w / (1 - a.f_repl) + c)
        speed = a.t1 / worst
        redundant = sum(r["tris_run"] for r in rows) / max(T, 1) - 1
        bmax = max(r["ghost_bytes_in"] + r["ghost_bytes_out"] for r in rows)
        mmax = max(r["recv_from"] + r["send_to"] for r in rows)
        eff_norepl = a.t1 / worst_norepl / P
        out.append((P, speed, speed / P, eff_norepl))
        print(f"{P:>6} {worst_w:>12.4g} {worst_c:>12.4g} {worst:>10.4g} {speed:>9.3g} "
              f"{speed / P:>6.3f} {bmax:>16} {mmax:>8} {100 * redundant:>12.1f}% "
              f"{eff_norepl:>13.3f}")
    print("eff. no repl.: the same model with the replicated share distributed like the element "
          "pass (a local grid of the broad phase; not built yet)")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        ps = [o[0] for o in out]
        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        ax[0].loglog(ps, [o[1] for o in out], "o-", label="model, today (M2b, local queries and apply)")
        ax[0].loglog(ps, [o[3] * o[0] for o in out], "s--", label="model, no replicated phase")
        ax[0].loglog(ps, ps, ":", color="grey", label="ideal")
        ax[0].set_xlabel("processes P")
        ax[0].set_ylabel("speed-up over one process")
        ax[0].legend()
        ax[1].semilogx(ps, [o[2] for o in out], "o-", label="today (M2b, local queries and apply)")
        ax[1].semilogx(ps, [o[3] for o in out], "s--", label="no replicated phase")
        ax[1].set_xlabel("processes P")
        ax[1].set_ylabel("parallel efficiency")
        ax[1].set_ylim(0, 1.05)
        ax[1].legend()
        fig.suptitle(f"alpha-beta model from fdem decompose counts (N = {N} nodes, T = {T} "
                     f"triangles)")
        fig.tight_layout()
        fig.savefig(a.png, dpi=100)
        print(f"plot {a.png}")


if __name__ == "__main__":
    main()
