"""Y8: fdem.plot draws a field on the deformed mesh and an energy history into PNG files."""
import matplotlib

matplotlib.use("Agg")

import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import fdem  # noqa: E402
import fdem.plot  # noqa: E402
from conftest import example  # noqa: E402


def png_ok(path):
    img = mpimg.imread(str(path))
    assert img.ndim == 3 and img.shape[0] > 100 and img.shape[1] > 100
    # not a blank canvas: several distinct colours
    assert len(np.unique(img.reshape(-1, img.shape[2])[:, :3], axis=0)) > 20


def test_tripcolor_and_energy_history(tmp_path):
    sim = fdem.Simulation.from_toml(example("03_contact_slide"))
    rec = fdem.EnergyRecorder()
    sim.run(steps=400, callback=rec, every=20)
    h = rec.arrays()
    assert len(h["time"]) == 20 and np.all(np.diff(h["time"]) > 0)
    fig, ax = fdem.plot.tripcolor(sim, field="von_mises")
    coll = ax.collections[0]
    np.testing.assert_array_equal(coll.get_array(), sim.von_mises())  # the plotted values
    fig.savefig(tmp_path / "vm.png", dpi=80)
    png_ok(tmp_path / "vm.png")
    ax2 = fdem.plot.energy_history(rec)
    ax2.figure.savefig(tmp_path / "energy.png", dpi=80)
    png_ok(tmp_path / "energy.png")
    labels = [t.get_text() for t in ax2.get_legend().get_texts()]
    assert "total (balance)" in labels and "kinetic" in labels


def test_history_csv_plot(tmp_path):
    sim = fdem.Simulation.from_toml(example("03_contact_slide"))
    sim.end_time = 200 * sim.dt
    sim.open_output(str(tmp_path / "out"))
    sim.run()
    h = fdem.history.read_history(str(tmp_path / "out" / "history.csv"))
    assert h["time"][-1] == pytest.approx(sim.time)
    ax = fdem.plot.energy_history(str(tmp_path / "out" / "history.csv"))
    ax.figure.savefig(tmp_path / "e.png", dpi=60)
    png_ok(tmp_path / "e.png")
    assert (tmp_path / "out" / "series.pvd").exists()


def test_unknown_field_is_an_error():
    sim = fdem.Simulation.from_toml(example("03_contact_slide"))
    with pytest.raises(ValueError, match="unknown field 'stres'"):
        fdem.plot.tripcolor(sim, field="stres")


def test_energy_history_of_a_fracturing_run(tmp_path):
    """Example 11: the joint energy and the fracture work are plotted, from the recorder and from
    history.csv (whose columns are energy.joint, energy.fracture)."""
    sim = fdem.Simulation.from_toml(example("11_impact_fragmentation"))
    sim.end_time = 4e-5
    sim.open_output(str(tmp_path / "out"))
    rec = fdem.EnergyRecorder()
    sim.run(callback=rec, every=200)
    for source in (rec, str(tmp_path / "out" / "history.csv")):
        ax = fdem.plot.energy_history(source)
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert "joint energy" in labels and "fracture work" in labels, labels
        ax.figure.savefig(tmp_path / "e.png", dpi=60)
        png_ok(tmp_path / "e.png")
