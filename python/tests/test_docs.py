"""help(fdem) is useful: every public class, function and property has a docstring beyond the
signature pybind11 generates."""
import inspect

import fdem
import fdem.plot


def own_doc(obj):
    doc = inspect.getdoc(obj) or ""
    # pybind11 puts "name(self: ...) -> ..." first; keep only what was written by hand
    lines = [ln for ln in doc.splitlines() if ln.strip() and "(self" not in ln
             and not ln.startswith(("Overloaded function", "1.", "2."))]
    return "\n".join(lines).strip()


def test_every_public_name_is_documented():
    missing = []
    assert len(own_doc(fdem)) > 200
    for cls in (fdem.Simulation, fdem.Model, fdem.State, fdem.Mesh, fdem.Support,
                fdem.ModelBuilder, fdem.EnergyRecorder, fdem.InputError, fdem.SimulationError):
        if not own_doc(cls):
            missing.append(cls.__name__)
        for name, member in vars(cls).items():
            if name.startswith("_"):
                continue
            if isinstance(member, property) or callable(member) or isinstance(member, staticmethod):
                target = member.__func__ if isinstance(member, staticmethod) else member
                if not own_doc(target):
                    missing.append(f"{cls.__name__}.{name}")
    for fn in (fdem.plot.tripcolor, fdem.plot.energy_history, fdem.plot.field_values,
               fdem.history.read_history):
        if not own_doc(fn):
            missing.append(fn.__name__)
    assert not missing, f"undocumented: {missing}"
