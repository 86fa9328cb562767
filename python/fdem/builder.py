"""ModelBuilder: a scenario built in Python.

The builder writes the same tables a TOML scenario has (docs/scenario.md: every keyword argument
is the key of that name, in SI units) and loads them through the scenario reader, so a model built
here is validated, defaulted and built exactly as the equivalent file would be: the same model
bits, the same error messages (``fdem.InputError`` names the line of ``builder.to_toml()``).
Meshes can be files (``.msh`` / ``.geo``, relative to ``base_dir``) or ``fdem.Mesh`` objects
(from NumPy arrays, ``Mesh.rectangle`` or ``Mesh.read``), which are handed over in memory.

    b = fdem.ModelBuilder()
    b.simulation(end_time=0.5, dt="auto", gravity=(0, -9.81))
    rock = b.material("rock", density=2700, youngs_modulus=30e9, poisson_ratio=0.25)
    b.body("base", mesh=fdem.Mesh.rectangle(0, 0, 1, 0.1, 40, 4), material=rock, fixed=True)
    b.body("block", mesh="block.msh", group="block", material=rock, velocity=(0, -1))
    b.contact("smooth", friction=0.3)
    sim = b.build()
"""
import math
import numbers

from . import _fdem


def _toml_value(v, where):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        x = float(v)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)  # shortest text that reads back as the same double
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    if hasattr(v, "tolist"):  # NumPy arrays and scalars
        return _toml_value(v.tolist(), where)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x, where) for x in v) + "]"
    raise TypeError(f"{where}: cannot write a value of type {type(v).__name__} ({v!r}) to TOML")


def _table(header, values):
    lines = [header]
    for k, v in values.items():
        if v is None:
            continue
        lines.append(f"{k} = {_toml_value(v, header + ' ' + k)}")
    return "\n".join(lines)


class ModelBuilder:
    """Build a scenario in Python; ``build()`` returns an ``fdem.Simulation``.

    Every method takes the keys of the scenario table of the same name (docs/scenario.md) as
    keyword arguments; the reader checks them as it checks a file.
    """

    def __init__(self, name="<ModelBuilder>", base_dir="."):
        """name appears in error messages; base_dir resolves relative mesh file paths."""
        self.name = name
        self.base_dir = base_dir
        self._tables = []  # (header, dict) in order
        self._single = {}  # header -> dict, for [simulation], [output], ...
        self._meshes = {}  # key -> fdem.Mesh
        self._mesh_keys = {}  # id(mesh) -> key

    def _set_single(self, header, values):
        if header in self._single:
            self._single[header].update(values)
        else:
            d = dict(values)
            self._single[header] = d
            self._tables.append((header, d))
        return self

    def simulation(self, end_time, dt="auto", **kw):
        """[simulation]: end_time [s], dt [s] or "auto", dt_fraction, gravity [m/s^2], max_steps."""
        return self._set_single("[simulation]", dict(end_time=end_time, dt=dt, **kw))

    def gravity(self, g):
        """Set [simulation] gravity = (gx, gy) [m/s^2]."""
        return self._set_single("[simulation]", dict(gravity=tuple(g)))

    def output(self, **kw):
        """[output]: interval [s], dir, vtu, bodies."""
        return self._set_single("[output]", kw)

    def checks(self, **kw):
        """[checks]: energy_tolerance, penetration."""
        return self._set_single("[checks]", kw)

    def damping(self, mass_proportional, until):
        """[damping]: mass-proportional damping c [1/s] while t < until [s]."""
        return self._set_single("[damping]", dict(mass_proportional=mass_proportional, until=until))

    def contact(self, algorithm="smooth", **kw):
        """[contact]: algorithm ("smooth", "legacy-triangle", "legacy-boundary", "none"), penalty
        [Pa], friction, damping [N s/m^2], ... (docs/scenario.md)."""
        return self._set_single("[contact]", dict(algorithm=algorithm, **kw))

    def contact_pair(self, materials, **kw):
        """[[contact.pair]]: parameters for a pair of materials."""
        self._tables.append(("[[contact.pair]]", dict(materials=list(materials), **kw)))
        return self

    def material(self, name, density, youngs_modulus, poisson_ratio, **kw):
        """[[material]]: density [kg/m^3], youngs_modulus [Pa], poisson_ratio, plane,
        viscosity [Pa s], damping_ratio. Returns the name (to pass to body())."""
        self._tables.append(("[[material]]", dict(name=name, density=density,
                                                  youngs_modulus=youngs_modulus,
                                                  poisson_ratio=poisson_ratio, **kw)))
        return name

    def _mesh_key(self, mesh):
        if isinstance(mesh, str):
            return mesh
        if not isinstance(mesh, _fdem.Mesh):
            raise TypeError(f"mesh must be a file path or an fdem.Mesh, got {type(mesh).__name__}")
        key = self._mesh_keys.get(id(mesh))
        if key is None:
            base = f"<mesh {mesh.file}>"
            key, n = base, 1
            while key in self._meshes:
                n += 1
                key = f"{base[:-1]} #{n}>"
            self._meshes[key] = mesh
            self._mesh_keys[id(mesh)] = key
        return key

    def body(self, name, mesh, material, **kw):
        """[[body]]: mesh (a .msh/.geo path or an fdem.Mesh), material, group, velocity [m/s],
        angular_velocity [rad/s], velocity_gradient [1/s], origin, piece_motion, fixed, pieces,
        element, mesh_size [m] (.geo)."""
        self._tables.append(("[[body]]", dict(name=name, mesh=self._mesh_key(mesh),
                                              material=material, **kw)))
        return name

    def boundary(self, body, group, **kw):
        """[[boundary]]: fix (["x", "y"]), velocity [m/s], components, start [s], end [s]."""
        self._tables.append(("[[boundary]]", dict(body=body, group=group, **kw)))
        return self

    def load(self, body, group, **kw):
        """[[load]]: traction [Pa], pressure [Pa] or force [N/m], time_function, ramp_time, table."""
        self._tables.append(("[[load]]", dict(body=body, group=group, **kw)))
        return self

    def kick(self, body, time, velocity, **kw):
        """[[kick]]: set the velocity [m/s] of a body entry at a time [s]."""
        self._tables.append(("[[kick]]", dict(body=body, time=time, velocity=velocity, **kw)))
        return self

    def probe(self, name, **kw):
        """[[probe]]: position [m], body, group."""
        self._tables.append(("[[probe]]", dict(name=name, **kw)))
        return self

    def to_toml(self):
        """The scenario as TOML text (what build() loads; line numbers of errors refer to it)."""
        return "\n\n".join(_table(h, v) for h, v in self._tables) + "\n"

    def build(self):
        """Load the scenario: an fdem.Simulation. Raises fdem.InputError as a file would."""
        return _fdem.Simulation.from_string(self.to_toml(), name=self.name,
                                            base_dir=self.base_dir, meshes=self._meshes)
