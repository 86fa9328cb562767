"""Energy histories: record them from a run's callback, or read a run's history.csv."""
import csv

import numpy as np


class EnergyRecorder:
    """A run() callback that records sim.energy (and the time) at every call.

        rec = fdem.EnergyRecorder()
        sim.run(until=1.0, callback=rec, every=100)
        h = rec.arrays()       # dict of NumPy arrays: time, kinetic, ..., total
    """

    def __init__(self):
        self.rows = []

    def __call__(self, sim):
        self.rows.append(sim.energy)
        return True

    def arrays(self):
        """dict name -> NumPy array of every recorded energy [J/m] and time [s]."""
        if not self.rows:
            return {}
        return {k: np.array([r[k] for r in self.rows]) for k in self.rows[0]}


def read_history(path):
    """history.csv of a run (docs/output.md) as a dict column name -> NumPy array."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], rows[1:]
    cols = {}
    for i, name in enumerate(header):
        try:
            cols[name] = np.array([float(r[i]) for r in data])
        except ValueError:
            cols[name] = np.array([r[i] for r in data])
    return cols
