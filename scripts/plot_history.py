#!/usr/bin/python3
"""Plot an fdem energy history (history.csv) to energies.png.

usage: scripts/plot_history.py out/history.csv [--out out/energies.png] [--check]

Top panel: every energy column against time [J/m]. Bottom panel: the balance error
energy_error = total - total(first row) [J/m], with its largest magnitude relative to the
largest energy in the run in the title. Columns: docs/output.md. --check also verifies that the
PNG was written (used by the CTest test output.plot_history).
Run with /usr/bin/python3 (needs python3-matplotlib).
"""
import argparse
import csv
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as exc:  # pragma: no cover - depends on the machine
    sys.stderr.write(f"plot_history.py: cannot import matplotlib ({exc}); install "
                     "python3-matplotlib and run with /usr/bin/python3\n")
    sys.exit(2)

ENERGIES = ["kinetic", "strain", "contact", "work_gravity", "work_external",
            "dissipated_viscous", "dissipated_contact", "total"]
REQUIRED = ["step", "time"] + ENERGIES + ["energy_error", "active_contacts"]


def read_history(path):
    """Columns of the CSV as lists of floats, keyed by header name."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in REQUIRED if c not in (reader.fieldnames or [])]
        if missing:
            raise ValueError(f"{path}: missing columns {missing} (header {reader.fieldnames})")
        cols = {c: [] for c in reader.fieldnames}
        for line, row in enumerate(reader, start=2):
            # a run killed mid-row may leave a partial last line: skip it with a note
            if any(row[c] in (None, "") for c in REQUIRED):
                sys.stderr.write(f"plot_history.py: {path}:{line}: incomplete row skipped\n")
                continue
            for c in reader.fieldnames:
                cols[c].append(float(row[c]))
    if not cols["time"]:
        raise ValueError(f"{path}: no data rows")
    return cols


def plot(cols, out_path, title):
    t = cols["time"]
    fig, (ax_e, ax_err) = plt.subplots(2, 1, sharex=True, figsize=(8, 7),
                                       gridspec_kw={"height_ratios": [3, 1.4]})
    for name in ENERGIES:
        style = {"color": "k", "linewidth": 2.0} if name == "total" else {"linewidth": 1.2}
        ax_e.plot(t, cols[name], label=name, **style)
    ax_e.set_ylabel("energy per unit thickness [J/m]")
    ax_e.grid(True, alpha=0.3)
    ax_e.legend(fontsize=8, ncol=2)
    ax_e.set_title(title)

    # relative measure: largest |error| over the largest magnitude of any energy term
    scale = max(max(abs(v) for v in cols[name]) for name in ENERGIES) or 1.0
    worst = max(abs(v) for v in cols["energy_error"])
    ax_err.plot(t, cols["energy_error"], color="tab:red")
    ax_err.axhline(0.0, color="k", linewidth=0.5)
    ax_err.set_ylabel("energy_error [J/m]")
    ax_err.set_xlabel("time [s]")
    ax_err.grid(True, alpha=0.3)
    ax_err.set_title(f"balance error: max |error| = {worst:.3e} J/m "
                     f"({100.0 * worst / scale:.3g} % of max energy {scale:.3e} J/m)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out_path, dpi=120)
    plt.close(fig)
    return worst, scale


def main(argv=None):
    ap = argparse.ArgumentParser(description="Plot fdem history.csv to energies.png")
    ap.add_argument("csv", help="history.csv written by fdem")
    ap.add_argument("--out", help="output PNG (default: energies.png next to the CSV)")
    ap.add_argument("--title", default=None, help="plot title (default: the CSV path)")
    ap.add_argument("--check", action="store_true", help="verify the PNG was written")
    args = ap.parse_args(argv)
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.csv)), "energies.png")
    try:
        cols = read_history(args.csv)
    except (OSError, ValueError) as exc:
        sys.stderr.write(f"plot_history.py: {exc}\n")
        return 1
    worst, scale = plot(cols, out, args.title or args.csv)
    if args.check:
        with open(out, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                sys.stderr.write(f"plot_history.py: {out} is not a PNG\n")
                return 1
    print(f"plot_history.py: wrote {out} ({len(cols['time'])} rows, "
          f"max |energy_error| {worst:.3e} J/m = {100.0 * worst / scale:.3g} % of {scale:.3e})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
