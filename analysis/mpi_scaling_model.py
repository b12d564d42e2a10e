#!/usr/bin/python3
"""Weak-scaling model of dustlift's x-slab decomposition for 8-1024 ranks (docs/parallel.md).

Usage: /usr/bin/python3 analysis/mpi_scaling_model.py [--rate M] [--active F] [--alpha US]
       [--beta GBS] [--output-every N] [--parcel-rate M] [--substeps S] [--ghost-bytes B]
       [--exchanges E]

Each rank holds one slab of the paper grid's size (950 x 160 cells + 2 ghost layers), so the
channel grows with the ranks (P x 237.5 mm). Per rank and step:
  compute  3 stages x cells x active fraction / cell-stage rate of one rank
  halo     E exchanges per step (5 for the gas: porosity at the step's start, 3 stages, the
           final fill; 10 with dust, measured: alpha_p, the derivatives, the implicit-exchange factors);
           an interior rank sends and receives one message per neighbour each:
           2 x (alpha + m / beta), m = 6 fields x 2 columns x 164 rows x 8 B = 15,744 B
           (measured, work summary; the coupling's messages are smaller, counted as these)
  collect. 7 allreduces (time step, 3 fault agreements, observers' gather, stop, wall
           checkpoint), each 2 ceil(log2 P) alpha (recursive doubling)
  output   rank 0 gathers the whole grid (10 fields) every N steps through one link:
           10 x 8 B x cells x P / beta, spread over the N steps (its VTK writing not counted)
  parcels  the layer's share of the slab (60,000 parcels per 400 mm: 35,625 per rank), all
           active (the resting ones the run skips would only shorten the compute), S DEM
           sub-steps per CFD step at the coupled parcel-sub-step rate of one rank; per
           sub-step one ghost refresh per neighbour (alpha + ghost bytes / beta) and the
           allreduce that decides a rebuild (2 ceil(log2 P) alpha); measured on the paper
           scene with dust (bench/mpi_ranks.sh ... vertical_shock.toml): 32,453 B in 13.7
           messages per rank and step, 11.4 sub-steps a step, i.e. 2,370 B a message.
Efficiency = compute / sum. The defaults are this machine's measurements (2026-12-02, one
thread per rank: 24.7 M cell-stages/s, 85.5 % of the cells active over 0.2 ms of the paper
scene; 37.3 M parcel-sub-steps/s coupled, 11.4 sub-steps per CFD step) and an
InfiniBand-class network (alpha = 2 us, beta = 10 GB/s), not a measurement.
"""
import argparse
import math

CELLS = 950 * 160
CELLS_WITH_GHOSTS = 954 * 164
MESSAGE_BYTES = 6 * 2 * 164 * 8


PARCELS_PER_RANK = 60000 * 0.2375 / 0.4


def model(ranks, rate, active, alpha, beta, output_every, parcel_rate, substeps, ghost_bytes, exchanges):
    compute = 3 * CELLS * active / rate + substeps * PARCELS_PER_RANK / parcel_rate
    neighbours = 1 if ranks == 1 else 2
    halo = exchanges * neighbours * (alpha + MESSAGE_BYTES / beta) if ranks > 1 else 0.0
    collectives = 7 * 2 * math.ceil(math.log2(ranks)) * alpha if ranks > 1 else 0.0
    parcels = substeps * (neighbours * (alpha + ghost_bytes / beta) + 2 * math.ceil(math.log2(ranks)) * alpha) \
        if ranks > 1 else 0.0
    output = 10 * 8 * CELLS_WITH_GHOSTS * ranks / beta / output_every if ranks > 1 else 0.0
    total = compute + halo + collectives + parcels + output
    return compute, halo, collectives, parcels, output, compute / total


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--rate", type=float, default=24.7, help="M cell-stages/s of one rank")
    p.add_argument("--active", type=float, default=0.855, help="fraction of cells updated")
    p.add_argument("--alpha", type=float, default=2.0, help="message latency, us")
    p.add_argument("--beta", type=float, default=10.0, help="link bandwidth, GB/s")
    p.add_argument("--output-every", type=float, default=900.0, help="steps between outputs")
    p.add_argument("--parcel-rate", type=float, default=37.3, help="M parcel-sub-steps/s of one rank, coupled")
    p.add_argument("--substeps", type=float, default=11.4, help="DEM sub-steps per CFD step")
    p.add_argument("--ghost-bytes", type=float, default=2370.0, help="ghost refresh message, B")
    p.add_argument("--exchanges", type=float, default=10.0, help="halo exchanges per step (5 gas only)")
    a = p.parse_args()
    print("| ranks | channel (m) | compute (ms) | gas halo (us) | collectives (us) | parcel ghosts (us) | "
          "output gather (us) | efficiency |")
    print("|---|---|---|---|---|---|---|---|")
    for ranks in (1, 8, 16, 64, 256, 1024):
        c, h, k, g, o, e = model(ranks, a.rate * 1e6, a.active, a.alpha * 1e-6, a.beta * 1e9, a.output_every,
                                 a.parcel_rate * 1e6, a.substeps, a.ghost_bytes, a.exchanges)
        print(f"| {ranks} | {ranks * 0.2375:.1f} | {c * 1e3:.2f} | {h * 1e6:.1f} | {k * 1e6:.1f} | {g * 1e6:.1f} | "
              f"{o * 1e6:.1f} | {100 * e:.1f} % |")


if __name__ == "__main__":
    main()
